"""Placement benchmark: every placement of the paper's three layouts, then random feasible commands.

Usage (from the repository root, in the project's virtualenv):

    python benchmarks/placement.py                  # 3 runs; writes benchmarks/results/placement.md
    python benchmarks/placement.py --repeats 5 --random 50 --out /tmp/placement.md
    python benchmarks/placement.py --quick --out /tmp/placement.md   # seconds: checks the script only

Each layout starts from the fresh site and is built step by step as in Figs. 16-18 (the refused
instruction of layout 3 is not a command, so it is not here). The random commands come in
episodes: each starts from the fresh site and carries out 1 to 5 commands drawn (fixed seed)
from ``feasible_commands`` of the site as the robot has left it, so later ones go onto partly
built walls. Every placement is simulated in full and measured on the simulated panel.

The whole benchmark runs ``--repeats`` times (default 3), with the machine's load average read
before and after each run. The physics is deterministic, so success and errors are the same in
every run (the script checks and says so); the real-time factor (simulated seconds per wall-clock
second, planning included) depends on the machine and its load, and the MEDIAN over the runs is
reported. The script writes its results file itself (``--out``): the machine, the date, the exact
command, the load of every run, the figures and every placement. The last line printed is
``success_rate=... max_pos_err_mm=... max_ang_err_deg=... realtime_factor=...``.
"""
from __future__ import annotations

import argparse
import random
import statistics
import sys
import time
from pathlib import Path

import mujoco
import pandas as pd

from drywall_lab.corpus.generator import feasible_commands
from drywall_lab.im import RobotCommand
from drywall_lab.machine import describe_machine, format_load, load_average
from drywall_lab.pipeline import paper_layouts
from drywall_lab.rc import ANGLE_TOLERANCE_DEG, POSITION_TOLERANCE, PlacementResult, RobotCell
sys.path.insert(0, str(Path(__file__).resolve().parent))
from results_file import add_results_options, command_line, results_path, write_results_file  # noqa: E402
from drywall_lab.site import default_site

SEED = 20240517
RESULTS = Path(__file__).resolve().parent / "results" / "placement.md"
#: The figures that depend on the physics only, compared between runs.
PHYSICS = ["drywall_id", "stud_id", "placement", "success", "failure", "pos_err_mm", "ang_err_deg", "slip_mm",
           "base_moves", "unexpected_contacts", "sim_s"]
#: What ``--quick`` shrinks the benchmark to: a check that the script runs, not a measurement.
QUICK = {"layout_steps": 1, "random": 1, "repeats": 2}


def layout_placements(log, steps: int | None = None) -> list[dict]:
    """Every commanded step of the paper's layouts (the first ``steps`` of layout 1 only, when given)."""
    site = default_site()
    rows = []
    layouts = paper_layouts()
    for layout in layouts if steps is None else layouts[:1]:
        cell = RobotCell()
        commands = [e for e in layout["expected"] if "refusal" not in e]
        for expected in commands if steps is None else commands[:steps]:
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


def physics_differences(runs: list[pd.DataFrame]) -> list[str]:
    """Where a later run's physics differs from the first run's (empty when every run agrees)."""
    first = runs[0][PHYSICS].reset_index(drop=True)
    out = []
    for number, frame in enumerate(runs[1:], start=2):
        other = frame[PHYSICS].reset_index(drop=True)
        if other.shape != first.shape:
            out.append(f"run {number}: {len(other)} placements instead of {len(first)}")
            continue
        changed = [c for c in PHYSICS if not first[c].equals(other[c])]
        if changed:
            out.append(f"run {number}: {', '.join(changed)} differ from run 1")
    return out


def one_run(args: argparse.Namespace, log) -> tuple[pd.DataFrame, dict]:
    """The layouts and the random commands once; returns the placements and the run's load and wall time."""
    before, started = load_average(), time.perf_counter()
    layouts = pd.DataFrame(layout_placements(log, QUICK["layout_steps"] if args.quick else None)).assign(part="layouts")
    randoms = pd.DataFrame(random_placements(args.random, args.seed, log)).assign(part="random")
    wall = time.perf_counter() - started
    frame = pd.concat([layouts, randoms], ignore_index=True)
    return frame, {"load_before": before, "load_after": load_average(), "wall_s": wall}


