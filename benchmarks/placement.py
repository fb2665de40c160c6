"""Placement benchmark: every placement of the paper's three layouts, then random feasible commands.

Usage (from the repository root, in the project's virtualenv):

    python benchmarks/placement.py                     # the layouts and 30+ random commands
    python benchmarks/placement.py --record benchmarks/results/placement.md

Each layout starts from the fresh site and is built step by step as in Figs. 16-18 (the refused
instruction of layout 3 is not a command, so it is not here). The random commands come in
episodes: each starts from the fresh site and carries out 1 to 5 commands drawn (fixed seed)
from ``feasible_commands`` of the site as the robot has left it, so later ones go onto partly
built walls. Every placement is simulated in full and measured on the simulated panel.

Prints one line per placement, the figures, and last the one-line summary
``success_rate=... max_pos_err_mm=... max_ang_err_deg=... realtime_factor=...``
(simulated seconds per wall-clock second, planning included).
"""
from __future__ import annotations

import argparse
import datetime as dt
import os
import platform
import random
import sys
import time
from pathlib import Path

import mujoco
import pandas as pd

from drywall_lab.corpus.generator import feasible_commands
from drywall_lab.im import RobotCommand
from drywall_lab.pipeline import paper_layouts
from drywall_lab.rc import ANGLE_TOLERANCE_DEG, POSITION_TOLERANCE, PlacementResult, RobotCell
from drywall_lab.site import default_site

SEED = 20240517


def layout_placements(log) -> list[dict]:
    site = default_site()
    rows = []
    for layout in paper_layouts():
        cell = RobotCell()
        for expected in layout["expected"]:
            if "refusal" in expected:
                continue
            result = cell.execute(RobotCommand.build(site, expected["drywall_id"], expected["stud_id"],
                                                     expected["placement"]))
            rows.append(row(f"{layout['id']}", len(cell.state.installed) - 1, result, log))
    return rows


def random_placements(n: int, seed: int, log) -> list[dict]:
    site = default_site()
    rng = random.Random(seed)
    rows, episode = [], 0
    while len(rows) < n:
        cell = RobotCell()
        for _ in range(rng.randint(1, 5)):
            options = feasible_commands(cell.state)
            if not options:
                break
            drywall_id, stud_id, placement = rng.choice(options)
            result = cell.execute(RobotCommand.build(site, drywall_id, stud_id, placement))
            rows.append(row(f"random{episode}", len(cell.state.installed) - 1, result, log))
        episode += 1
    return rows


def row(group: str, installed_before: int, result: PlacementResult, log) -> dict:
    r = {"group": group, "installed_before": installed_before, **result.summary()}
    contacts = "; ".join(str(c) for c in result.unexpected_contacts)
    log(f"{group:<9} on a wall of {installed_before}: {result}" + (f" [{contacts}]" if contacts else ""))
    return r


def machine() -> dict:
    cpu = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    load = os.getloadavg() if hasattr(os, "getloadavg") else (float("nan"),) * 3
    return {"cpu": cpu, "cores": os.cpu_count(), "python": platform.python_version(), "mujoco": mujoco.__version__,
            "platform": platform.platform(), "load average (1, 5, 15 min)": ", ".join(f"{x:.2f}" for x in load)}


def summarise(frame: pd.DataFrame) -> dict:
    return {
        "placements": len(frame),
        "success_rate": frame["success"].mean(),
        "max_pos_err_mm": frame["pos_err_mm"].max(),
        "max_ang_err_deg": frame["ang_err_deg"].max(),
        "realtime_factor": frame["sim_s"].sum() / frame["wall_s"].sum(),
        "unexpected_contacts": int(frame["unexpected_contacts"].sum()),
        "base_moves": int(frame["base_moves"].sum()),
        "sim_s": frame["sim_s"].sum(),
        "wall_s": frame["wall_s"].sum(),
    }


def summary_line(s: dict) -> str:
    return (f"success_rate={s['success_rate']:.3f} max_pos_err_mm={s['max_pos_err_mm']:.3f} "
            f"max_ang_err_deg={s['max_ang_err_deg']:.4f} realtime_factor={s['realtime_factor']:.1f}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--random", type=int, default=30, help="at least this many random commands (default 30)")
    parser.add_argument("--seed", type=int, default=SEED)
    parser.add_argument("--record", type=Path, help="also write the results as Markdown to this file")
    args = parser.parse_args(argv)

    lines: list[str] = []

    def log(text: str) -> None:
        print(text, flush=True)
        lines.append(text)

    started = time.perf_counter()
    layouts = pd.DataFrame(layout_placements(log))
    randoms = pd.DataFrame(random_placements(args.random, args.seed, log))
    total_wall = time.perf_counter() - started
    everything = pd.concat([layouts, randoms], ignore_index=True)
    figures = pd.DataFrame({"the paper's layouts": summarise(layouts), "random commands": summarise(randoms),
                            "all": summarise(everything)})
    print()
    print(figures.to_string(float_format=lambda x: f"{x:.4g}"))
    print(f"tolerances: {POSITION_TOLERANCE * 1000:g} mm, {ANGLE_TOLERANCE_DEG:g} deg; "
          f"script wall time {total_wall:.1f} s")
    line = summary_line(summarise(everything))
    print(line)
    if args.record:
        write_record(args.record, everything, figures, line, total_wall, argv)
    return 0 if everything["success"].all() else 1


def write_record(path: Path, frame: pd.DataFrame, figures: pd.DataFrame, line: str, total_wall: float,
                 argv: list[str] | None) -> None:
    command = "python benchmarks/placement.py " + " ".join(sys.argv[1:] if argv is None else argv)
    info = machine()
    text = [
        "# Placement benchmark: results",
        "",
        f"Recorded {dt.datetime.now().strftime('%Y-%m-%d %H:%M')} with `{command.strip()}` "
        "(repository root, the project's `.venv`).",
        "",
        "## Machine",
        "",
        *[f"- {k}: {v}" for k, v in info.items()],
        "",
        "The machine was shared with other jobs while this ran (see the load average), so the wall",
        "times and the real-time factor are on the low side of what it does alone.",
        "",
        "## Summary",
        "",
        "```",
        line,
        "```",
        "",
        "```",
        figures.to_string(float_format=lambda x: f"{x:.4g}"),
        "```",
        "",
        f"Script wall time {total_wall:.1f} s (scene building included). Tolerances: "
        f"{POSITION_TOLERANCE * 1000:g} mm and {ANGLE_TOLERANCE_DEG:g} deg. Errors are measured on the simulated",
        "panel after the robot has let go and stepped back; `realtime_factor` is simulated seconds per wall-clock",
        "second over all placements, motion planning included.",
        "",
        "## Every placement",
        "",
        "```",
        frame.to_string(index=False),
        "```",
        "",
    ]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(text), encoding="utf-8")
    print(f"recorded in {path}")


if __name__ == "__main__":
    sys.exit(main())
