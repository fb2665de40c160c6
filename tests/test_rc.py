"""Robot control (drywall_lab/rc): the scene built from the site tables, the robot's reach, the motion
planner's rules, one real simulated pick-and-place measured against its place pose, refusals that
cause no motion, failures that are reported as failures, episodes carried out step by step, the
``simulate`` command (the batch contract carried through the robot; the paper's three layouts), the layout
replay, the joint table, and the checks of notebooks 05 and 06's exercises (tried with wrong answers too).

Failures are forced rather than waited for: a panel taken off its stack or a sheet laid on it in the
simulation only (the tables do not know), a robot mistaken about its grip, a planner made to fail.

Expected geometry is computed here from the spec's section 1 (stud i at x = 0.4064 i, 1.5 x 3.5 in,
8 ft; panels 1/2 in thick; stacks at x = 0.9 / 2.4 / 3.9), not read from the project's tables.
"""
from __future__ import annotations

import json
import math

import mujoco
import numpy as np
import pytest

from drywall_lab.errors import Refusal
from drywall_lab.im import RobotCommand
from drywall_lab.rc import (ANGLE_TOLERANCE_DEG, JOINTS, POSITION_TOLERANCE, ArmIK, MotionPlanner, PlacementResult,
                            PlanningError, RobotCell, build_scene, goes_on_after, panel_mass, pose_error,
                            simulate_episode)
from drywall_lab.rc import cell as cell_module
from drywall_lab.rc.collision import CollisionChecker
from drywall_lab.rc.motion import DROP, RESUME_TOLERANCE, seating_offset, timed_stage
from drywall_lab.rc.robot import grip_transform, pose_matrix
from drywall_lab.site import STACK_Y, Pose, default_site

# meshcat 0.3.2 (the animations simulate --html writes) imports a pyzmq module that pyzmq has deprecated
pytestmark = pytest.mark.filterwarnings("ignore:zmq.eventloop.ioloop is deprecated:DeprecationWarning")

SPACING, HALF_STUD, DEPTH, H, T = 0.4064, 0.01905, 0.0889, 2.4384, 0.0127
FT = 0.3048


@pytest.fixture(scope="module")
def site():
    return default_site()


def command(site, drywall_id, stud_id, placement):
    return RobotCommand.build(site, drywall_id, stud_id, placement)


def by_ids(drywall_id: str, stud_id: str) -> tuple[str, list[str], list[str]]:
    """An instruction naming a panel and a stud by id: its text, words and gold tags."""
    text = f"Take panel {drywall_id} and put it on stud {stud_id}"
    return text, text.split(), ["O", "O", "ID_wall", "O", "O", "O", "O", "O", "ID_stud"]


def episode(name: str, *pairs: tuple[str, str]) -> dict:
    """A gold-tagged episode of ``(drywall_id, stud_id)`` instructions, vertical on the stud's left line."""
    steps = [by_ids(d, s) for d, s in pairs]
    return {"id": name, "instructions": [t for t, _, _ in steps], "words": [w for _, w, _ in steps],
            "tags": [g for _, _, g in steps]}


def put_panel(cell: RobotCell, drywall_id: str, position) -> None:
    """Move a panel in the simulation only (lying flat, at rest): the site tables still have it where it was."""
    sc = cell.scene
    joint = sc.model.body_jntadr[sc.panel_body[drywall_id]]
    adr, dof = sc.model.jnt_qposadr[joint], sc.model.jnt_dofadr[joint]
    sc.data.qpos[adr:adr + 3] = position
    sc.data.qvel[dof:dof + 6] = 0.0
    mujoco.mj_forward(sc.model, sc.data)
    cell.hold(0.5)  # let it settle


def joints_at_ready(cell: RobotCell) -> bool:
    return bool(np.max(np.abs(cell.scene.q - cell.planner.ready_posture(cell.scene.q[0]))) < 2e-3)


# --- the scene ------------------------------------------------------------------------------------------
def test_scene_has_the_thirteen_studs_where_the_spec_puts_them(site):
    scene = build_scene(site.fresh())
    m = scene.model
    assert len(scene.stud_geom) == 13
    for i in range(13):
        g = scene.stud_geom[str(500100 + i)]
        assert m.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX
        np.testing.assert_allclose(scene.data.geom_xpos[g], [SPACING * i, 0.0, H / 2], atol=1e-6)
        np.testing.assert_allclose(m.geom_size[g], [HALF_STUD, DEPTH / 2, H / 2], atol=1e-6)


def test_scene_panels_are_free_bodies_in_their_stacks_with_realistic_mass(site):
    scene = build_scene(site.fresh())
    m, d = scene.model, scene.data
    stacks = {"500300": 0.9, "500301": 2.4, "500302": 3.9}
    sizes = {"0": (4, 8), "1": (2, 8), "2": (4, 6)}
    for pid, body in scene.panel_body.items():
        level, stack_key = int(pid[4]), pid[5]
        w_ft, l_ft = sizes[stack_key]
        x = stacks[f"50030{stack_key}"]
        assert m.body_jntnum[body] == 1 and m.jnt_type[m.body_jntadr[body]] == mujoco.mjtJoint.mjJNT_FREE
        np.testing.assert_allclose(d.xpos[body], [x, STACK_Y, (level + 0.5) * T], atol=1e-6)
        # lying flat: the panel's own z (its length) along the floor, its y (thickness) up
        np.testing.assert_allclose(d.xmat[body].reshape(3, 3)[:, 1], [0, 0, 1], atol=1e-9)
        np.testing.assert_allclose(m.body_mass[body], 25.0 * w_ft * l_ft / 32, rtol=1e-3)
        np.testing.assert_allclose(m.geom_size[scene.panel_geom[pid]], [w_ft * FT / 2, T / 2, l_ft * FT / 2], atol=1e-6)
    assert math.isclose(panel_mass(site.panel("500320")), 25.0, rel_tol=1e-6)


