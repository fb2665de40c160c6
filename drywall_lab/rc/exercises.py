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
- ``check_ik_step`` (notebook 05, from scratch): one damped least-squares step of differential inverse
  kinematics, compared with the closed form and tried on the robot's own Jacobian (``mujoco.mj_jacSite``).
- ``check_panel_rect`` (notebook 06, from scratch): where a panel covers the wall from its stud and placement
  (the paper's Fig. 6), compared with ``Site.rect`` on every panel, stud and placement.

All say "NOT ATTEMPTED YET: fill in ..." (``ExerciseCheck.not_attempted``) for the notebook's stub, left as it
is; the reference solutions are in ``drywall_lab/course/solutions/ch05.py`` and ``ch06.py``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from drywall_lab.nlu.normalise import normalise
from drywall_lab.exercise import ExerciseCheck, call_student, is_unattempted
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


# --- notebook 05, from scratch: one step of differential inverse kinematics ------------------------------------
#: The worked example's target: this far (m) from where the TCP is in the robot's resting posture (``ArmIK.home``).
IK_EXAMPLE_OFFSET = (0.10, -0.05, 0.08)


@dataclass
class IKExample:
    """One differential-IK step's ingredients on the project's robot (``robot_mjcf``, alone: rail and arm).

    ``jacobian`` is the TCP's position Jacobian (3 x 7, ``mujoco.mj_jacSite``) at joint values ``q``,
    ``error`` the target's position minus the TCP's (m).
    """

    model: "mujoco.MjModel"
    q: np.ndarray
    target: np.ndarray
    tcp: np.ndarray
    jacobian: np.ndarray
    error: np.ndarray


def tcp_position_and_jacobian(model: "mujoco.MjModel", q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The TCP site's world position and its 3 x nv position Jacobian at joint values ``q``: column j is how
    fast the TCP moves when joint j moves (m per m on the rail, m per rad on the arm)."""
    import mujoco

    from drywall_lab.rc.robot import TCP_SITE

    data = mujoco.MjData(model)
    data.qpos[:] = q
    mujoco.mj_forward(model, data)
    site = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, TCP_SITE)
    jacp = np.zeros((3, model.nv))
    mujoco.mj_jacSite(model, data, jacp, None, site)
    return data.site_xpos[site].copy(), jacp


def ik_example(offset: Sequence[float] = IK_EXAMPLE_OFFSET) -> IKExample:
    """The notebook's worked example: the robot at rest (``ArmIK.home``), a target ``offset`` from its TCP."""
    import mujoco

    from drywall_lab.rc.robot import ArmIK, robot_mjcf

    model = mujoco.MjModel.from_xml_string(robot_mjcf())
    q = ArmIK().home.copy()
    tcp, jacobian = tcp_position_and_jacobian(model, q)
    target = tcp + np.asarray(offset, dtype=float)
    return IKExample(model, q, target, tcp, jacobian, target - tcp)


def reference_ik_step(jacobian: np.ndarray, error: np.ndarray, damping: float) -> np.ndarray:
    """Damped least squares: dq = J^T (J J^T + damping^2 I)^-1 e, the dq that minimises
    |J dq - e|^2 + damping^2 |dq|^2 (finite even where J J^T is singular)."""
    J, e = np.asarray(jacobian, dtype=float), np.asarray(error, dtype=float)
    return J.T @ np.linalg.solve(J @ J.T + damping**2 * np.eye(J.shape[0]), e)


def ik_iterations(example: IKExample, step: Callable[[np.ndarray, np.ndarray, float], np.ndarray],
                  damping: float = 0.05, step_size: float = 0.5, iterations: int = 8):
    """``step`` repeated from the example's posture: each time the Jacobian and the error are taken anew and
    ``step_size`` times the step is applied with ``mujoco.mj_integratePos``. A pandas DataFrame: iteration,
    the TCP's distance from the target (mm) and the size of the step (rad, the rail's m counted alike)."""
    import mujoco
    import pandas as pd

    q = example.q.copy()
    rows = []
    for k in range(iterations + 1):
        tcp, J = tcp_position_and_jacobian(example.model, q)
        e = example.target - tcp
        dq = np.asarray(step(J, e, damping), dtype=float)
        rows.append({"iteration": k, "distance to target (mm)": round(float(np.linalg.norm(e)) * 1000, 3),
                     "|dq|": round(float(np.linalg.norm(dq)), 5)})
        mujoco.mj_integratePos(example.model, q, dq, step_size)
    return pd.DataFrame(rows)


def _ik_slips(J: np.ndarray, e: np.ndarray, damping: float) -> dict[str, np.ndarray | None]:
    """What the usual slips compute, where they compute anything (None where the shapes do not fit)."""
    slips: dict[str, np.ndarray | None] = {}
    I = np.eye(J.shape[0])
    with np.errstate(all="ignore"):
        slips["sign"] = -reference_ik_step(J, e, damping)
        slips["lambda"] = J.T @ np.linalg.solve(J @ J.T + damping * I, e)
        try:
            slips["undamped"] = J.T @ np.linalg.solve(J @ J.T, e)
        except np.linalg.LinAlgError:
            slips["undamped"] = None
        slips["pinv"] = np.linalg.pinv(J) @ e
        slips["transpose"] = (J @ np.linalg.solve(J @ J.T + damping**2 * I, e)) if J.shape[0] == J.shape[1] else None
        slips["plain transpose"] = J.T @ e
    return slips


_IK_SLIP_MESSAGES = {
    "sign": "your step points the wrong way (it is minus the right one): the error is the target's position minus "
            "the TCP's, e = p_target - p(q), and the step follows it: dq = J^T (J J^T + lambda^2 I)^-1 e",
    "lambda": "the damping enters squared: J J^T + lambda^2 I, not J J^T + lambda I (lambda is in the units of J, "
              "lambda^2 in those of J J^T)",
    "undamped": "your step has no damping: J^T (J J^T)^-1 e is right only where J J^T is well invertible; add "
                "lambda^2 I to J J^T",
    "pinv": "that is the pseudo-inverse step pinv(J) e, with no damping: add lambda^2 I to J J^T",
    "transpose": "J where J^T belongs: dq = J^T (J J^T + lambda^2 I)^-1 e (J maps joint steps to TCP motion, J^T "
                 "maps TCP errors back to joint steps)",
    "plain transpose": "that is the Jacobian-transpose step J^T e: the damped least-squares step also divides by "
                       "(J J^T + lambda^2 I)",
}


def _ik_cases(example: IKExample, rng: np.random.Generator) -> list[tuple[str, np.ndarray, np.ndarray, float]]:
    """The check's cases: the worked example, random Jacobians (3 x 7, 3 x 3, 6 x 7), a singular one."""
    cases = [("the worked example (the robot's TCP Jacobian at rest)", example.jacobian, example.error, 0.05)]
    for shape, damping in (((3, 7), 0.5), ((3, 3), 0.3), ((6, 7), 0.2), ((3, 7), 0.05)):
        cases.append((f"a random {shape[0]} x {shape[1]} Jacobian, damping {damping:g}", rng.normal(size=shape),
                      rng.normal(size=shape[0]) * 0.1, damping))
    row = rng.normal(size=7)
    singular = np.array([row, 2 * row, rng.normal(size=7)])  # rank 2: J J^T cannot be inverted
    cases.append(("a singular 3 x 7 Jacobian (two rows in proportion, as at a stretched-out arm), damping 0.1",
                  singular, rng.normal(size=3) * 0.1, 0.1))
    return cases


def check_ik_step(ik_step: Callable[[np.ndarray, np.ndarray, float], np.ndarray]) -> ExerciseCheck:
    """Notebook 05's from-scratch exercise: ``ik_step(jacobian, error, damping)`` -> dq, one damped
    least-squares step of differential IK.

    Compared with the closed form J^T (J J^T + damping^2 I)^-1 e on the worked example, random Jacobians
    (wide, square, six rows) and a singular one, with a message for each usual slip (the sign of the error,
    J for J^T, no damping, lambda for lambda^2); then applied on the real robot (``ik_iterations``): the TCP
    must come nearer its target. The notebook's stub (raises ``NotImplementedError``) is "not attempted yet".
    """
    example = ik_example()
    cases = _ik_cases(example, np.random.default_rng(5))
    if is_unattempted(ik_step, cases[0][1], cases[0][2], cases[0][3], none=True):
        return ExerciseCheck.not_attempted("ik_step(jacobian, error, damping): dq = J^T (J J^T + damping^2 I)^-1 e",
                                           SOLUTIONS[5])
    messages = []
    for what, J, e, damping in cases:
        got, error = call_student(ik_step, J.copy(), e.copy(), damping)
        if error:
            hint = (" (the undamped J J^T of a singular Jacobian cannot be inverted: add damping^2 I)"
                    if "singular" in what.lower() or "Singular" in error else "")
            if "broadcast" in error:
                hint = f" (J is {J.shape[0]} x {J.shape[1]}: the identity is {J.shape[0]} x {J.shape[0]}, np.eye(J.shape[0]))"
            elif "shape" in error or "mismatch" in error or "aligned" in error:
                hint = (f" (J is {J.shape[0]} x {J.shape[1]}: dq has one entry per joint, {J.shape[1]}; J where J^T "
                        f"belongs does not fit: dq = J^T (J J^T + damping^2 I)^-1 e)")
            return ExerciseCheck(False, [f"on {what}: ik_step raised {error}{hint}"])
        try:
            got = np.asarray(got, dtype=float)
        except (TypeError, ValueError):
            return ExerciseCheck(False, [f"on {what}: ik_step must return an array of joint steps, not {type(got).__name__}"])
        if got.shape != (J.shape[1],):
            return ExerciseCheck(False, [f"on {what}: dq must have one entry per joint, shape ({J.shape[1]},), not "
                                         f"{got.shape}: J is {J.shape[0]} x {J.shape[1]}, so dq = J^T (...) e"])
        if not np.all(np.isfinite(got)):
            return ExerciseCheck(False, [f"on {what}: your step is not finite ({got}): " + _IK_SLIP_MESSAGES["undamped"]])
        want = reference_ik_step(J, e, damping)
        if np.allclose(got, want, rtol=1e-6, atol=1e-9):
            continue
        for slip, value in _ik_slips(J, e, damping).items():
            if value is not None and np.all(np.isfinite(value)) and np.allclose(got, value, rtol=1e-6, atol=1e-9):
                return ExerciseCheck(False, [f"on {what}: {_IK_SLIP_MESSAGES[slip]}"])
        return ExerciseCheck(False, [f"on {what}: expected dq = {np.round(want, 5)}, got {np.round(got, 5)} "
                                     f"(dq = J^T (J J^T + damping^2 I)^-1 e)"])
    messages.append(f"ik_step matches J^T (J J^T + damping^2 I)^-1 e on {len(cases)} cases, the singular one included")
    table = ik_iterations(example, ik_step, iterations=3)
    distances = table["distance to target (mm)"].tolist()
    if not distances[-1] < distances[0]:
        return ExerciseCheck(False, messages + [f"on the robot the TCP did not come nearer its target: {distances} mm"])
    messages.append(f"on the robot, three half steps bring the TCP from {distances[0]:.1f} mm to {distances[-1]:.2f} "
                    f"mm of its target")
    return ExerciseCheck(True, messages)


# --- notebook 06, from scratch: where a panel covers the wall ---------------------------------------------------
#: The worked example: the first instruction of the paper's layout 1 (a standard sheet on stud 500100's left line).
RECT_EXAMPLE = ("500320", "500100", "vertical_left")


def _rect_slips(panel, stud, placement) -> dict[str, tuple[float, float, float, float]]:
    """What the usual slips compute for one case: (x_left, x_right, z_bottom, z_top)."""
    from drywall_lab.site import WALL_HEIGHT, Placement

    placement = Placement(placement)
    left, centre = stud.x_left_line, stud.x_center
    x = centre if placement is Placement.VERTICAL_MIDDLE else left
    slips = {}
    if placement is Placement.VERTICAL_MIDDLE:
        slips["middle on the left line"] = (left, left + panel.w, 0.0, panel.l)
    else:
        slips["left line at the centre"] = ((centre, centre + panel.w, 0.0, panel.l) if placement.vertical
                                            else (centre, centre + panel.l, *(
                                                (WALL_HEIGHT - panel.w, WALL_HEIGHT)
                                                if placement is Placement.HORIZONTAL_TOP else (0.0, panel.w))))
    if placement.vertical:
        slips["sides swapped"] = (x, x + panel.l, 0.0, panel.w)
    else:
        top = placement is Placement.HORIZONTAL_TOP
        slips["sides swapped"] = (x, x + panel.w, *((WALL_HEIGHT - panel.l, WALL_HEIGHT) if top else (0.0, panel.l)))
        slips["rows swapped"] = (x, x + panel.l, *((0.0, panel.w) if top else (WALL_HEIGHT - panel.w, WALL_HEIGHT)))
        if top:
            slips["top row from the floor"] = (x, x + panel.l, panel.w, 2 * panel.w)
    return slips


_RECT_SLIP_MESSAGES = {
    "middle on the left line": "vertical_middle (Vr_md) puts the panel's left edge on the stud's centre line "
                               "(stud.x_center), not on its left line",
    "left line at the centre": "every placement but vertical_middle puts the panel's left edge on the stud's left "
                               "line (stud.x_left_line), not on its centre line",
    "sides swapped": "a vertical panel stands on its short side (w across, l up); a horizontal one lies on its long "
                     "side (l across, w up): the two sides are swapped",
    "rows swapped": "horizontal_top is the top row (its top edge at the wall's height, WALL_HEIGHT), "
                    "horizontal_bottom the bottom row (its bottom edge on the floor, z = 0): the rows are swapped",
    "top row from the floor": "the top row hangs from the wall's top: z_top = WALL_HEIGHT, z_bottom = WALL_HEIGHT - w",
}


def _rect_tuple(rect) -> tuple[float, float, float, float] | None:
    try:
        return tuple(float(getattr(rect, k)) for k in ("x_left", "x_right", "z_bottom", "z_top"))
    except (AttributeError, TypeError, ValueError):
        return None


def check_panel_rect(panel_rect: Callable, site=None) -> ExerciseCheck:
    """Notebook 06's from-scratch exercise: ``panel_rect(panel, stud, placement)`` -> ``Rect``, where a panel put
    on a stud covers the wall (the paper's Fig. 6: the four placements).

    Compared with the site's own ``Site.rect`` on the worked example (``RECT_EXAMPLE``), then on every panel, stud
    and placement of the site (enumeration: 9 x 13 x 4 cases), with a message for each usual slip (the centre
    line and the left line, the panel's sides, the two rows). The notebook's stub is "not attempted yet".
    """
    from drywall_lab.site import Placement

    site = site if site is not None else default_site()
    d, s, p = RECT_EXAMPLE
    example = (site.panel(d), site.stud(s), Placement(p))
    if is_unattempted(panel_rect, *example, none=True):
        return ExerciseCheck.not_attempted("panel_rect(panel, stud, placement): the Rect the panel covers on the "
                                           "wall", SOLUTIONS[6])
    cases = [example] + [(panel, stud, placement) for placement in Placement for panel in site.panels
                         for stud in site.studs]
    for k, (panel, stud, placement) in enumerate(cases):
        what = (f"{'the worked example: ' if k == 0 else ''}panel {panel.drywall_id} ({panel.w_ft:g} x "
                f"{panel.l_ft:g} ft) on stud {stud.stud_id}, {placement.value}")
        got, error = call_student(panel_rect, panel, stud, placement)
        if error:
            return ExerciseCheck(False, [f"{what}: panel_rect raised {error}"])
        got_t, want_t = _rect_tuple(got), _rect_tuple(site.rect(panel, stud, placement))
        if got_t is None:
            return ExerciseCheck(False, [f"{what}: panel_rect must return a Rect(x_left, x_right, z_bottom, z_top), "
                                         f"not {type(got).__name__}"])
        if np.allclose(got_t, want_t, atol=1e-9):
            continue
        for slip, value in _rect_slips(panel, stud, placement).items():
            if np.allclose(got_t, value, atol=1e-9):
                return ExerciseCheck(False, [f"{what}: {_RECT_SLIP_MESSAGES[slip]}"])
        words = ("x_left", "x_right", "z_bottom", "z_top")
        wrong = [f"{n} {g:.4f} (expected {w:.4f})" for n, g, w in zip(words, got_t, want_t) if abs(g - w) > 1e-9]
        return ExerciseCheck(False, [f"{what}: " + ", ".join(wrong) + " m"])
    return ExerciseCheck(True, [f"panel_rect agrees with the site's own Site.rect on the worked example and on all "
                                f"{len(cases) - 1} cases: every panel, every stud, the four placements"])
