"""Checks for the robot-control exercises of notebooks 05 and 06, in the way of a manipulation course: the
student completes a skeleton or picks a value, the check runs the real simulation and says what is right,
and if not, why not.

- ``check_servo_gains`` (notebook 05): softer joint servos. The student writes how a servo's gains change
  when its stiffness ``kp`` is scaled (the damping ratio kept: ``kv`` scales with the square root) and
  picks a scale at most ``SOFTEST_ASKED``; the check runs one placement with those servos and reports the
  placement error against the tolerances, or what went wrong and why.
- ``check_layout`` (notebook 06): a wall of the student's own, ``EXERCISE_WALL``, said as a worker would.
  The student writes the instructions; the check tags and interprets them, says which panel each one
  puts where (or why it was refused), and once they build the wall, lets the simulated robot build it.

Both say "NOT ATTEMPTED YET: fill in ..." (``ExerciseCheck.not_attempted``) for the notebook's stub, left as it
is; the reference solutions are in ``drywall_lab/course/solutions/ch05.py`` and ``ch06.py``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from drywall_lab.nlu.normalise import normalise
from drywall_lab.exercise import ExerciseCheck, is_unattempted
from drywall_lab.im import ActionHistory, RobotCommand
from drywall_lab.pipeline import WordTagger
from drywall_lab.rc.cell import RobotCell
from drywall_lab.decision import interpret_instruction
from drywall_lab.rc.episode import EpisodeRun, simulate_episode
from drywall_lab.rc.placement import ANGLE_TOLERANCE_DEG, POSITION_TOLERANCE, PlacementResult
from drywall_lab.rc.robot import JOINTS, SERVOS, ServoGains
from drywall_lab.site import Installed, SiteState, default_site


@dataclass
class SimulationCheck(ExerciseCheck):
    """An exercise check (``drywall_lab.exercise.ExerciseCheck``) that also keeps what it simulated."""

    result: PlacementResult | None = None  #: the placement the check simulated (servo gains)
    run: EpisodeRun | None = None  #: the episode the check simulated (layout)


# --- notebook 05: servo gains -------------------------------------------------------------------------------
#: The exercise asks for servos at most this stiff (a fraction of ``SERVOS``' kp).
SOFTEST_ASKED = 0.2
#: Where the exercises' reference solutions are (``drywall_lab.course.solutions``; not imported here: the library
#: imports nothing of the course).
SOLUTIONS = {5: "drywall_lab/course/solutions/ch05.py", 6: "drywall_lab/course/solutions/ch06.py"}


def reference_softer(gains: ServoGains, kp_scale: float) -> ServoGains:
    """The reference answer: ``kp`` scaled, ``kv`` by its square root (for a joint of inertia J the damping
    ratio is kv / (2 sqrt(kp J)), so it stays the same), the drive's force limit unchanged."""
    return ServoGains(kp=gains.kp * kp_scale, kv=gains.kv * math.sqrt(kp_scale), force=gains.force)


def _gain_problems(softer: Callable[[ServoGains, float], ServoGains]) -> list[str]:
    """What is wrong with the student's ``softer``, tried on every joint at two scales."""
    problems = []
    for scale in (0.25, 0.04):
        for name in JOINTS:
            given, want = SERVOS[name], reference_softer(SERVOS[name], scale)
            try:
                got = softer(given, scale)
            except Exception as e:  # the student's code: report, never crash the check
                return [f"softer({name}'s gains, {scale}) raised {type(e).__name__}: {e}"]
            if not isinstance(got, ServoGains):
                return [f"softer(...) must return a ServoGains(kp=..., kv=..., force=...), not {type(got).__name__}"]
            if not math.isclose(got.kp, want.kp, rel_tol=1e-9):
                problems.append(f"kp at scale {scale}: expected {want.kp:.4g} ({name}'s kp times the scale), got {got.kp:.4g}")
            if not math.isclose(got.kv, want.kv, rel_tol=1e-6):
                ratio = got.kv / given.kv if given.kv else float("nan")
                problems.append(f"kv at scale {scale}: expected {want.kv:.4g}, got {got.kv:.4g} ({ratio:.3g} times {name}'s "
                                f"kv): the damping ratio kv / (2 sqrt(kp J)) stays the same only if kv scales with the "
                                f"square root of the kp scale, here {math.sqrt(scale):g}")
            if not math.isclose(got.force, given.force, rel_tol=1e-9):
                problems.append(f"force at scale {scale}: the drive's force limit ({given.force:g}) is the motor's, "
                                f"not the controller's: leave it as it is (got {got.force:g})")
            if problems:
                return problems[:3]
    return problems