def test_scene_robot_has_a_rail_six_arm_joints_and_a_servo_each(site):
    scene = build_scene(site.fresh())
    m = scene.model
    names = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j) for j in range(m.njnt)]
    assert [n for n in names if n in JOINTS] == list(JOINTS)
    rail = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, "rail")
    assert m.jnt_type[rail] == mujoco.mjtJoint.mjJNT_SLIDE
    np.testing.assert_allclose(m.jnt_axis[rail], [1, 0, 0])  # along the wall
    for j in JOINTS:
        jid = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, j)
        assert m.jnt_limited[jid] and m.jnt_range[jid, 0] < m.jnt_range[jid, 1]
    assert len(scene.actuator_index) == 7 and np.all(scene.kp > 0) and np.all(scene.kv > 0)
    # every servo can hold a 25 kg sheet at 2 m: 25 * 9.81 * 2 ~ 490 N m, far below the limits
    assert np.all(m.actuator_forcerange[scene.actuator_index, 1] >= 3000)


def test_scene_welds_are_off_for_stacked_panels_and_on_for_installed_ones(site):
    state = site.fresh().install("500320", "500100", "vertical_left")
    scene = build_scene(state)
    d = scene.data
    assert not any(d.eq_active[e] for e in scene.grip_weld.values())
    assert d.eq_active[scene.screws_weld["500320"]] and not d.eq_active[scene.screws_weld["500310"]]
    pose = scene.panel_pose("500320")
    np.testing.assert_allclose(pose.position, [-HALF_STUD + 4 * FT / 2, DEPTH / 2 + T / 2, 8 * FT / 2], atol=1e-6)


# --- reach and planning ------------------------------------------------------------------------------------
def test_the_arm_reaches_the_bottom_of_a_stack_and_the_top_row(site):
    ik = ArmIK()
    grip = np.linalg.inv(grip_transform(T))
    bottom = site.pick_pose("500300")  # the lowest panel, on the floor
    top_row = site.place_pose("500321", "500106", "horizontal_top")  # 2 x 8 ft, top edge at 2.44 m
    for pose, rail in ((bottom, 0.9 - 1.0), (top_row, top_row.position[0] - 1.0)):
        seed = ik.home.copy()
        seed[0] = rail
        target = pose_matrix(pose.position, pose.quaternion) @ grip
        solution = ik.solve(target, seed, hold_rail=True, max_iterations=400)
        np.testing.assert_allclose(ik.fk(solution.q)[:3, 3], target[:3, 3], atol=1e-4)


def test_every_stage_moves_the_arm_or_the_base_never_both(site):
    planner = MotionPlanner(site)
    far = command(site, "500322", "500100", "horizontal_top")  # right stack to the wall's left end
    plan = planner.plan(far, planner.ready_posture(0.0), site.fresh())
    assert plan.base_moves >= 1
    for stage in plan.stages:
        moved = np.ptp(stage.samples, axis=0) > 1e-9
        if stage.kind == "base":
            assert not moved[1:].any(), stage.name
        else:
            assert not moved[0], stage.name


def test_the_base_stays_when_the_arm_alone_can_do_the_job(site):
    planner = MotionPlanner(site)
    near = command(site, "500320", "500100", "vertical_left")  # left stack, first stud, robot at x = 0
    plan = planner.plan(near, planner.ready_posture(0.0), site.fresh())
    assert plan.base_moves == 0 and plan.pick_station == plan.place_station == 0.0


def test_seating_offset_keeps_clear_of_neighbours(site):
    state = site.fresh().install("500320", "500100", "horizontal_top")  # 0 .. 2.44 m wide, 1.22 .. 2.44 m high
    under = command(site, "500310", "500100", "horizontal_bottom")  # exactly between the floor and it
    assert seating_offset(under, state) == (0.0, 0.0)
    apart = command(site, "500321", "500108", "vertical_left")  # next to nothing: drops 4 mm onto the floor
    assert seating_offset(apart, state) == (0.0, DROP)
    beside = command(site, "500321", "500106", "vertical_left")  # its left edge meets 500320's right end
    assert seating_offset(beside, state) == (DROP, DROP)
    state = site.fresh().install("500320", "500100", "vertical_left")
    right_of = command(site, "500310", "500103", "vertical_left")  # its left edge meets 500320's right edge
    assert seating_offset(right_of, state) == (DROP, DROP)


def test_collision_check_sees_the_arm_in_the_floor(site):
    checker = CollisionChecker(site.fresh())
    ik = ArmIK()
    checker.reset()
    checker.set_context("free", None)
    assert checker.first_collision(ik.home) is None
    slumped = ik.home.copy()
    slumped[2], slumped[3] = math.radians(110), 0.0  # upper arm leaning out, forearm straight down
    assert "floor" in (checker.first_collision(slumped) or "")


def test_the_planner_plans_no_motion_without_a_collision_check(site):
    """Every motion is checked: a stage planned outside ``checking`` is an error, never an unchecked stage."""
    planner = MotionPlanner(site)
    q = planner.ready_posture(0.0)
    with pytest.raises(RuntimeError, match="collision"):
        planner.joint_stage("ready", "free", q, q + 0.1)
    with pytest.raises(RuntimeError, match="collision"):
        planner.base_stage("base", "free", q, 0.5)
    with planner.checking(site.fresh()):
        stage = planner.base_stage("base", "free", q, 0.5)
    assert stage.collision_checked and stage.duration > 0


def test_the_cell_runs_no_stage_that_was_not_checked_for_collisions():
    cell = RobotCell()
    q = cell.scene.q
    unchecked = timed_stage("slump", "arm", "free", np.array([q, q + np.radians([0, 0, 20, 0, 0, 0, 0])]), 1.0)
    t, qpos = cell.time, cell.scene.data.qpos.copy()
    with pytest.raises(ValueError, match="not checked for collisions"):
        cell.run_stage(unchecked)
    assert cell.time == t and np.array_equal(cell.scene.data.qpos, qpos)


