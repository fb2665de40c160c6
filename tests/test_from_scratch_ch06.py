"""Notebook 06's from-scratch exercise: where a panel covers the wall from its stud and placement
(``check_panel_rect``, the paper's Fig. 6).

The reference solution passes (it agrees with ``Site.rect`` on every panel, stud and placement), the notebook's
stub is "not attempted yet", the usual slips fail with a message that names them, and the committed notebook
holds the stub (not the solution) under a markdown cell that names the solution file.
"""
from __future__ import annotations

from pathlib import Path

import nbformat
import pytest

from drywall_lab.course.common import solution_file
from drywall_lab.course.solutions import ch06
from drywall_lab.rc.exercises import check_panel_rect
from drywall_lab.site import WALL_HEIGHT, Placement, Rect, default_site

ROOT = Path(__file__).resolve().parent.parent
NOTEBOOK = ROOT / "notebooks" / "06_end_to_end.ipynb"
MARKER = "# from scratch: your code here"


def _stub(panel, stud, placement):
    # from scratch: your code here
    raise NotImplementedError("your code here")


def _left(stud, placement):
    return stud.x_center if placement == Placement.VERTICAL_MIDDLE else stud.x_left_line


def middle_on_the_left_line(panel, stud, placement):
    x = stud.x_left_line
    return Rect(x, x + panel.w, 0.0, panel.l) if placement.vertical else ch06.panel_rect(panel, stud, placement)


def every_edge_on_the_centre_line(panel, stud, placement):
    right = ch06.panel_rect(panel, stud, placement)
    shift = stud.x_center - right.x_left
    return Rect(right.x_left + shift, right.x_right + shift, right.z_bottom, right.z_top)


def horizontal_sides_swapped(panel, stud, placement):
    if placement.vertical:
        return ch06.panel_rect(panel, stud, placement)
    x = _left(stud, placement)
    top = placement == Placement.HORIZONTAL_TOP
    return Rect(x, x + panel.w, WALL_HEIGHT - panel.l if top else 0.0, WALL_HEIGHT if top else panel.l)


def rows_swapped(panel, stud, placement):
    if placement.vertical:
        return ch06.panel_rect(panel, stud, placement)
    x = _left(stud, placement)
    if placement == Placement.HORIZONTAL_TOP:
        return Rect(x, x + panel.l, 0.0, panel.w)
    return Rect(x, x + panel.l, WALL_HEIGHT - panel.w, WALL_HEIGHT)


def top_row_from_the_floor(panel, stud, placement):
    right = ch06.panel_rect(panel, stud, placement)
    return Rect(right.x_left, right.x_right, panel.w, 2 * panel.w) if placement == Placement.HORIZONTAL_TOP else right


def test_the_solution_passes_on_every_case():
    check = check_panel_rect(ch06.panel_rect)
    assert check.passed and check.attempted, str(check)
    site = default_site()
    assert f"{len(site.panels) * len(site.studs) * len(Placement)} cases" in str(check)


def test_the_stub_is_not_attempted_and_names_the_solution_file():
    check = check_panel_rect(_stub)
    text = str(check)
    assert not check.passed and not check.attempted
    assert text.startswith("NOT ATTEMPTED YET:\n- fill in "), text
    assert solution_file(6) in text


@pytest.mark.parametrize("wrong, says", [
    (middle_on_the_left_line, "centre line (stud.x_center), not on its left line"),
    (every_edge_on_the_centre_line, "left line (stud.x_left_line), not on its centre line"),
    (horizontal_sides_swapped, "the two sides are swapped"),
    (rows_swapped, "the rows are swapped"),
    (top_row_from_the_floor, "z_bottom = WALL_HEIGHT - w"),
    (lambda panel, stud, placement: (0.0, 1.0, 0.0, 1.0), "must return a Rect"),
    (lambda panel, stud, placement: panel.w + "", "raised TypeError"),
])
def test_the_usual_slips_fail_with_a_message_that_names_them(wrong, says):
    check = check_panel_rect(wrong)
    assert check.attempted and not check.passed
    assert says in str(check), str(check)


def test_a_slip_that_only_shows_on_one_stud_is_found():
    """Right on the worked example, wrong on the last stud: the enumeration finds it and names the edges."""
    site = default_site()
    last = site.studs[-1].stud_id

    def off_at_the_end(panel, stud, placement):
        right = ch06.panel_rect(panel, stud, placement)
        return Rect(right.x_left, right.x_right + 0.01, right.z_bottom, right.z_top) if stud.stud_id == last else right

    check = check_panel_rect(off_at_the_end)
    assert not check.passed and f"stud {last}" in str(check) and "x_right" in str(check), str(check)


def _cells():
    return nbformat.read(NOTEBOOK, as_version=4).cells


def test_the_committed_notebook_holds_the_stub_under_a_cell_naming_the_solution():
    cells = _cells()
    found = [i for i, c in enumerate(cells) if c.cell_type == "code" and MARKER in c.source]
    assert len(found) == 1
    source = cells[found[0]].source
    assert 'raise NotImplementedError("your code here")' in source
    assert "x_left_line" not in source and "WALL_HEIGHT" not in source  # not the solution
    assert source.rstrip().endswith("check = check_panel_rect(panel_rect)\nprint(check)\n"
                                    "assert check.passed or not check.attempted")
    above = next(c for c in reversed(cells[:found[0]]) if c.cell_type == "markdown")
    assert f"`{solution_file(6)}`" in above.source and "try the exercise first" in above.source


def test_the_committed_stub_runs_and_says_not_attempted():
    source = next(c.source for c in _cells() if c.cell_type == "code" and MARKER in c.source)
    namespace = {"check_panel_rect": check_panel_rect, "Placement": Placement, "Rect": Rect}
    exec(compile(source, "notebook 06's from-scratch cell", "exec"), namespace)  # noqa: S102
    assert not namespace["check"].attempted
