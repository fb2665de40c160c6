"""The site tables and the site state, checked against the spec's sections 1, 4 and 5.

Every expected number is computed here from the spec's formulas, not copied from
the data files, so a typo in ``data/site/*.csv`` shows up as a failing test.
"""
from __future__ import annotations

import csv
import shutil
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from drywall_lab.errors import Refusal
from drywall_lab.site import (
    DATA_DIR,
    FOOT,
    STACK_NAMES,
    WALL_HEIGHT,
    Placement,
    Rect,
    Site,
    SiteState,
    default_site,
)

INCH = 0.0254
H = 2.4384
N_STUDS = 13
STUD_SPACING = 0.4064  # 16 in on centre
STUD_WIDTH, STUD_DEPTH, STUD_HEIGHT = 0.0381, 0.0889, 2.4384
HALF = 0.01905
THICKNESS = 0.0127
WALL_END = 4.8768 + 0.01905

#: The spec's panel table: stack -> (stack centre x, size name, w ft, l ft).
STACKS = {
    "left": (0.9, "standard", 4, 8),
    "middle": (2.4, "unique_a", 2, 8),
    "right": (3.9, "unique_b", 4, 6),
}
STACK_IDS = {
    "left": ("500300", "500310", "500320"),
    "middle": ("500301", "500311", "500321"),
    "right": ("500302", "500312", "500322"),
}


def approx(x: float) -> object:
    return pytest.approx(x, abs=1e-9)


def corners(rect: Rect) -> tuple[float, float, float, float]:
    return (rect.x_left, rect.x_right, rect.z_bottom, rect.z_top)


def read_rows(name: str) -> list[dict[str, str]]:
    with open(DATA_DIR / "site" / name, newline="") as f:
        return list(csv.DictReader(f))


@pytest.fixture(scope="module")
def site() -> Site:
    return Site.load()


@pytest.fixture
def fresh(site: Site) -> SiteState:
    return site.fresh()


# --- constants -----------------------------------------------------------------------


def test_module_constants_match_the_spec(site: Site) -> None:
    assert FOOT == 0.3048
    assert WALL_HEIGHT == approx(H) and WALL_HEIGHT == approx(8 * FOOT)
    assert STACK_NAMES == ("left", "middle", "right")
    assert site.wall_end_x == approx(WALL_END)


# --- data/site/studs.csv -------------------------------------------------------------


def test_studs_csv_every_value() -> None:
    rows = read_rows("studs.csv")
    assert list(rows[0]) == [
        "stud_id", "index", "x_center_m", "x_left_line_m", "x_right_line_m",
        "width_in", "depth_in", "height_ft", "width_m", "depth_m", "height_m",
    ]
    assert len(rows) == N_STUDS
    for i, row in enumerate(rows):
        centre = STUD_SPACING * i
        assert row["stud_id"] == str(500100 + i)
        assert int(row["index"]) == i
        assert float(row["x_center_m"]) == approx(centre)
        assert float(row["x_left_line_m"]) == approx(centre - HALF)
        assert float(row["x_right_line_m"]) == approx(centre + HALF)
        assert float(row["width_in"]) == 1.5
        assert float(row["depth_in"]) == 3.5
        assert float(row["height_ft"]) == 8
        assert float(row["width_m"]) == approx(STUD_WIDTH) == approx(1.5 * INCH)
        assert float(row["depth_m"]) == approx(STUD_DEPTH) == approx(3.5 * INCH)
        assert float(row["height_m"]) == approx(STUD_HEIGHT) == approx(8 * FOOT)


def test_loaded_studs(site: Site) -> None:
    assert site.stud_ids == [str(500100 + i) for i in range(N_STUDS)]
    for i, stud in enumerate(site.studs):
        centre = STUD_SPACING * i
        assert stud.index == i
        assert site.stud_at(i) is stud
        assert stud.x_center == approx(centre)
        assert stud.width == approx(STUD_WIDTH)
        assert stud.depth == approx(STUD_DEPTH)
        assert stud.height == approx(STUD_HEIGHT)
        assert stud.x_left_line == approx(centre - HALF)
        assert stud.x_right_line == approx(centre + HALF)