def test_planned_stages_are_taken_up_again_only_from_where_the_robot_is_and_only_if_safe(site):
    planner = MotionPlanner(site)
    state = site.fresh()
    c = command(site, "500320", "500100", "vertical_left")
    plan = planner.plan(c, planner.ready_posture(0.0), state)
    seated = plan.carrying[-1].end
    place = pose_matrix(c.place_pose.position, c.place_pose.quaternion)
    close = seated + RESUME_TOLERANCE / 2
    taken_up = planner.verified(plan.after_release, close, c, state, panel_pose=place)
    np.testing.assert_array_equal(taken_up[0].samples[0], close)  # no jump in the set points
    assert all(s.collision_checked for s in taken_up)
    with pytest.raises(PlanningError, match="away from where the robot is"):
        planner.verified(plan.after_release, seated + 10 * RESUME_TOLERANCE, c, state, panel_pose=place)
    # held 10 cm further along its length than planned, the sheet would be carried into the floor
    grip = grip_transform(T)
    grip[1, 3] -= 0.1
    with pytest.raises(PlanningError, match="floor"):
        planner.verified(plan.carrying, plan.before_grip[-1].end, c, state, grip=grip)


@pytest.mark.parametrize("success, lifted, contacts, clear, goes_on", [
    (True, True, 0, True, True),
    (False, False, 0, True, True),    # unreachable, grip failed: the panel is still on its stack
    (False, False, 1, True, False),   # ... but something was hit
    (False, False, 0, False, False),  # ... but the robot could not get back
    (False, True, 0, True, False),    # slipped, off its pose, collided on the way
])
def test_the_episode_goes_on_only_while_the_site_is_what_the_tables_say(site, success, lifted, contacts, clear,
                                                                           goes_on):
    from drywall_lab.rc.contacts import ContactEvent

    result = PlacementResult(command(site, "500320", "500100", "vertical_left"), success, None if success else "x",
                             None, 0.0, 0.0, 0.0, 1.0, 1.0, 0,
                             [ContactEvent("a", "b", "lift", 1.0, 1, 0.001)] * contacts,
                             panel_lifted=lifted, robot_clear=clear)
    assert goes_on_after(result) is goes_on


# --- failures forced in the simulation ----------------------------------------------------------------------
@pytest.fixture(scope="module")
def taken_panel_run(site):
    """Someone carried panel 500320 off the left stack (the tables still have it there); then an episode:
    500320 (the grip fails), 500310 (under 500320, by the tables), 500321 (placed)."""
    cell = RobotCell()
    put_panel(cell, "500320", (0.9, STACK_Y + 2.6, T / 2))  # on the floor beyond the stacks
    return simulate_episode(episode("taken", ("500320", "500100"), ("500310", "500104"), ("500321", "500104")),
                            cell=cell)


def test_a_failed_grip_leaves_site_and_history_as_they_were_and_the_episode_goes_on(taken_panel_run):
    run = taken_panel_run
    assert [s.status for s in run.steps] == ["failed", "refused", "placed"]
    failed = run.steps[0].result
    assert failed.failure == "grip_failed" and not failed.panel_lifted and failed.robot_clear
    assert not failed.unexpected_contacts
    # IM interprets the next instruction against the history without 500320: it is still on the stack
    refusal = run.steps[1].interpretation.refusal
    assert refusal.reason == "not_on_top" and "500320" in refusal.message and not run.steps[1].robot_moved
    assert [c.drywall_id for c in run.history.commands] == ["500321"]
    assert run.history.state == run.cell.state and run.stopped_after is None and not run.all_placed
    assert run.table().outcome.tolist() == ["failed: grip_failed", "no motion", "placed"]


def test_the_way_back_after_a_failed_grip_is_a_checked_motion(taken_panel_run):
    stages = [name for name, _, _ in taken_panel_run.steps[0].result.trace.stages]
    assert stages[-3:] == ["descend", "withdraw", "ready"]


def test_after_a_failed_grip_the_robot_stays_put_when_no_safe_way_back_is_found(site, monkeypatch):
    """The way back is checked like every motion: when the check finds a collision on it, the robot does not
    move, says why, and the episode stops."""
    cell = RobotCell()
    put_panel(cell, "500320", (0.9, STACK_Y + 2.6, T / 2))
    real_grip = RobotCell.grip

    def grip_then_block_the_way(self, c):
        gripped = real_grip(self, c)
        monkeypatch.setattr(CollisionChecker, "first_collision", lambda checker, q: "a worker would be in the way")
        return gripped

    monkeypatch.setattr(RobotCell, "grip", grip_then_block_the_way)
    run = simulate_episode(episode("blocked", ("500320", "500100"), ("500321", "500104")), cell=cell)
    result = run.steps[0].result
    assert result.failure == "grip_failed" and not result.robot_clear
    assert any("a worker would be in the way" in n and "stays where it is" in n for n in result.notes)
    assert [name for name, _, _ in result.trace.stages][-1] == "descend"
    assert not joints_at_ready(cell)
    assert [s.status for s in run.steps] == ["failed", "not carried out"] and run.stopped_after == 0


@pytest.fixture(scope="module")
def extra_sheet_run(site):
    """A sheet the tables do not know about (500321, from the middle stack) lies on top of the left stack;
    the episode asks for 500320, then 500310."""
    cell = RobotCell()
    put_panel(cell, "500321", (0.9, STACK_Y, 3.5 * T))
    return simulate_episode(episode("extra sheet", ("500320", "500100"), ("500310", "500104")), cell=cell)


def test_contact_watch_reports_the_pad_pressing_on_a_sheet_the_tables_do_not_know(extra_sheet_run):
    """Collisions in the running simulation are reported, not hidden: the planned (and checked) descent onto
    500320 meets the unknown sheet first."""
    result = extra_sheet_run.steps[0].result
    events = result.unexpected_contacts
    assert events and all(e.stage == "descend" for e in events)
    assert any({"lifter_pad", "panel_500321"} == {e.geom1, e.geom2} and e.max_depth > 0.001 for e in events)


