"""Building component information: the stud wall and the drywall stacks.

This is the case study's site (the paper's Fig. 5 and the tables of its Fig. 9,
whose values the spec's section 1 fixes): 13 studs 16 in on centre and nine
drywall panels in three stacks of three. ``Site`` holds the fixed tables, loaded
from ``data/site/studs.csv`` and ``data/site/panels.csv``; ``SiteState`` is the
site at one moment (what is still stacked, what is on the wall) and tells what
changes when a panel is picked and installed.

Frame: x runs along the wall, left to right as the worker faces it; z is up; the
wall stands in the plane y = 0. Lengths are metres.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from enum import Enum
from functools import lru_cache
from pathlib import Path
from typing import Callable, Iterable, TypeVar

import pandas as pd

from drywall_lab.errors import Refusal

FOOT = 0.3048  #: metres per foot
WALL_HEIGHT = 2.4384  #: H, the studs' height (8 ft)
STUD_HALF_WIDTH = 0.01905  #: half of a stud's 1.5 in width
STACK_NAMES = ("left", "middle", "right")  #: stacks from left to right
TOLERANCE = 1e-6  #: metres; touching edges are not an overlap
#: Where the stacks lie, across the floor from the wall (y of their centre line). The spec
#: puts them "on the far side of the robot" without a number; 2.6 m leaves room for a robot
#: on a rail at y of about 1.1 m between the wall and the 2.44 m long sheets, which lie
#: with their length along y and their width along x.
STACK_Y = 2.6

DATA_DIR = Path(__file__).resolve().parent.parent / "data"
SIZE_WORDS_PATH = DATA_DIR / "site" / "size_words.csv"
SIZE_MEASURES = ("width", "length")


@lru_cache(maxsize=4)
def size_words(path: Path | str = SIZE_WORDS_PATH) -> dict[str, tuple[str, str]]:
    """Words that say a panel's size by a property, not a number (``data/site/size_words.csv``): word -> (measure,
    "least" or "most"). "narrow" is the least width, "short" the least length; which stack that is, the site's sizes
    decide (``Site.stacks_with_extreme``). "big" and "small" say no measure, and are not in it."""
    table = pd.read_csv(path, dtype=str)
    bad = table[~table["measure"].isin(SIZE_MEASURES) | ~table["extreme"].isin(("least", "most"))]
    if len(bad) or table["word"].duplicated().any():
        raise ValueError(f"{path}: each word once, measure one of {SIZE_MEASURES}, extreme least or most; "
                         f"check {bad.to_dict('records') or table[table['word'].duplicated()]['word'].tolist()}")
    return {r.word: (r.measure, r.extreme) for r in table.itertuples(index=False)}


class Placement(str, Enum):
    """How a panel goes on its stud (the paper's Fig. 6; spec section 4)."""

    VERTICAL_LEFT = "vertical_left"  # default: vertical, left edge on the stud's left line
    VERTICAL_MIDDLE = "vertical_middle"  # Vr_md: vertical, left edge on the stud's centre line
    HORIZONTAL_TOP = "horizontal_top"  # Hr_top: horizontal, top row
    HORIZONTAL_BOTTOM = "horizontal_bottom"  # Hr_btm: horizontal, bottom row

    @property
    def vertical(self) -> bool:
        return self in (Placement.VERTICAL_LEFT, Placement.VERTICAL_MIDDLE)

    @property
    def described(self) -> str:
        """In a worker's words: "vertically on the stud's centre line"."""
        return {
            "vertical_left": "vertically on the stud's left line",
            "vertical_middle": "vertically on the stud's centre line",
            "horizontal_top": "horizontally in the top row",
            "horizontal_bottom": "horizontally in the bottom row",
        }[self.value]


@dataclass(frozen=True)
class Stud:
    """One stud of the wall (spec section 1)."""

    stud_id: str
    index: int  # 0 = leftmost
    x_center: float
    width: float
    depth: float
    height: float

    @property
    def x_left_line(self) -> float:
        return self.x_center - self.width / 2

    @property
    def x_right_line(self) -> float:
        return self.x_center + self.width / 2


@dataclass(frozen=True)
class Panel:
    """One drywall panel: width ``w`` is the short side, length ``l`` the long side."""

    drywall_id: str
    stack: str
    stack_x: float
    level: int  # 0 = bottom of its stack
    size_name: str
    w_ft: float
    l_ft: float
    w: float
    l: float
    thickness: float

    @property
    def size_ft(self) -> tuple[float, float]:
        return (self.w_ft, self.l_ft)


@dataclass(frozen=True)
class Rect:
    """The area an installed panel covers on the wall: [x_left, x_right] x [z_bottom, z_top]."""

    x_left: float
    x_right: float
    z_bottom: float
    z_top: float

    def overlaps(self, other: "Rect") -> bool:
        """True when the two share positive area (touching edges do not count)."""
        return (
            min(self.x_right, other.x_right) - max(self.x_left, other.x_left) > TOLERANCE
            and min(self.z_top, other.z_top) - max(self.z_bottom, other.z_bottom) > TOLERANCE
        )


@dataclass(frozen=True)
class Pose:
    """Where a panel's centre is and how it is turned: quaternion (w, x, y, z), MuJoCo's order.

    The panel's own axes: x along its width, y through its thickness, z along its
    length. The identity is a panel standing upright against the wall.
    """

    position: tuple[float, float, float]
    quaternion: tuple[float, float, float, float]


_HALF = 0.5**0.5
UPRIGHT = (1.0, 0.0, 0.0, 0.0)  #: vertical placements: length up, width along the wall
ON_ITS_SIDE = (_HALF, 0.0, _HALF, 0.0)  #: horizontal placements: a quarter turn about y, length along the wall
LYING_FLAT = (_HALF, _HALF, 0.0, 0.0)  #: in a stack: a quarter turn about x, length along y, thickness up


_Item = TypeVar("_Item", Stud, Panel)


def _by_id(items: Iterable[_Item], id_field: str, wanted: str | int, unknown: Callable[[str], str]) -> _Item:
    """The item whose ``id_field`` is ``wanted`` (as a string, spaces stripped); a ``Refusal('unknown_id')`` saying
    ``unknown(key)`` for any other."""
    key = str(wanted).strip()
    for item in items:
        if getattr(item, id_field) == key:
            return item
    raise Refusal("unknown_id", unknown(key))


@dataclass(frozen=True)
class Site:
    """The fixed building component tables: studs and panels (the paper's Fig. 9)."""

    studs: tuple[Stud, ...]
    panels: tuple[Panel, ...]

    @classmethod
    def load(cls, data_dir: Path | str | None = None) -> "Site":
        """Read ``studs.csv`` and ``panels.csv`` from ``data_dir/site`` (default: the project's)."""
        site_dir = Path(data_dir) / "site" if data_dir is not None else DATA_DIR / "site"
        studs_df = pd.read_csv(site_dir / "studs.csv", dtype={"stud_id": str})
        panels_df = pd.read_csv(site_dir / "panels.csv", dtype={"drywall_id": str})
        studs = tuple(Stud(stud_id=r.stud_id, index=int(r.index), x_center=float(r.x_center_m), width=float(r.width_m),
                           depth=float(r.depth_m), height=float(r.height_m))
                      for r in studs_df.sort_values("index").itertuples(index=False))
        panels = tuple(Panel(drywall_id=r.drywall_id, stack=r.stack, stack_x=float(r.stack_x_m), level=int(r.level),
                             size_name=r.size_name, w_ft=float(r.w_ft), l_ft=float(r.l_ft), w=float(r.w_m),
                             l=float(r.l_m), thickness=float(r.thickness_m))
                       for r in panels_df.itertuples(index=False))
        return cls(studs=studs, panels=panels)

    # --- look-ups -----------------------------------------------------------------
    @property
    def stud_ids(self) -> list[str]:
        return [s.stud_id for s in self.studs]

    @property
    def panel_ids(self) -> list[str]:
        return [p.drywall_id for p in self.panels]

    def stud(self, stud_id: str | int) -> Stud:
        """The stud with this id; a ``Refusal('unknown_id')`` for any other."""
        return _by_id(self.studs, "stud_id", stud_id, lambda key: (
            f"There is no stud {key} on this wall; studs run from {self.studs[0].stud_id} to {self.studs[-1].stud_id}."))

    def panel(self, drywall_id: str | int) -> Panel:
        """The panel with this id; a ``Refusal('unknown_id')`` for any other."""
        return _by_id(self.panels, "drywall_id", drywall_id, lambda key: (
            f"There is no panel {key} on this site; the panels are {', '.join(sorted(self.panel_ids))}."))

    def stud_at(self, index: int) -> Stud:
        return self.studs[index]

    def stack(self, name: str) -> tuple[Panel, ...]:
        """The panels of one stack at the start, bottom to top."""
        return tuple(sorted((p for p in self.panels if p.stack == name), key=lambda p: p.level))

    @property
    def stacks(self) -> dict[str, tuple[str, ...]]:
        """Stack name -> panel ids, bottom to top, at the start."""
        return {name: tuple(p.drywall_id for p in self.stack(name)) for name in STACK_NAMES}

    def stack_size(self, name: str) -> tuple[float, float]:
        """(w, l) in feet of the panels in a stack."""
        return self.stack(name)[0].size_ft

    @property
    def sizes(self) -> dict[str, tuple[float, float]]:
        """Stack name -> (w, l) in feet."""
        return {name: self.stack_size(name) for name in STACK_NAMES}

    def stacks_with_extreme(self, measure: str, extreme: str) -> list[str]:
        """The stacks whose panels have the least or the most of a measure ("width" or "length"): what a size said by
        a property means ("the narrow one": the least width; ``size_words``). More than one stack when they share it
        ("the wide one" on this site: the 4 x 8 and the 4 x 6)."""
        amounts = {name: size[SIZE_MEASURES.index(measure)] for name, size in self.sizes.items()}
        best = (min if extreme == "least" else max)(amounts.values())
        return [name for name in STACK_NAMES if amounts[name] == best]

    @property
    def wall_end_x(self) -> float:
        """The right line of the last stud: no panel may reach past it."""
        return self.studs[-1].x_right_line

    def rect(self, panel: Panel | str, stud: Stud | str, placement: Placement | str) -> Rect:
        """Where ``panel`` would cover the wall when put on ``stud`` (spec section 4)."""
        panel = panel if isinstance(panel, Panel) else self.panel(panel)
        stud = stud if isinstance(stud, Stud) else self.stud(stud)
        placement = Placement(placement)
        x_left = stud.x_center if placement is Placement.VERTICAL_MIDDLE else stud.x_left_line
        if placement.vertical:
            return Rect(x_left, x_left + panel.w, 0.0, panel.l)
        if placement is Placement.HORIZONTAL_TOP:
            return Rect(x_left, x_left + panel.l, WALL_HEIGHT - panel.w, WALL_HEIGHT)
        return Rect(x_left, x_left + panel.l, 0.0, panel.w)

    @property
    def wall_face_y(self) -> float:
        """The y of the studs' face that panels are fixed to (the side the robot works from)."""
        return self.studs[0].depth / 2

    def pick_pose(self, panel: Panel | str) -> Pose:
        """The centre of ``panel`` lying in its stack (it is on top when it is picked)."""
        panel = panel if isinstance(panel, Panel) else self.panel(panel)
        z = (panel.level + 0.5) * panel.thickness
        return Pose((panel.stack_x, STACK_Y, z), LYING_FLAT)

    def place_pose(self, panel: Panel | str, stud: Stud | str, placement: Placement | str) -> Pose:
        """The centre of ``panel`` installed on ``stud``: against the studs' face, over ``rect()``."""
        panel = panel if isinstance(panel, Panel) else self.panel(panel)
        r = self.rect(panel, stud, placement)
        y = self.wall_face_y + panel.thickness / 2
        turn = UPRIGHT if Placement(placement).vertical else ON_ITS_SIDE
        return Pose(((r.x_left + r.x_right) / 2, y, (r.z_bottom + r.z_top) / 2), turn)

    def fresh(self) -> "SiteState":
        """The site before anything is installed."""
        return SiteState(self, {k: tuple(v) for k, v in self.stacks.items()}, ())


@dataclass(frozen=True)
class Installed:
    """One panel on the wall."""

    drywall_id: str
    stud_id: str
    placement: Placement
    rect: Rect


@dataclass(frozen=True)
class SiteState:
    """The site at one moment: the stacks as they are now, and the installed panels.

    States are immutable: ``pick`` and ``install`` return a new state, so a refused
    instruction cannot leave the site half changed.
    """

    site: Site
    stacks: dict[str, tuple[str, ...]]
    installed: tuple[Installed, ...] = field(default=())

    def top(self, stack: str) -> str | None:
        """The id of the panel on top of ``stack``, or None when it is empty."""
        ids = self.stacks[stack]
        return ids[-1] if ids else None

    @property
    def tops(self) -> dict[str, str | None]:
        return {name: self.top(name) for name in STACK_NAMES}

    def is_installed(self, drywall_id: str) -> bool:
        return any(i.drywall_id == drywall_id for i in self.installed)

    def check_pickable(self, drywall_id: str) -> Panel:
        """The panel, if the robot can pick it now; otherwise the refusal that says why."""
        panel = self.site.panel(drywall_id)
        if self.is_installed(panel.drywall_id):
            raise Refusal("already_installed", f"Panel {panel.drywall_id} is already installed on the wall.")
        ids = self.stacks[panel.stack]
        if panel.drywall_id not in ids:
            raise Refusal(
                "already_installed",
                f"Panel {panel.drywall_id} has already been taken off the {panel.stack} stack.",
            )
        if ids[-1] != panel.drywall_id:
            above = ids[ids.index(panel.drywall_id) + 1 :]
            raise Refusal(
                "not_on_top",
                f"Panel {panel.drywall_id} is under {' and '.join(above)} in the {panel.stack} stack; "
                f"only the top panel, {ids[-1]}, can be picked.",
            )
        return panel

    def pick(self, drywall_id: str) -> "SiteState":
        """The state after the robot lifts ``drywall_id`` off its stack."""
        panel = self.check_pickable(drywall_id)
        stacks = dict(self.stacks)
        stacks[panel.stack] = stacks[panel.stack][:-1]
        return replace(self, stacks=stacks)

    def check_fits(self, drywall_id: str, stud_id: str, placement: Placement | str) -> Rect:
        """The area the panel would cover; a refusal if it passes the wall's end or overlaps."""
        panel = self.site.panel(drywall_id)
        stud = self.site.stud(stud_id)
        placement = Placement(placement)
        rect = self.site.rect(panel, stud, placement)
        if rect.x_right > self.site.wall_end_x + TOLERANCE:
            raise Refusal(
                "past_wall_end",
                f"Panel {panel.drywall_id} on stud {stud.stud_id}, {placement.described}, would end at "
                f"x = {rect.x_right:.3f} m, past the wall's last stud ({self.site.wall_end_x:.3f} m).",
            )
        for other in self.installed:
            if rect.overlaps(other.rect):
                raise Refusal(
                    "overlap",
                    f"Panel {panel.drywall_id} on stud {stud.stud_id}, {placement.described}, would overlap "
                    f"panel {other.drywall_id}, already installed on stud {other.stud_id}.",
                )
        return rect

    def install(self, drywall_id: str, stud_id: str, placement: Placement | str) -> "SiteState":
        """The state after picking ``drywall_id`` and installing it; a ``Refusal`` leaves ``self`` as it was.

        Whether the panel can be picked is checked first, so that a panel already on
        the wall is refused as ``already_installed``, not as overlapping itself.
        """
        picked = self.pick(drywall_id)
        rect = self.check_fits(drywall_id, stud_id, placement)
        panel, stud = self.site.panel(drywall_id), self.site.stud(stud_id)
        return replace(
            picked,
            installed=self.installed + (Installed(panel.drywall_id, stud.stud_id, Placement(placement), rect),),
        )

    def replay(self, commands: Iterable[dict]) -> "SiteState":
        """Apply accepted commands ``{"drywall_id", "stud_id", "placement"}`` in order."""
        state = self
        for c in commands:
            state = state.install(c["drywall_id"], c["stud_id"], c["placement"])
        return state


@lru_cache(maxsize=1)
def default_site() -> Site:
    """The project's site, loaded once."""
    return Site.load()
