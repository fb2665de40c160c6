"""Matplotlib drawings for the notebooks: the site and the corpus statistics."""
from __future__ import annotations

from typing import Mapping

import matplotlib.pyplot as plt
import pandas as pd
from matplotlib.patches import Rectangle
from matplotlib.ticker import MaxNLocator

from drywall_lab.site import STACK_NAMES, WALL_HEIGHT, SiteState

STACK_COLOURS = {"left": "#f4d03f", "middle": "#85c1e9", "right": "#f1948a"}


def draw_wall(state: SiteState, ax: plt.Axes | None = None, title: str | None = None) -> plt.Axes:
    """Elevation of the stud wall as the worker faces it, with the installed panels (the paper's Fig. 5(b))."""
    ax = ax or plt.subplots(figsize=(10, 4))[1]
    site = state.site
    for stud in site.studs:
        ax.add_patch(Rectangle((stud.x_left_line, 0), stud.width, stud.height, color="#8d6e63"))
        ax.text(stud.x_center, -0.12, stud.stud_id[-3:], ha="center", va="top", fontsize=7)
    for item in state.installed:
        panel = site.panel(item.drywall_id)
        r = item.rect
        ax.add_patch(Rectangle((r.x_left, r.z_bottom), r.x_right - r.x_left, r.z_top - r.z_bottom,
                               facecolor=STACK_COLOURS[panel.stack], edgecolor="k", alpha=0.75))
        ax.text((r.x_left + r.x_right) / 2, (r.z_bottom + r.z_top) / 2,
                f"{item.drywall_id}\n{item.placement.value.replace('_', ' ')}", ha="center", va="center", fontsize=7)
    ax.set_xlim(-0.3, site.wall_end_x + 0.3)
    ax.set_ylim(-0.35, WALL_HEIGHT + 0.2)
    ax.set_aspect("equal")
    ax.set_xlabel("x along the wall (m); stud ids 500xxx")
    ax.set_ylabel("z (m)")
    ax.set_title(title or "Stud wall (elevation)")
    return ax


def draw_stacks(state: SiteState, ax: plt.Axes | None = None) -> plt.Axes:
    """The three panel stacks on the floor, seen from the wall, top panel last (the paper's Fig. 5(c))."""
    ax = ax or plt.subplots(figsize=(10, 2.2))[1]
    site = state.site
    for name in STACK_NAMES:
        stack = site.stack(name)
        remaining = state.stacks[name]
        for level, panel in enumerate(stack):
            on_stack = panel.drywall_id in remaining
            x0 = panel.stack_x - panel.w / 2  # panels lie with their width along the wall
            ax.add_patch(Rectangle((x0, level * 0.12), panel.w, 0.1, facecolor=STACK_COLOURS[name] if on_stack else "none",
                                   edgecolor="k", linestyle="-" if on_stack else ":"))
            label = panel.drywall_id + ("" if on_stack else " (picked)")
            ax.text(panel.stack_x, level * 0.12 + 0.05, label, ha="center", va="center", fontsize=7)
        w_ft, l_ft = site.stack_size(name)
        ax.text(stack[0].stack_x, -0.08, f"{name} stack: {w_ft:g} x {l_ft:g} ft", ha="center", va="top", fontsize=8)
    ax.set_xlim(-0.5, 5.3)
    ax.set_ylim(-0.3, 0.45)
    ax.set_yticks([])
    ax.set_xlabel("x (m)")
    ax.set_title("Panel stacks on the floor (bottom to top)")
    return ax


def plot_tag_shares(table: pd.DataFrame, ax: plt.Axes | None = None) -> plt.Axes:
    """Bar chart of each tag's share of words, ours against the paper's Table 2 (O left out)."""
    ax = ax or plt.subplots(figsize=(9, 3.5))[1]
    t = table.drop(index="O")
    t[["share_%", "paper_share_%"]].rename(columns={"share_%": "this corpus", "paper_share_%": "paper (Table 2)"}).plot.bar(ax=ax)
    ax.set_ylabel("% of all words")
    ax.set_title("Words per tag: generated corpus against the paper")
    return ax


def draw_wall_steps(states: list[SiteState], titles: list[str], ncols: int = 2, width: float = 13.0) -> plt.Figure:
    """One elevation per state, in a grid: how the wall grows step by step (the paper's Figs. 16-18)."""
    nrows = max(1, -(-len(states) // ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=(width, 2.9 * nrows), squeeze=False)
    for ax, state, title in zip(axes.flat, states, titles):
        draw_wall(state, ax, title)
        ax.set_xlabel("")
    for ax in list(axes.flat)[len(states):]:
        ax.axis("off")
    fig.tight_layout()
    return fig


def plot_training_curves(histories: Mapping[str, pd.DataFrame], column: str = "train_acc_word",
                         ax: plt.Axes | None = None, title: str | None = None) -> plt.Axes:
    """One line per model of a ``Tagger.history`` column against the epoch (the paper's Fig. 13)."""
    ax = ax or plt.subplots(figsize=(6, 3.5))[1]
    for name, history in histories.items():
        if column not in history:
            raise KeyError(f"history {name!r} has no column {column!r}; it has {', '.join(history.columns)}")
        ax.plot(history["epoch"], history[column], marker="o", markersize=3, label=name)
    ax.set_xlabel("epoch")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_ylabel(column)
    ax.set_title(title or column)
    ax.grid(alpha=0.3)
    ax.legend()
    return ax