# --- data/site/panels.csv ------------------------------------------------------------


def expected_panels() -> list[dict[str, object]]:
    """The spec's table, one dict per panel, ids bottom -> top."""
    out = []
    for stack_index, (stack, (x, size_name, w_ft, l_ft)) in enumerate(STACKS.items()):
        for level in range(3):
            out.append(
                dict(
                    drywall_id=str(500300 + 10 * level + stack_index),
                    stack=stack, stack_x=x, level=level, size_name=size_name,
                    w_ft=w_ft, l_ft=l_ft, w=w_ft * FOOT, l=l_ft * FOOT,
                )
            )
    return out


def test_expected_ids_follow_the_spec_table() -> None:
    by_stack: dict[str, list[str]] = {}
    for p in expected_panels():
        by_stack.setdefault(p["stack"], []).append(p["drywall_id"])
    assert {k: tuple(v) for k, v in by_stack.items()} == STACK_IDS


def test_panels_csv_every_value() -> None:
    rows = read_rows("panels.csv")
    assert list(rows[0]) == [
        "drywall_id", "stack", "stack_x_m", "level", "size_name",
        "w_ft", "l_ft", "w_m", "l_m", "thickness_in", "thickness_m",
    ]
    expected = {p["drywall_id"]: p for p in expected_panels()}
    assert sorted(r["drywall_id"] for r in rows) == sorted(expected)
    for row in rows:
        e = expected[row["drywall_id"]]
        assert row["stack"] == e["stack"]
        assert float(row["stack_x_m"]) == approx(e["stack_x"])
        assert int(row["level"]) == e["level"]
        assert row["size_name"] == e["size_name"]
        assert float(row["w_ft"]) == e["w_ft"]
        assert float(row["l_ft"]) == e["l_ft"]
        assert float(row["w_m"]) == approx(e["w"])
        assert float(row["l_m"]) == approx(e["l"])
        assert float(row["thickness_in"]) == 0.5
        assert float(row["thickness_m"]) == approx(THICKNESS) == approx(0.5 * INCH)


def test_loaded_panels(site: Site) -> None:
    expected = {p["drywall_id"]: p for p in expected_panels()}
    assert sorted(site.panel_ids) == sorted(expected)
    for panel in site.panels:
        e = expected[panel.drywall_id]
        assert panel.stack == e["stack"]
        assert panel.stack_x == approx(e["stack_x"])
        assert panel.level == e["level"]
        assert panel.size_name == e["size_name"]
        assert panel.size_ft == (e["w_ft"], e["l_ft"])
        assert panel.w == approx(e["w"])
        assert panel.l == approx(e["l"])
        assert panel.w <= panel.l  # w is the short side
        assert panel.thickness == approx(THICKNESS)


def test_stacks_and_sizes(site: Site) -> None:
    assert site.stacks == STACK_IDS
    assert list(site.stacks) == list(STACK_NAMES)
    assert site.sizes == {"left": (4, 8), "middle": (2, 8), "right": (4, 6)}
    for name in STACK_NAMES:
        assert [p.level for p in site.stack(name)] == [0, 1, 2]


def test_load_from_another_directory(tmp_path: Path) -> None:
    shutil.copytree(DATA_DIR / "site", tmp_path / "site")
    assert Site.load(tmp_path) == Site.load() == default_site()


# --- look-ups and unknown ids ----------------------------------------------------------


def test_lookups_accept_ints_and_spaces(site: Site) -> None:
    assert site.panel(500320).drywall_id == "500320"
    assert site.stud(" 500106 ").index == 6