def explain_failure(result: PlacementResult) -> str:
    """Why a placement failed, in words, with the measurements that show it."""
    tracking = result.trace.largest_tracking_error if result.trace.q else np.zeros(len(JOINTS))
    lag = (f"the largest tracking errors were {tracking[0] * 1000:.1f} mm on the rail and "
           f"{math.degrees(float(np.max(tracking[1:]))):.2f} deg on the arm")
    code = (result.failure or "").split(":")[0]
    if code == "collision":
        hits = "; ".join(str(e) for e in result.unexpected_contacts[:2])
        return (f"collision: {hits}. Soft servos lag behind their set points and sag under the load, so the "
                f"panel or the arm leaves the planned path and uses up its clearance ({lag})")
    if code == "off_pose":
        return (f"off_pose: the panel was fastened {result.position_error_mm:.2f} mm and {result.angle_error_deg:.3f} "
                f"deg from its pose (tolerance {POSITION_TOLERANCE * 1000:g} mm, {ANGLE_TOLERANCE_DEG:g} deg): the "
                f"servos had not brought it onto its pose when the robot let go ({lag})")
    if code == "slipped":
        return f"slipped: the panel slid {result.slip_mm:.2f} mm on the pad while it was carried ({lag})"
    return f"{result.failure} ({lag})"


def check_servo_gains(softer: Callable[[ServoGains, float], ServoGains], kp_scale: float,
                      command: RobotCommand | None = None) -> SimulationCheck:
    """Notebook 05's exercise: ``softer(gains, scale)`` as the student wrote it, and the student's scale.

    Checks ``softer`` against the damping rule (``reference_softer``) on every joint, then the scale
    (a number in (0, ``SOFTEST_ASKED``]), then runs ``command`` (layout 1's first: 500320 on 500100) with
    every servo made softer by ``kp_scale`` and says whether the placement is within tolerance, and if
    not, why not.

    The notebook's stub is "not attempted yet": ``softer`` that raises ``NotImplementedError`` (or whose body is
    still ``...``), ``kp_scale`` left as ``...`` (or ``None``). A ``softer`` already written is checked even
    while the scale is not chosen yet; nothing is simulated until both are there.
    """
    softer_stub = is_unattempted(softer, SERVOS[JOINTS[0]], 0.25, none=True)
    scale_stub = is_unattempted(kp_scale, none=True)
    if softer_stub or scale_stub:
        scale_asked = f"KP_SCALE, a kp scale above 0 and at most {SOFTEST_ASKED:g}"
        if softer_stub:
            what = "softer(gains, kp_scale): kp scaled, kv so that the damping ratio is kept, the force limit as it is"
            return SimulationCheck.not_attempted(what + (f"; and {scale_asked}" if scale_stub else ""), SOLUTIONS[5])
        problems = _gain_problems(softer)
        if problems:
            return SimulationCheck(False, problems + [f"then fill in {scale_asked}"])
        check = SimulationCheck.not_attempted(scale_asked, SOLUTIONS[5])
        check.messages.insert(1, "softer() is right: it keeps every servo's damping ratio and force limit")
        return check
    if isinstance(kp_scale, bool) or not isinstance(kp_scale, (int, float)) or not math.isfinite(kp_scale):
        return SimulationCheck(False, [f"the scale must be a number, not {kp_scale!r}"])
    if not 0 < kp_scale <= SOFTEST_ASKED:
        return SimulationCheck(False, [f"the exercise asks for softer servos: a kp scale above 0 and at most "
                                     f"{SOFTEST_ASKED:g}, not {kp_scale:g}"])
    problems = _gain_problems(softer)
    if problems:
        return SimulationCheck(False, problems)
    site = default_site()
    command = command or RobotCommand.build(site, "500320", "500100", "vertical_left")
    cell = RobotCell(servo_gains={name: softer(SERVOS[name], kp_scale) for name in JOINTS})
    result = cell.execute(command)
    messages = [f"softer() keeps every servo's damping ratio and force limit; kp scale {kp_scale:g}"]
    if result.success:
        tracking = result.trace.largest_tracking_error
        messages.append(f"placed within tolerance: {result.position_error_mm:.2f} mm (of {POSITION_TOLERANCE * 1000:g}) "
                        f"and {result.angle_error_deg:.3f} deg (of {ANGLE_TOLERANCE_DEG:g}), nothing hit; largest "
                        f"tracking errors {tracking[0] * 1000:.1f} mm on the rail, "
                        f"{math.degrees(float(np.max(tracking[1:]))):.2f} deg on the arm")
    else:
        messages.append(f"not placed within tolerance: {explain_failure(result)}; try a stiffer scale")
    return SimulationCheck(result.success, messages, result=result)