def test_anything_hit_stops_the_episode_even_before_the_panel_left_its_stack(extra_sheet_run):
    run = extra_sheet_run
    result = run.steps[0].result
    assert result.failure == "grip_failed" and not result.panel_lifted and result.robot_clear
    assert run.stopped_after == 0 and [s.status for s in run.steps] == ["failed", "not carried out"]
    assert run.steps[1].interpretation is None and not run.steps[1].robot_moved
    assert len(run.history) == 0 and run.history.state == run.cell.state


# --- one real pick-and-place --------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def placed(site):
    """A fresh site, the first command of the paper's layout 1 carried out by the simulated robot."""
    cell = RobotCell()
    result = cell.execute(command(site, "500320", "500100", "vertical_left"))
    return cell, result


def test_pick_and_place_puts_the_panel_on_its_pose(placed):
    cell, result = placed
    assert result.success, result
    assert result.failure is None and not result.unexpected_contacts
    assert result.position_error_mm < POSITION_TOLERANCE * 1000
    assert result.angle_error_deg < ANGLE_TOLERANCE_DEG
    assert result.base_moves == 0  # the arm alone: the left stack and stud 500100 are in its reach
    # the panel really moved, from the top of the left stack to the wall
    assert np.linalg.norm(np.subtract(result.final_pose.position, (0.9, STACK_Y, 2.5 * T))) > 2.0
    assert cell.state.is_installed("500320")


def test_pick_and_place_error_is_measured_on_the_simulated_panel(placed):
    cell, result = placed
    pose = cell.scene.panel_pose("500320")
    pos, ang = pose_error(pose, result.command.place_pose)
    assert pos * 1000 == pytest.approx(result.position_error_mm, abs=0.05)
    # fastened where it was released: it stays there
    cell.hold(1.0)
    pos_later, _ = pose_error(cell.scene.panel_pose("500320"), result.command.place_pose)
    assert abs(pos_later - pos) < 2e-4


def test_pick_and_place_traces_every_stage_of_the_joints(placed):
    """Speed (the real-time factor) is measured by benchmarks/placement.py, not asserted here."""
    _, result = placed
    assert result.sim_time > 20
    frame = result.trace.frame()
    assert list(frame.columns[:3]) == ["time", "rail", "rail_set"]
    names = [s[0] for s in result.trace.stages]
    for stage in ("approach_pick", "descend", "lift", "tilt", "swing", "turn", "approach", "set", "seat", "retreat"):
        assert stage in names
    assert np.all(result.trace.largest_tracking_error < 0.02)


def test_refused_command_causes_no_motion(placed, site):
    cell, _ = placed
    qpos, t, n = cell.scene.data.qpos.copy(), cell.time, len(cell.results)
    for drywall_id, stud_id, reason in (("500300", "500104", "not_on_top"),     # under 500310 in the left stack
                                        ("500310", "500101", "overlap"),        # over 500320, installed above
                                        ("500320", "500106", "already_installed")):
        with pytest.raises(Refusal) as refusal:
            cell.execute(command(site, drywall_id, stud_id, "vertical_left"))
        assert refusal.value.reason == reason
    assert cell.time == t and len(cell.results) == n
    np.testing.assert_array_equal(cell.scene.data.qpos, qpos)


def mistaken_grip(monkeypatch, offset) -> None:
    """Make the robot believe it holds the panel ``offset`` (m, TCP frame) from where it does."""
    real = cell_module.believed_grip

    def mistaken(ik, q, cmd):
        grip = real(ik, q, cmd)
        grip[:3, 3] += offset
        return grip

    monkeypatch.setattr(cell_module, "believed_grip", mistaken)


def test_a_panel_set_off_its_pose_is_a_failure_and_the_robot_stops(site, monkeypatch):
    """A robot that believes it holds the panel 8 mm from where it does sets it 8 mm off: a failure. The site
    no longer matches the tables, so the rest of the episode is not carried out."""
    mistaken_grip(monkeypatch, (0.008, 0.0, 0.0))  # along the panel's width
    run = simulate_episode(episode("off pose", ("500320", "500100"), ("500321", "500103"), ("500310", "500106")))
    result = run.steps[0].result
    assert not result.success and result.failure == "off_pose" and result.panel_lifted
    assert 6.0 < result.position_error_mm < 10.0
    assert run.stopped_after == 0 and [s.status for s in run.steps] == ["failed"] + ["not carried out"] * 2
    t = run.steps[0].sim_time_after
    assert all(s.interpretation is None and s.result is None and not s.robot_moved and s.sim_time_before == t
               for s in run.steps[1:])
    assert run.outcomes()[1:] == [None, None] and len(run.history) == 0
    assert run.cell.state.is_installed("500320")  # fastened, off its pose: what the robot stopped for
    assert run.table().outcome.tolist() == ["failed: off_pose; the robot stopped"] + [
        "not carried out: the robot stopped after step 0"] * 2


def test_a_planning_error_leaves_site_and_history_as_they_were_and_the_episode_goes_on(site, monkeypatch):
    """A collision found while planning fails the step before any motion; IM then reads the next instruction
    against a history without it (before, the history had the panel and the robot refused it: a Refusal)."""
    real_plan = MotionPlanner.plan

    def plan(self, c, q, state):
        if c.drywall_id == "500320":
            raise PlanningError("approach_pick: lifter_pad would come within 2 mm of panel_500320")
        return real_plan(self, c, q, state)

    monkeypatch.setattr(MotionPlanner, "plan", plan)
    run = simulate_episode(episode("planning error", ("500320", "500100"), ("500310", "500104")))
    first, second = run.steps
    assert first.status == "failed" and first.result.failure.startswith("unreachable: approach_pick")
    assert not first.robot_moved and first.sim_time_before == first.sim_time_after
    assert second.status == "refused" and second.interpretation.refusal.reason == "not_on_top"
    assert len(run.history) == 0 and run.history.state == run.cell.state == site.fresh()