@pytest.mark.parametrize("bad", ["500330", "500303", "123", "", "panel"])
def test_unknown_panel_id(site: Site, fresh: SiteState, bad: str) -> None:
    with pytest.raises(Refusal) as e:
        site.panel(bad)
    assert e.value.reason == "unknown_id"
    with pytest.raises(Refusal) as e:
        fresh.check_pickable(bad)
    assert e.value.reason == "unknown_id"
    with pytest.raises(Refusal) as e:
        fresh.install(bad, "500100", "vertical_left")
    assert e.value.reason == "unknown_id"


@pytest.mark.parametrize("bad", ["500113", "500099", "500300", "stud"])
def test_unknown_stud_id(site: Site, fresh: SiteState, bad: str) -> None:
    with pytest.raises(Refusal) as e:
        site.stud(bad)
    assert e.value.reason == "unknown_id"
    assert "500100" in str(e.value) and "500112" in str(e.value)
    with pytest.raises(Refusal) as e:
        fresh.install("500320", bad, "vertical_left")
    assert e.value.reason == "unknown_id"


# --- stacks, tops, picking -------------------------------------------------------------


def test_fresh_tops(fresh: SiteState) -> None:
    assert fresh.tops == {"left": "500320", "middle": "500321", "right": "500322"}
    assert fresh.top("middle") == "500321"
    assert fresh.installed == ()


def test_pick_takes_the_top_and_leaves_the_old_state_alone(site: Site, fresh: SiteState) -> None:
    after = fresh.pick("500320")
    assert after.stacks["left"] == ("500300", "500310")
    assert after.top("left") == "500310"
    assert after.stacks["middle"] == STACK_IDS["middle"]
    # the original state and the site's tables did not change
    assert fresh.stacks == STACK_IDS
    assert fresh.top("left") == "500320"
    assert site.stacks == STACK_IDS


def test_emptied_stack_has_no_top(fresh: SiteState) -> None:
    state = fresh.pick("500321").pick("500311").pick("500301")
    assert state.stacks["middle"] == ()
    assert state.top("middle") is None
    assert state.tops == {"left": "500320", "middle": None, "right": "500322"}


def test_not_on_top(fresh: SiteState) -> None:
    with pytest.raises(Refusal) as e:
        fresh.check_pickable("500300")
    assert e.value.reason == "not_on_top"
    assert str(e.value).startswith("Panel 500300 is under 500310 and 500320 in the left stack")
    assert "500320" in str(e.value)

    with pytest.raises(Refusal) as e:
        fresh.pick("500300")  # pick refuses too
    assert e.value.reason == "not_on_top"

    with pytest.raises(Refusal) as e:
        fresh.pick("500320").check_pickable("500300")
    assert str(e.value).startswith("Panel 500300 is under 500310 in the left stack")


def test_already_installed(fresh: SiteState) -> None:
    state = fresh.install("500320", "500100", "vertical_left")
    with pytest.raises(Refusal) as e:
        state.check_pickable("500320")
    assert e.value.reason == "already_installed"
    # installing it again, even where it would overlap itself, says it is installed
    for stud in ("500100", "500106"):
        with pytest.raises(Refusal) as e:
            state.install("500320", stud, "vertical_left")
        assert e.value.reason == "already_installed"


def test_picked_panel_cannot_be_picked_again(fresh: SiteState) -> None:
    state = fresh.pick("500320")
    with pytest.raises(Refusal) as e:
        state.check_pickable("500320")
    assert e.value.reason == "already_installed"


# --- geometry (spec section 4) ---------------------------------------------------------


def test_rect_example_500320_on_500100(site: Site) -> None:
    w, l = 4 * FOOT, 8 * FOOT
    assert corners(site.rect("500320", "500100", "vertical_left")) == approx((-HALF, 1.20015, 0, H))
    assert corners(site.rect("500320", "500100", "vertical_middle")) == approx((0, w, 0, l))
    assert corners(site.rect("500320", "500100", "horizontal_top")) == approx((-HALF, l - HALF, H - w, H))
    assert corners(site.rect("500320", "500100", "horizontal_bottom")) == approx((-HALF, l - HALF, 0, w))