# --- notebook 06: a wall of your own -------------------------------------------------------------------------
#: The exercise's wall (in order of one way to build it): a standard sheet lying in the bottom row and a
#: 4 x 6 ft above it at the left end, a standard sheet standing on stud 500106's left line and a 2 x 8 ft on
#: stud 500109's centre line.
EXERCISE_WALL = (("500320", "500100", "horizontal_bottom"), ("500322", "500100", "horizontal_top"),
                 ("500310", "500106", "vertical_left"), ("500321", "500109", "vertical_middle"))


def exercise_wall() -> SiteState:
    """The wall ``EXERCISE_WALL`` asks for, built on the fresh site."""
    return default_site().fresh().replay(
        {"drywall_id": d, "stud_id": s, "placement": p} for d, s, p in EXERCISE_WALL)


def _piece(state: SiteState, item: Installed) -> tuple:
    """What the wall shows of an installed panel: where it is and its size (not which of equal sheets)."""
    panel = state.site.panel(item.drywall_id)
    r = item.rect
    return tuple(round(v, 4) for v in (r.x_left, r.x_right, r.z_bottom, r.z_top, panel.w, panel.l))


def _describe(state: SiteState, item: Installed) -> str:
    panel = state.site.panel(item.drywall_id)
    return (f"a {panel.w_ft:g} x {panel.l_ft:g} ft panel on stud {item.stud_id}, {item.placement.described} "
            f"(x {item.rect.x_left:.2f}..{item.rect.x_right:.2f} m)")


def check_layout(instructions: Sequence[str], tagger: WordTagger, target: SiteState | None = None) -> SimulationCheck:
    """Notebook 06's exercise: do the student's ``instructions`` build the ``target`` wall (``exercise_wall()``)?

    Each instruction is tagged and interpreted in order, as ``run`` would; every command is compared with
    the target wall (a panel of the same size in the same place counts, whichever of equal sheets it is).
    Only when the commands build exactly the target does the simulated robot carry the episode out; the
    check passes when it places every panel within tolerance. The notebook's stub, ``[...]`` (or ``...``,
    ``None``), is "not attempted yet"; nothing is tagged or simulated then.
    """
    if is_unattempted(instructions, none=True):
        return SimulationCheck.not_attempted("my_instructions: one instruction per panel of the wall, in an order "
                                             "the stacks allow", SOLUTIONS[6])
    target = target if target is not None else exercise_wall()
    if isinstance(instructions, str) or not all(isinstance(i, str) and i.strip() for i in instructions):
        placeholder = not isinstance(instructions, str) and any(i is Ellipsis for i in instructions)
        return SimulationCheck(False, ["give a list of instructions, each a non-empty string"]
                               + (["replace every ... with an instruction of your own"] if placeholder else []))
    instructions = list(instructions)
    wanted = {_piece(target, i): i for i in target.installed}
    history = ActionHistory(target.site)
    messages, wrong = [], False
    for k, text in enumerate(instructions):
        result = interpret_instruction(list(normalise(text).words), tagger, history)
        heard = " ".join(f"{w}/{t}" if t != "O" else w for w, t in zip(result.words, result.tags))
        if result.command is not None:
            history.record(result.command)
        else:
            wrong = True
            messages.append(f"instruction {k}: refused ({result.refusal.reason}): {result.refusal.message} "
                            f"The tagger read: {heard}")
            continue
        placed = history.state.installed[-1]
        if _piece(history.state, placed) in wanted:
            messages.append(f"instruction {k}: {_describe(history.state, placed)}: part of the wall")
        else:
            wrong = True
            messages.append(f"instruction {k}: {_describe(history.state, placed)}: not in the wall asked for. "
                            f"The tagger read: {heard}")
    built = {_piece(history.state, i) for i in history.state.installed}
    missing = [wanted[p] for p in wanted if p not in built]
    if missing:
        wrong = True
        messages += [f"still missing: {_describe(target, i)}" for i in missing]
    if wrong:
        messages.append("the robot was not run: the instructions do not build the wall yet")
        return SimulationCheck(False, messages)
    run = simulate_episode({"id": "your wall", "instructions": instructions}, tagger)
    failed = [s for s in run.steps if s.status != "placed"]
    for s in failed:
        reason = s.result.failure if s.result is not None else "not carried out"
        messages.append(f"instruction {s.step}: the robot did not place it ({reason})")
    if not failed:
        worst = max(r.position_error_mm for r in run.placements)
        messages.append(f"the simulated robot built the wall: {len(run.placements)} panels, every one within "
                        f"tolerance (largest error {worst:.2f} mm of {POSITION_TOLERANCE * 1000:g} mm), nothing hit")
    return SimulationCheck(not failed, messages, run=run)