def test_replanning_errors_are_recorded_and_the_first_plan_is_used_once_checked_again(site, monkeypatch):
    def fail(*args, **kwargs):
        raise PlanningError("forced for the test")

    cell = RobotCell()
    monkeypatch.setattr(cell.planner, "replan_carry", fail)
    monkeypatch.setattr(cell.planner, "replan_release", fail)
    result = cell.execute(command(site, "500320", "500100", "vertical_left"))
    assert result.success, result
    assert result.notes == ["re-planning the carry from the measured grip failed: forced for the test",
                            "carried as first planned (checked again with the measured grip)",
                            "re-planning the retreat failed: forced for the test",
                            "retreated as first planned (checked again)"]
    assert "forced for the test" in result.summary()["notes"]


def test_an_unsafe_first_plan_is_not_used_when_replanning_fails(site, monkeypatch):
    """The robot believes it holds the sheet 10 cm further along its length than it does: the re-planned carry
    fails (forced), and the first plan's carry, checked with that grip, would put the sheet into the floor. The
    step fails cleanly: the vacuum lets go, the pad withdraws, the panel is still on its stack."""
    mistaken_grip(monkeypatch, (0.0, -0.1, 0.0))
    cell = RobotCell()

    def fail(*args, **kwargs):
        raise PlanningError("forced for the test")

    monkeypatch.setattr(cell.planner, "replan_carry", fail)
    c = command(site, "500320", "500100", "vertical_left")
    result = cell.execute(c)
    assert result.failure.startswith("unreachable") and not result.panel_lifted and result.robot_clear
    assert result.notes[0].endswith("forced for the test") and "floor" in result.notes[1]
    assert np.linalg.norm(np.subtract(cell.scene.panel_pose("500320").position, c.pick_pose.position)) < 0.005
    assert cell.state == site.fresh() and joints_at_ready(cell) and goes_on_after(result)
    assert [name for name, _, _ in result.trace.stages][-2:] == ["withdraw", "ready"]


def test_a_blocked_retreat_leaves_the_robot_where_it_is(site, monkeypatch):
    def fail(*args, **kwargs):
        raise PlanningError("forced for the test")

    cell = RobotCell()
    monkeypatch.setattr(cell.planner, "replan_release", fail)
    monkeypatch.setattr(cell.planner, "verified", fail)
    result = cell.execute(command(site, "500320", "500100", "vertical_left"))
    assert result.failure.startswith("retreat_blocked") and result.panel_lifted and not result.robot_clear
    assert "retreat" not in [name for name, _, _ in result.trace.stages]
    assert cell.state.is_installed("500320") and not goes_on_after(result)


def test_pose_error_angle():
    half = math.radians(0.3) / 2
    turned = Pose((0.0, 0.0, 0.001), (math.cos(half), 0.0, math.sin(half), 0.0))
    pos, ang = pose_error(turned, Pose((0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0)))
    assert pos == pytest.approx(0.001) and ang == pytest.approx(0.3)
    flipped = Pose((0.0, 0.0, 0.0), (-1.0, 0.0, 0.0, 0.0))  # the same orientation
    assert pose_error(flipped, Pose((0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0)))[1] == pytest.approx(0.0)


def test_fast_mode_is_the_courses_one_and_records_fewer_frames(monkeypatch):
    """One fast-mode switch for the whole course (drywall_lab.course.fast_mode): robot control reads it."""
    from drywall_lab.course import fast_mode
    from drywall_lab.rc import record_fps
    from drywall_lab.rc.settings import RECORD_FPS, RECORD_FPS_FAST

    monkeypatch.setenv("DRYWALL_FAST", "1")
    assert fast_mode() and record_fps() == RECORD_FPS_FAST < RECORD_FPS
    for off in ("", "0", "false"):
        monkeypatch.setenv("DRYWALL_FAST", off)
        assert not fast_mode() and record_fps() == RECORD_FPS
    monkeypatch.delenv("DRYWALL_FAST")
    assert not fast_mode()


def test_a_refused_instruction_in_an_episode_reaches_no_robot():
    run = simulate_episode(episode("one refusal", ("500300", "500108")))
    step = run.steps[0]
    assert step.status == "refused" and step.interpretation.refusal.reason == "not_on_top"
    assert step.result is None and not step.robot_moved and step.sim_time_before == step.sim_time_after
    assert step.text.endswith("500108") and run.outcomes() == [{"refusal": "not_on_top"}]
    assert run.table().outcome.tolist() == ["no motion"] and len(run.history) == 0 and run.all_placed


def test_an_episode_without_gold_tags_needs_a_tagger():
    with pytest.raises(ValueError, match="give a tagger"):
        simulate_episode({"id": "e", "instructions": ["Take panel 500320 and put it on stud 500100"]})


def test_an_episode_in_a_cell_with_a_partly_built_wall_starts_from_its_history(site):
    """IM reads the first instruction against the panels already on the cell's wall: no motion, no Refusal."""
    cell = RobotCell(site.fresh().install("500320", "500100", "vertical_left"))
    run = simulate_episode(episode("partly built", ("500320", "500104"), ("500310", "500101")), cell=cell)
    assert [s.interpretation.refusal.reason for s in run.steps] == ["already_installed", "overlap"]
    assert [c.drywall_id for c in run.history.commands] == ["500320"] and run.history.state == cell.state
    assert not any(s.robot_moved for s in run.steps)



# --- simulate: the batch contract carried through the robot (spec section 6) --------------------------------
RUN_FIELDS = ["episode", "step", "words", "tags", "command", "refusal"]
PLACEMENT_FIELDS = ["status", "success", "position_error_mm", "angle_error_deg", "collisions", "failure", "sim_time_s"]


def simulate_cli(capsys, *args: str) -> tuple[int, list[dict], str]:
    from drywall_lab.__main__ import main

    code = main(["simulate", *args])
    out, err = capsys.readouterr()
    return code, [json.loads(line) for line in out.splitlines()], err


def run_cli(capsys, path) -> list[dict]:
    from drywall_lab.__main__ import main

    assert main(["run", str(path)]) == 0
    return [json.loads(line) for line in capsys.readouterr().out.splitlines()]