@pytest.mark.parametrize("placement", list(Placement))
@pytest.mark.parametrize("panel_id", [p["drywall_id"] for p in expected_panels()])
def test_rect_for_every_panel_and_stud(site: Site, panel_id: str, placement: Placement) -> None:
    e = next(p for p in expected_panels() if p["drywall_id"] == panel_id)
    w, l = e["w"], e["l"]
    for i in range(N_STUDS):
        centre = STUD_SPACING * i
        x_left = centre if placement is Placement.VERTICAL_MIDDLE else centre - HALF
        extent, (z0, z1) = {
            Placement.VERTICAL_LEFT: (w, (0, l)),
            Placement.VERTICAL_MIDDLE: (w, (0, l)),
            Placement.HORIZONTAL_TOP: (l, (H - w, H)),
            Placement.HORIZONTAL_BOTTOM: (l, (0, w)),
        }[placement]
        rect = site.rect(panel_id, str(500100 + i), placement.value)
        assert corners(rect) == approx((x_left, x_left + extent, z0, z1))


def test_placement_values() -> None:
    assert [p.value for p in Placement] == ["vertical_left", "vertical_middle", "horizontal_top", "horizontal_bottom"]
    assert [p.vertical for p in Placement] == [True, True, False, False]


def test_rect_overlaps() -> None:
    a = Rect(0, 1, 0, 1)
    assert a.overlaps(Rect(0.5, 1.5, 0.5, 1.5))
    assert not a.overlaps(Rect(1, 2, 0, 1))  # touching side
    assert not a.overlaps(Rect(0, 1, 1, 2))  # touching top
    assert not a.overlaps(Rect(2, 3, 0, 1))
    assert a.overlaps(Rect(0.2, 0.8, 0.2, 0.8))  # inside


# --- check_fits --------------------------------------------------------------------------


def test_past_wall_end(fresh: SiteState) -> None:
    # 500320 vertical_left: x_right = 0.4064 i - 0.01905 + 1.2192
    assert fresh.check_fits("500320", "500109", "vertical_left").x_right == approx(4.85775)
    assert fresh.check_fits("500320", "500109", "vertical_middle").x_right == approx(4.8768)
    with pytest.raises(Refusal) as e:
        fresh.check_fits("500320", "500110", "vertical_left")
    assert e.value.reason == "past_wall_end"
    # 8 ft horizontal: stud 6 ends on 4.85775, stud 7 passes the end
    fresh.check_fits("500320", "500106", "horizontal_top")
    with pytest.raises(Refusal) as e:
        fresh.install("500320", "500107", "horizontal_bottom")
    assert e.value.reason == "past_wall_end"


def test_touching_panels_are_accepted_and_overlaps_refused(fresh: SiteState) -> None:
    state = fresh.install("500320", "500100", "vertical_left")
    state = state.install("500310", "500103", "vertical_left")  # left edge 1.20015 touches
    assert [i.drywall_id for i in state.installed] == ["500320", "500310"]
    with pytest.raises(Refusal) as e:
        state.check_fits("500300", "500105", "vertical_left")
    assert e.value.reason == "overlap"
    assert "500310" in str(e.value)


def test_top_and_bottom_rows_touch(fresh: SiteState) -> None:
    state = fresh.install("500322", "500100", "horizontal_bottom").install("500312", "500100", "horizontal_top")
    assert len(state.installed) == 2
    with pytest.raises(Refusal) as e:
        state.install("500321", "500102", "vertical_left")
    assert e.value.reason == "overlap"