def parse_args(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--random", type=int, default=30, help="at least this many random commands (default 30)")
    parser.add_argument("--seed", type=int, default=SEED)
    parser.add_argument("--repeats", type=int, default=3, metavar="N",
                        help="run the whole benchmark N times and report the median real-time factor (default 3)")
    add_results_options(parser, RESULTS, "one layout step and one random command, twice, in seconds")
    args = parser.parse_args(argv)
    if args.quick:
        args.random, args.repeats = QUICK["random"], QUICK["repeats"]
    args.out = results_path(parser, args, RESULTS)
    if args.repeats < 1 or args.random < 0:
        parser.error(f"--repeats must be at least 1 and --random at least 0, got {args.repeats} and {args.random}")
    return args


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    args = parse_args(argv)
    command = command_line("placement.py", argv)
    machine = describe_machine()
    print(f"machine: {machine.summary()}; MuJoCo {mujoco.__version__}", flush=True)

    lines: list[str] = []

    def log(text: str) -> None:
        print(text, flush=True)
        lines.append(text)

    started = time.perf_counter()
    frames, runs = [], []
    for number in range(1, args.repeats + 1):
        log(f"run {number} of {args.repeats}")
        frame, info = one_run(args, log)
        frames.append(frame)
        runs.append({"run": number, **info, **summarise(frame)})
        log(f"run {number}: load {format_load(info['load_before'])} before, {format_load(info['load_after'])} after; "
            f"realtime_factor={runs[-1]['realtime_factor']:.1f}")
    total_wall = time.perf_counter() - started

    first = frames[0]
    figures = pd.DataFrame({"the paper's layouts": summarise(first[first.part == "layouts"]),
                            "random commands": summarise(first[first.part == "random"]) if args.random else {},
                            "all": summarise(first)})
    everything = pd.concat(frames, ignore_index=True)
    overall = summarise(everything) | {"realtime_factor": statistics.median(r["realtime_factor"] for r in runs)}
    differences = physics_differences(frames)
    line = summary_line(overall)
    print()
    print(figures.to_string(float_format=lambda x: f"{x:.4g}"))
    print(f"tolerances: {POSITION_TOLERANCE * 1000:g} mm, {ANGLE_TOLERANCE_DEG:g} deg; "
          f"{args.repeats} runs in {total_wall:.1f} s; physics "
          + ("identical in every run" if not differences else "DIFFERS: " + "; ".join(differences)))
    print(line)
    write_results(args.out, command=command, machine=machine, args=args, runs=runs, first=first,
                  figures=figures, differences=differences, line=line, total_wall=total_wall)
    print(f"wrote {args.out}")
    return 0 if everything["success"].all() else 1


def write_results(path: Path, *, command: str, machine, args: argparse.Namespace, runs: list[dict],
                  first: pd.DataFrame, figures: pd.DataFrame, differences: list[str], line: str,
                  total_wall: float) -> None:
    """The results file: machine, date, command, every run with its load, the figures, every placement."""
    per_run = pd.DataFrame([{"run": r["run"], "load before (1, 5, 15 min)": format_load(r["load_before"]),
                             "load after": format_load(r["load_after"]), "placements": r["placements"],
                             "sim_s": round(r["sim_s"], 1), "wall_s": round(r["wall_s"], 1),
                             "realtime_factor": round(r["realtime_factor"], 2)} for r in runs])
    text = [
        "# Placement benchmark: results",
        "",
        f"Written by `{command}` (repository root, the project's `.venv`), {machine.date}; "
        f"{args.repeats} runs in {total_wall:.1f} s (scene building included).",
        *(["", "**`--quick`: a check that the script runs, on a few placements; these figures mean nothing.**"]
          if args.quick else []),
        "",
        "## Machine",
        "",
        *machine.markdown_lines(),
        f"- mujoco: {mujoco.__version__}",
        "",
        "## Summary",
        "",
        "Success and errors over every placement of every run; `realtime_factor` is the median over the runs of",
        "simulated seconds per wall-clock second (motion planning included), which depends on the machine and",
        "its load (below; the 1-minute load average counts this benchmark too).",
        "",
        "```",
        line,
        "```",
        "",
        "Physics: " + ("identical in every run (success, errors, slip, base moves, contacts, simulated time)."
                       if not differences else "NOT identical between runs: " + "; ".join(differences) + "."),
        "",
        "## Every run",
        "",
        "```",
        per_run.to_string(index=False),
        "```",
        "",
        "## Run 1 by part",
        "",
        "```",
        figures.to_string(float_format=lambda x: f"{x:.4g}"),
        "```",
        "",
        f"Tolerances: {POSITION_TOLERANCE * 1000:g} mm and {ANGLE_TOLERANCE_DEG:g} deg. Errors are measured on the",
        "simulated panel after the robot has let go and stepped back.",
        "",
        "## Every placement (run 1)",
        "",
        "```",
        first.drop(columns="part").to_string(index=False),
        "```",
        "",
    ]
    write_results_file(path, text)


if __name__ == "__main__":
    sys.exit(main())