@pytest.fixture(scope="module")
def small_episodes(tmp_path_factory):
    """One placement, a refusal and an empty instruction in one episode; a refusal in a second one with a number
    as its id. One simulated placement in all, so that the test stays short."""
    path = tmp_path_factory.mktemp("simulate") / "episodes.jsonl"
    path.write_text(json.dumps({"id": "e1", "instructions": [
        "Pick up the full-size drywall and put it on stud 500100.",
        "Take panel 500300 and put it on stud 500104.",
        "",
    ]}) + "\n" + json.dumps({"id": 2, "instructions": ["Put the 4 by 6 panel on stud 500112."]}) + "\n",
        encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def simulated_small(small_episodes, tmp_path_factory):
    """``simulate --html`` on the small episodes: exit code, records, what it said on stderr, the page."""
    from drywall_lab.__main__ import main
    import contextlib
    import io

    html = tmp_path_factory.mktemp("html") / "out" / "episodes.html"
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(["simulate", str(small_episodes), "--html", str(html)])
    return code, [json.loads(line) for line in out.getvalue().splitlines()], err.getvalue(), html


def test_simulate_writes_the_run_fields_and_each_placement(simulated_small, small_episodes, capsys):
    code, records, _, _ = simulated_small
    assert code == 0
    assert [(r["episode"], r["step"]) for r in records] == [("e1", 0), ("e1", 1), ("e1", 2), (2, 0)]
    for r in records:
        assert list(r) == RUN_FIELDS + ["placement"] and list(r["placement"]) == PLACEMENT_FIELDS
    # the run fields are run's own, line for line
    assert [{k: r[k] for k in RUN_FIELDS} for r in records] == run_cli(capsys, small_episodes)
    placed, buried, empty, past_end = (r["placement"] for r in records)
    assert placed["status"] == "placed" and placed["success"] and placed["failure"] is None
    assert 0 <= placed["position_error_mm"] < POSITION_TOLERANCE * 1000
    assert 0 <= placed["angle_error_deg"] < ANGLE_TOLERANCE_DEG and placed["collisions"] == []
    assert placed["sim_time_s"] > 20
    for refused in (buried, empty, past_end):
        assert refused == {"status": "refused", "success": False, "position_error_mm": None, "angle_error_deg": None,
                           "collisions": [], "failure": None, "sim_time_s": 0.0}


def test_simulate_html_is_one_self_contained_animation_of_all_episodes(simulated_small):
    import base64
    import re

    import umsgpack

    _, _, err, html = simulated_small
    page = html.read_text(encoding="utf-8")
    assert page.lstrip().startswith("<!DOCTYPE html>") and "MeshCat.Viewer" in page
    assert not re.search(r"<(?:script|link|img|iframe)\b[^>]*\b(?:src|href)\s*=", page)
    assert set(re.findall(r"https?://[^\s\"'<>)]+", page)) <= {"http://www.w3.org/1999/xhtml"}
    blobs = re.findall(r"data:application/octet-binary;base64,([A-Za-z0-9+/=]+)", page)
    commands = [umsgpack.unpackb(base64.b64decode(b)) for b in blobs]
    (animation,) = [c for c in commands if c["type"] == "set_animation"]
    clips = {a["path"].split("/")[-1]: a["clip"] for a in animation["animations"]}
    keys = {t["name"]: t for t in clips["panel_500320"]["tracks"]}[".position"]["keys"]
    # 500320 goes from its stack to the wall, and back to its stack when the second episode starts afresh
    ys = [k["value"][1] for k in keys]
    assert ys[0] == pytest.approx(STACK_Y, abs=0.01) and min(ys) < 0.1 and ys[-1] == pytest.approx(STACK_Y, abs=0.01)
    assert f"animation of 2 episode(s): {html}" in err


def test_simulate_without_html_writes_no_page(small_episodes, tmp_path, capsys, monkeypatch):
    """No --html: nothing recorded, no page; a placement the robot fails is reported as failed with its reason,
    and the instructions after it as not carried out (not tagged, not interpreted)."""
    mistaken_grip(monkeypatch, (0.008, 0.0, 0.0))  # the robot sets the panel 8 mm off
    monkeypatch.chdir(tmp_path)
    code, records, err = simulate_cli(capsys, str(small_episodes))
    assert code == 0 and err == "" and list(tmp_path.iterdir()) == []
    failed, after, empty, other = records
    assert failed["command"] is not None and failed["placement"]["status"] == "failed"
    assert failed["placement"]["failure"] == "off_pose" and not failed["placement"]["success"]
    assert failed["placement"]["position_error_mm"] > POSITION_TOLERANCE * 1000
    for r in (after, empty):
        assert r["tags"] is None and r["command"] is None and r["refusal"] is None
        assert r["placement"]["status"] == "not carried out"
        assert r["placement"]["failure"] == "not carried out: the robot stopped after step 0"
    assert after["words"] == ["Take", "panel", "500300", "and", "put", "it", "on", "stud", "500104"]
    assert other["placement"]["status"] == "refused"  # the next episode starts afresh


def test_simulate_reports_bad_input_like_run_before_simulating(tmp_path, capsys):
    code, records, err = simulate_cli(capsys, str(tmp_path / "missing.jsonl"))
    assert code == 2 and records == [] and "no episodes file" in err
    bad = tmp_path / "bad.jsonl"
    bad.write_text('{"id": "a", "instructions": ["Take panel 500320 and put it on stud 500100"]}\n{"id": "b"}\n')
    code, records, err = simulate_cli(capsys, str(bad))
    assert code == 2 and records == [] and "line 2" in err
    good = tmp_path / "good.jsonl"
    good.write_text('{"id": "a", "instructions": ["Take panel 500320 and put it on stud 500100"]}\n')
    code, records, err = simulate_cli(capsys, str(good), "--html", str(tmp_path))
    assert code == 2 and records == [] and "is a folder" in err
    code, records, err = simulate_cli(capsys, str(good), "--html", str(good / "page.html"))
    assert code == 2 and records == [] and "is a file, not a folder" in err


def test_simulate_places_every_panel_of_the_papers_three_layouts(capsys):
    """Issue 13's target: the three layouts (Figs. 15-18) through the default tagger, the IM rules and the robot."""
    from drywall_lab.pipeline import LAYOUTS_PATH, paper_layouts

    code, records, _ = simulate_cli(capsys, str(LAYOUTS_PATH))
    assert code == 0
    expected = [(layout["id"], k, want) for layout in paper_layouts() for k, want in enumerate(layout["expected"])]
    assert [(r["episode"], r["step"]) for r in records] == [(e, k) for e, k, _ in expected]
    for r, (_, _, want) in zip(records, expected):
        p = r["placement"]
        if "refusal" in want:
            assert r["command"] is None and p["status"] == "refused"
            continue
        assert r["command"] == want
        assert p["status"] == "placed" and p["success"] and p["collisions"] == [] and p["failure"] is None
        assert p["position_error_mm"] < POSITION_TOLERANCE * 1000 and p["angle_error_deg"] < ANGLE_TOLERANCE_DEG
    assert sum(r["placement"]["status"] == "placed" for r in records) == 13


def test_each_instruction_is_decided_as_run_decides_it(site):
    """``interpret_instruction`` against a growing history gives what ``run`` (pipeline.run_episode) gives."""
    from drywall_lab.corpus import tokenize
    from drywall_lab.im import ActionHistory
    from drywall_lab.nlu import default_tagger
    from drywall_lab.pipeline import run_episode
    from drywall_lab.decision import interpret_instruction

    episode = {"id": "e", "instructions": [
        "Pick up the full-size drywall and put it on stud 500100.", "Take panel 500300 and put it on stud 500104.",
        "Grab the panel that is two feet wide and put it on the stud three to the right of the previous stud.",
        "put it there", "same again on the centre of the next one"]}
    tagger = default_tagger()
    history = ActionHistory(site)
    mine = []
    for text in episode["instructions"]:
        result = interpret_instruction(tokenize(text), tagger, history)
        if result.command is not None:
            history.record(result.command)
        mine.append(result)
    theirs = run_episode(episode, tagger, site)
    assert [(m.tags, m.command, m.refusal and m.refusal.reason) for m in mine] == \
        [(t.tags, t.command, t.refusal and t.refusal.reason) for t in theirs]


# --- the library behind notebooks 05 and 06 ---------------------------------------------------------------
def test_joint_table_reads_the_model(site):
    from drywall_lab.rc import SERVOS, joint_table
    from drywall_lab.rc.robot import RAIL_RANGE, SPEED_LIMITS

    table = joint_table()
    assert table.joint.tolist() == list(JOINTS) and table.unit.tolist() == ["m"] + ["deg"] * 6
    assert (table.low[0], table.high[0]) == RAIL_RANGE and (table.low[2], table.high[2]) == (-80, 110)
    assert table.kp.tolist() == [SERVOS[j].kp for j in JOINTS] and table.kv.tolist() == [SERVOS[j].kv for j in JOINTS]
    assert table["speed limit (unit/s)"][1] == pytest.approx(math.degrees(SPEED_LIMITS[1]), abs=0.05)
    cell = RobotCell(servo_gains={"a2": SERVOS["a2"].__class__(kp=1.0e5, kv=2.0e3, force=1.0e3)})
    softer = joint_table(cell.scene.model).set_index("joint")
    assert (softer.kp["a2"], softer.kv["a2"], softer["force limit"]["a2"]) == (1.0e5, 2.0e3, 1.0e3)
    assert softer.kp["a3"] == SERVOS["a3"].kp


def test_servo_gains_reach_the_model_and_the_controller_or_are_refused():
    from drywall_lab.rc import SERVOS, ServoGains

    cell = RobotCell()
    sc = cell.scene
    sc.set_servo_gains({"a1": ServoGains(kp=2.0e5, kv=1.0e4, force=5.0e3)})
    a1 = sc.actuator_index[1]
    assert sc.model.actuator_gainprm[a1, 0] == 2.0e5 and tuple(sc.model.actuator_biasprm[a1, 1:3]) == (-2.0e5, -1.0e4)
    assert tuple(sc.model.actuator_forcerange[a1]) == (-5.0e3, 5.0e3) and (sc.kp[1], sc.kv[1]) == (2.0e5, 1.0e4)
    assert sc.kp[2] == SERVOS["a2"].kp
    with pytest.raises(ValueError, match="no joint 'a7'"):
        sc.set_servo_gains({"a7": SERVOS["a1"]})
    for bad in (ServoGains(kp=-1.0, kv=1.0, force=1.0), ServoGains(kp=1.0, kv=float("nan"), force=1.0),
                ServoGains(kp=1.0, kv=1.0, force=0.0)):
        with pytest.raises(ValueError, match="must be a positive number"):
            sc.set_servo_gains({"a1": bad})


def test_a_layout_replay_lists_what_is_not_as_the_layout_expects(site):
    """``replay_layout`` compares outcomes and placements with the layout's ``expected``; a wrong expectation is
    reported step by step."""
    from drywall_lab.rc import replay_layout

    layout = episode("one panel", ("500320", "500100"), ("500300", "500104"))
    layout["expected"] = [{"drywall_id": "500320", "stud_id": "500100", "placement": "vertical_left"},
                          {"refusal": "not_on_top"}]
    replay = replay_layout(layout)
    assert replay.ok and replay.problems() == [] and replay.history_figure == ""
    assert "1 placed; largest errors" in replay.report() and "tolerance 5 mm" in replay.report()
    wrong = dict(layout, id="layout2", expected=[{"drywall_id": "500320", "stud_id": "500101",
                                                  "placement": "vertical_left"}, {"refusal": "overlap"}])
    other = replay.__class__(wrong, replay.run)
    assert not other.ok and other.history_figure == "Fig. 17(c)"
    assert [p.split(":")[0] for p in other.problems()] == ["step 0", "step 1"]
    assert "NOT as expected" in other.report()


def test_an_episode_film_shows_each_placement_and_the_finished_wall():
    import matplotlib

    matplotlib.use("Agg")
    from drywall_lab import viz

    run = simulate_episode(episode("film", ("500320", "500100"), ("500300", "500104")), record_fps=8)
    fig = viz.draw_episode_film(run, ncols=2)
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    assert titles == ["step 0: 500320 to 500100", "film: the wall at the end"]
    start = run.steps[0].result.sim_start
    assert start == run.steps[0].sim_time_before
    with pytest.raises(ValueError, match="record_fps"):
        viz.draw_episode_film(simulate_episode(episode("unrecorded", ("500300", "500104"))))


# --- exercises: the checks, with right and wrong answers ----------------------------------------------------
def test_the_servo_gain_check_passes_the_reference_answer():
    from drywall_lab.rc.exercises import check_servo_gains, reference_softer

    check = check_servo_gains(reference_softer, 0.1)
    assert check.passed and check.result.success, str(check)
    assert str(check).startswith("PASSED") and "placed within tolerance" in str(check)


def test_the_servo_gain_check_says_why_servos_too_soft_fail():
    from drywall_lab.rc.exercises import check_servo_gains, reference_softer

    check = check_servo_gains(reference_softer, 0.02)
    assert not check.passed and not check.result.success and str(check).startswith("NOT YET")
    assert "collision" in check.messages[-1] and "lag behind their set points" in check.messages[-1]
    assert "try a stiffer scale" in check.messages[-1]


def test_the_servo_gain_check_finds_wrong_gain_rules_without_simulating(monkeypatch):
    from drywall_lab.rc import exercises
    from drywall_lab.rc.robot import ServoGains

    monkeypatch.setattr(exercises, "RobotCell", None)  # any simulation would fail here
    kv_like_kp = exercises.check_servo_gains(lambda g, s: ServoGains(g.kp * s, g.kv * s, g.force), 0.1)
    assert not kv_like_kp.passed and "square root" in kv_like_kp.messages[0]
    force_too = exercises.check_servo_gains(lambda g, s: ServoGains(g.kp * s, g.kv * s ** 0.5, g.force * s), 0.1)
    assert not force_too.passed and "force limit" in force_too.messages[0]
    kp_wrong = exercises.check_servo_gains(lambda g, s: ServoGains(g.kp, g.kv * s ** 0.5, g.force), 0.1)
    assert not kp_wrong.passed and kp_wrong.messages[0].startswith("kp at scale")
    tuple_back = exercises.check_servo_gains(lambda g, s: (g.kp * s, g.kv, g.force), 0.1)
    assert not tuple_back.passed and "must return a ServoGains" in tuple_back.messages[0]
    raising = exercises.check_servo_gains(lambda g, s: 1 / 0, 0.1)
    assert not raising.passed and "ZeroDivisionError" in raising.messages[0]
    for scale in (1.0, 0.0, -0.1, float("nan"), "0.1", True):
        check = exercises.check_servo_gains(exercises.reference_softer, scale)
        assert not check.passed and check.result is None


@pytest.fixture(scope="module")
def tagger():
    from drywall_lab.nlu import default_tagger

    return default_tagger()


EXERCISE_ANSWER = ["Pick up the full-size drywall and put it on stud 500100 in the bottom row.",
                   "Take the 4 by 6 panel. Put it on the first stud in the top row.",
                   "Pick up the standard panel and put it on stud 500106.",
                   "Grab the drywall from the middle stack and hang it on stud 500109 on the center line."]


def test_the_layout_check_passes_instructions_that_build_the_wall(site, tagger):
    """A one-panel wall (the exercise's own has four: notebook 06 runs the reference answer against it)."""
    from drywall_lab.rc.exercises import check_layout

    wall = site.fresh().install("500320", "500100", "horizontal_bottom")
    check = check_layout(EXERCISE_ANSWER[:1], tagger, target=wall)
    assert check.passed, str(check)
    assert check.run.all_placed and "the simulated robot built the wall" in check.messages[-1]


def test_the_layout_check_says_what_is_wrong_without_running_the_robot(tagger, monkeypatch):
    from drywall_lab.rc import exercises

    monkeypatch.setattr(exercises, "simulate_episode", None)  # the robot must not be run for a wrong answer
    too_few = exercises.check_layout(EXERCISE_ANSWER[:2], tagger)
    assert not too_few.passed and sum(m.startswith("still missing") for m in too_few.messages) == 2
    assert too_few.messages[-1].startswith("the robot was not run")
    upright = exercises.check_layout(["Pick up the full-size drywall and put it on stud 500100."] + EXERCISE_ANSWER[1:],
                                     tagger)
    assert not upright.passed
    assert "not in the wall asked for" in upright.messages[0] and "500100/ID_stud" in upright.messages[0]
    assert upright.messages[1].startswith("instruction 1: refused (overlap)")
    buried = exercises.check_layout(["Take panel 500310 and put it on stud 500106."] + EXERCISE_ANSWER, tagger)
    assert not buried.passed and buried.messages[0].startswith("instruction 0: refused (not_on_top)")
    for bad in ("Pick up the full-size drywall", [""], [3]):
        assert exercises.check_layout(bad, tagger).messages == ["give a list of instructions, each a non-empty string"]


def test_the_layout_check_counts_an_equal_sheet_from_the_same_place(site, tagger):
    """The wall asks for sizes in places, not for sheet numbers: 500310 lying where 500320 was asked is right."""
    from drywall_lab.rc import exercises

    wall = site.fresh().install("500320", "500100", "horizontal_bottom").install("500310", "500106", "vertical_left")
    pieces = {exercises._piece(wall, i) for i in wall.installed}
    swapped = site.fresh().install("500320", "500106", "vertical_left").install("500310", "500100", "horizontal_bottom")
    assert {exercises._piece(swapped, i) for i in swapped.installed} == pieces
    assert exercises.exercise_wall().installed[-1].drywall_id == "500321"