def test_install_record(fresh: SiteState) -> None:
    state = fresh.install(500320, 500101, Placement.VERTICAL_MIDDLE)
    (record,) = state.installed
    assert record.drywall_id == "500320" and record.stud_id == "500101"
    assert record.placement is Placement.VERTICAL_MIDDLE
    assert corners(record.rect) == approx((0.4064, 0.4064 + 1.2192, 0, H))
    assert state.is_installed("500320") and not fresh.is_installed("500320")
    assert state.top("left") == "500310"


# --- replay --------------------------------------------------------------------------------


def test_replay(fresh: SiteState) -> None:
    commands = [
        {"drywall_id": "500320", "stud_id": "500100", "placement": "vertical_left"},
        {"drywall_id": "500310", "stud_id": "500103", "placement": "vertical_left"},
        {"drywall_id": "500322", "stud_id": "500106", "placement": "horizontal_bottom"},
    ]
    state = fresh.replay(commands)
    assert [(i.drywall_id, i.stud_id, i.placement.value) for i in state.installed] == [
        (c["drywall_id"], c["stud_id"], c["placement"]) for c in commands
    ]
    assert state.tops == {"left": "500300", "middle": "500321", "right": "500312"}
    assert fresh.replay([]) == fresh
    with pytest.raises(Refusal) as e:
        fresh.replay(commands + [{"drywall_id": "500300", "stud_id": "500100", "placement": "vertical_left"}])
    assert e.value.reason == "overlap"


# --- properties ---------------------------------------------------------------------------

ALL_PANEL_IDS = [p["drywall_id"] for p in expected_panels()]
ALL_STUD_IDS = [str(500100 + i) for i in range(N_STUDS)]

attempts = st.lists(
    st.tuples(
        st.sampled_from(ALL_PANEL_IDS + ["500330"]),
        st.sampled_from(ALL_STUD_IDS + ["500113"]),
        st.sampled_from([p.value for p in Placement]),
    ),
    max_size=15,
)


def run_attempts(state: SiteState, steps: list[tuple[str, str, str]]) -> tuple[SiteState, list[dict]]:
    """Try every step; keep the accepted ones. A refusal must leave the state as it was."""
    accepted = []
    for panel_id, stud_id, placement in steps:
        before = state
        snapshot = (dict(state.stacks), state.installed)
        try:
            state = state.install(panel_id, stud_id, placement)
        except Refusal:
            assert state is before
            assert (state.stacks, state.installed) == snapshot
            continue
        accepted.append({"drywall_id": panel_id, "stud_id": stud_id, "placement": placement})
        assert (before.stacks, before.installed) == snapshot  # the old state is untouched
    return state, accepted


@settings(max_examples=200, deadline=None)
@given(attempts)
def test_accepted_panels_never_overlap_or_pass_the_wall_end(steps: list[tuple[str, str, str]]) -> None:
    state, accepted = run_attempts(default_site().fresh(), steps)
    rects = [i.rect for i in state.installed]
    assert len(rects) == len(accepted)
    for k, a in enumerate(rects):
        assert a.x_right <= WALL_END + 1e-6
        assert a.x_left >= -HALF - 1e-9
        assert 0 <= a.z_bottom < a.z_top <= H + 1e-9
        for b in rects[k + 1 :]:
            assert not a.overlaps(b)


@settings(max_examples=200, deadline=None)
@given(attempts)
def test_panels_are_either_stacked_or_installed_and_replay_agrees(steps: list[tuple[str, str, str]]) -> None:
    fresh = default_site().fresh()
    state, accepted = run_attempts(fresh, steps)
    installed = [i.drywall_id for i in state.installed]
    stacked = [pid for ids in state.stacks.values() for pid in ids]
    assert len(set(installed)) == len(installed)
    assert sorted(installed + stacked) == sorted(ALL_PANEL_IDS)
    for name, ids in state.stacks.items():
        assert ids == STACK_IDS[name][: len(ids)]  # panels only ever leave from the top
    assert fresh.replay(accepted) == state
