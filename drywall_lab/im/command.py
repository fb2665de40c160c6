"""The final command handed to robot control (the paper's Fig. 1, IM -> RC)."""
from __future__ import annotations

from dataclasses import dataclass

from drywall_lab.site import Placement, Pose, Site

#: The action history's nine fields, in the paper's order (spec section 4).
HISTORY_FIELDS = ("stud_id", "installed_x_left", "installed_x_right", "left_cent", "ver_hor", "top_btm",
                  "drywall_id", "w", "l")


@dataclass(frozen=True)
class RobotCommand:
    """Target panel, destination stud and placement, with the installed geometry and the poses.

    ``x_left``/``x_right``/``z_bottom``/``z_top`` are the area the panel covers on the
    wall (spec section 4); ``pick_pose`` is the panel's centre lying on top of its
    stack, ``place_pose`` its centre installed against the studs (``Site.pick_pose`` and
    ``Site.place_pose``). Lengths in metres.
    """

    drywall_id: str
    stud_id: str
    placement: Placement
    x_left: float
    x_right: float
    z_bottom: float
    z_top: float
    w: float
    l: float
    pick_pose: Pose
    place_pose: Pose

    @classmethod
    def build(cls, site: Site, drywall_id: str, stud_id: str, placement: Placement | str) -> "RobotCommand":
        """The command for ``drywall_id`` on ``stud_id``; does not check that it can be carried out."""
        panel, stud, placement = site.panel(drywall_id), site.stud(stud_id), Placement(placement)
        r = site.rect(panel, stud, placement)
        return cls(panel.drywall_id, stud.stud_id, placement, r.x_left, r.x_right, r.z_bottom, r.z_top,
                   panel.w, panel.l, site.pick_pose(panel), site.place_pose(panel, stud, placement))

    def as_contract(self) -> dict:
        """``{"drywall_id", "stud_id", "placement"}``: the ``run`` output's command (spec section 6)."""
        return {"drywall_id": self.drywall_id, "stud_id": self.stud_id, "placement": self.placement.value}

    def history_row(self) -> dict:
        """The action history row with the paper's nine fields (spec section 4)."""
        vertical = self.placement.vertical
        return {
            "stud_id": self.stud_id,
            "installed_x_left": self.x_left,
            "installed_x_right": self.x_right,
            "left_cent": "center" if self.placement is Placement.VERTICAL_MIDDLE else "left",
            "ver_hor": "vertical" if vertical else "horizontal",
            "top_btm": "" if vertical else ("top" if self.placement is Placement.HORIZONTAL_TOP else "bottom"),
            "drywall_id": self.drywall_id,
            "w": self.w,
            "l": self.l,
        }

    def __str__(self) -> str:
        return (f"panel {self.drywall_id} on stud {self.stud_id}, {self.placement.described}: "
                f"x {self.x_left:.4f}..{self.x_right:.4f} m, z {self.z_bottom:.4f}..{self.z_top:.4f} m")


def placement_of_row(row: dict) -> Placement:
    """The placement a history row's ``left_cent``/``ver_hor``/``top_btm`` describe."""
    ver_hor, left_cent, top_btm = str(row["ver_hor"]).strip(), str(row["left_cent"]).strip(), str(row["top_btm"]).strip()
    if ver_hor == "vertical" and left_cent in ("left", "center"):
        return Placement.VERTICAL_MIDDLE if left_cent == "center" else Placement.VERTICAL_LEFT
    if ver_hor == "horizontal" and top_btm in ("top", "bottom"):
        return Placement.HORIZONTAL_TOP if top_btm == "top" else Placement.HORIZONTAL_BOTTOM
    raise ValueError(
        f"ver_hor={ver_hor!r}, left_cent={left_cent!r}, top_btm={top_btm!r} is not a placement: expected "
        "vertical with left or center, or horizontal with top or bottom"
    )
