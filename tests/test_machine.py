"""The machine a figure was measured on (drywall_lab.machine), and the timing scripts that record it.

``benchmarks/latency.py`` and ``benchmarks/placement.py`` run ``--quick`` here (seconds, figures that
mean nothing) to check that they write their own results file with the machine, the date, the exact
command and the load average before and after every run, and report the median over the runs.
"""
from __future__ import annotations

import datetime as dt
import os
import re
import statistics
import time
from pathlib import Path
from types import ModuleType

import numpy as np
import pandas as pd
import pytest
from conftest import load_benchmark
import torch
from hypothesis import given, settings
from hypothesis import strategies as st

from drywall_lab.machine import (
    Machine,
    cpu_model,
    cpu_model_from_cpuinfo,
    describe_machine,
    format_load,
    load_average,
)

REPO = Path(__file__).resolve().parent.parent
README = REPO / "README.md"
#: Where the benchmarks' findings are told, quoting their results files.
RESULTS_PAGE = REPO / "benchmarks" / "README.md"

X86 = """processor\t: 0
vendor_id\t: AuthenticAMD
model name\t: AMD EPYC 7B13
cpu MHz\t\t: 2450.000

processor\t: 1
model name\t: AMD EPYC 7B13
"""
ARM = """processor\t: 0
BogoMIPS\t: 108.00
Features\t: fp asimd

Hardware\t: BCM2835
Model\t\t: Raspberry Pi 4 Model B Rev 1.4
"""


def load_script(name: str) -> ModuleType:
    """A script of ``benchmarks/`` imported as a module (it is not a package)."""
    return load_benchmark(name)


# --- drywall_lab.machine ------------------------------------------------------------------------
def test_cpu_model_from_cpuinfo() -> None:
    assert cpu_model_from_cpuinfo(X86) == "AMD EPYC 7B13"
    assert cpu_model_from_cpuinfo(ARM) == "BCM2835"
    assert cpu_model_from_cpuinfo("") is None
    assert cpu_model_from_cpuinfo("processor : 0\nmodel name :\n") is None  # an empty value is no model


@settings(max_examples=60, deadline=None)
@given(name=st.text(st.characters(blacklist_categories=("Cc", "Cs", "Zl", "Zp")), min_size=1, max_size=40)
       .filter(lambda s: s.strip() != ""),
       before=st.lists(st.sampled_from(["processor : 3", "flags : fpu vme", "cpu MHz : 1.0", ""]), max_size=4))
def test_model_name_is_found_wherever_it_is(name: str, before: list[str]) -> None:
    text = "\n".join([*before, f"model name\t: {name}", "model name\t: another CPU"])
    assert cpu_model_from_cpuinfo(text) == name.strip()


def test_cpu_model_without_cpuinfo_still_names_something(tmp_path) -> None:
    assert cpu_model(tmp_path / "no-such-file")  # platform's answer, never empty
    (tmp_path / "cpuinfo").write_text(X86)
    assert cpu_model(tmp_path / "cpuinfo") == "AMD EPYC 7B13"


def test_format_load() -> None:
    assert format_load((0.5, 1.25, 2.0)) == "0.50, 1.25, 2.00 (1, 5, 15 min)"
    assert format_load(None) == "not available"


def test_load_average_is_the_systems(monkeypatch) -> None:
    monkeypatch.setattr(os, "getloadavg", lambda: (3.0, 2.0, 1.0))
    assert load_average() == (3.0, 2.0, 1.0)
    monkeypatch.delattr(os, "getloadavg")  # as on Windows
    assert load_average() is None


def test_describe_machine_now() -> None:
    before = dt.datetime.now(dt.timezone.utc).replace(microsecond=0)
    m = describe_machine()
    when = dt.datetime.strptime(m.date, "%Y-%m-%d %H:%M:%S UTC").replace(tzinfo=dt.timezone.utc)
    assert before <= when <= dt.datetime.now(dt.timezone.utc)
    assert m.logical_cores == os.cpu_count()
    assert m.cpu == cpu_model()
    assert m.torch == torch.__version__ and m.torch_threads == torch.get_num_threads()
    assert (m.gpu is None) == (not torch.cuda.is_available())
    assert m.load_average is not None and len(m.load_average) == 3 and min(m.load_average) >= 0
    summary = m.summary()
    assert m.cpu in summary and f"{m.logical_cores} logical cores" in summary
    assert f"load average {format_load(m.load_average)}" in summary and m.date in summary
    lines = m.markdown_lines()
    assert f"- cpu: {m.cpu}" in lines and f"- date: {m.date}" in lines
    assert f"- load average: {format_load(m.load_average)}" in lines


def test_describe_machine_at_a_given_time_is_in_utc() -> None:
    plus_two = dt.timezone(dt.timedelta(hours=2))
    assert describe_machine(dt.datetime(2026, 3, 1, 12, 30, 5, tzinfo=plus_two)).date == "2026-03-01 10:30:05 UTC"


def test_a_machine_without_gpu_or_torch_says_so() -> None:
    m = Machine(cpu="X", logical_cores=1, gpu=None, torch=None, torch_threads=None, python="3.11.7",
                platform="p", load_average=None, date="2026-01-01 00:00:00 UTC")
    assert m.summary() == ("X, 1 logical cores, no GPU, no torch, Python 3.11.7; load average not available; "
                           "2026-01-01 00:00:00 UTC")
    assert "- gpu: none" in m.markdown_lines() and "- torch threads: None" not in m.markdown_lines()


def test_cpuinfo_is_read_in_one_place() -> None:
    """The experiment and both timing scripts use drywall_lab.machine, not their own /proc/cpuinfo parser."""
    sources = [*sorted((REPO / "drywall_lab").rglob("*.py")), *sorted((REPO / "benchmarks").glob("*.py"))]
    readers = [p.relative_to(REPO).as_posix() for p in sources if "cpuinfo" in p.read_text(encoding="utf-8")]
    assert readers == ["drywall_lab/machine.py"]
    for script in ("benchmarks/latency.py", "benchmarks/placement.py", "benchmarks/bert_settings.py",
                   "drywall_lab/nlu/experiments.py"):
        assert "describe_machine" in (REPO / script).read_text(encoding="utf-8"), script


# --- the timing scripts -------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["latency", "placement"])
def test_timing_script_help(name: str, capsys) -> None:
    with pytest.raises(SystemExit) as stop:
        load_script(name).main(["--help"])
    assert stop.value.code == 0
    out = capsys.readouterr().out
    for option in ("--repeats", "--out", "--quick"):
        assert option in out


@pytest.mark.parametrize("name, argv", [("latency", []), ("placement", []), ("bert_settings", []), ("decision", []),
                                        ("field_seeds", [])])
def test_quick_figures_never_replace_the_recorded_results(name: str, argv: list[str], capsys) -> None:
    """Every benchmark with ``--quick`` (benchmarks/results_file.py) stops before anything runs unless given its own
    ``--out``, and its help names the recorded results file it would otherwise write."""
    script = load_script(name)
    with pytest.raises(SystemExit) as stop:
        script.main(["--quick", *argv])
    assert stop.value.code == 2
    assert "give --out FILE" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        script.main(["--help"])
    assert f"benchmarks/results/{name}.md" in " ".join(capsys.readouterr().out.split())


@pytest.mark.parametrize("name", ["latency", "placement"])
def test_repeats_must_be_positive(name: str, capsys) -> None:
    with pytest.raises(SystemExit) as stop:
        load_script(name).main(["--repeats", "0", "--out", "unused.md"])
    assert stop.value.code == 2
    assert "--repeats" in capsys.readouterr().err


def test_latency_reports_the_median_of_the_runs() -> None:
    latency = load_script("latency")
    runs = pd.DataFrame([{"run": r, "model": m, "single_p50_ms": v, "batched_p50_ms": 2 * v}
                         for r, values in enumerate([(1.0, 9.0), (5.0, 7.0), (2.0, 30.0)], start=1)
                         for m, v in zip(("lstm", "minilm"), values)])
    medians = latency.median_table(runs)
    assert medians.loc["lstm", "single_p50_ms"] == 2.0 and medians.loc["minilm", "single_p50_ms"] == 9.0
    assert medians.loc["minilm", "batched_p50_ms"] == 18.0
    assert latency.summary_line(medians) == "lstm_p50_ms=2.00 minilm_p50_ms=9.00"
    assert latency.target_lines(medians) == ["target lstm single p50 < 2 ms: MISSED (2.00 ms, median over the runs)",
                                            "target minilm single p50 < 10 ms: met (9.00 ms, median over the runs)"]
    decided = pd.concat([medians, pd.DataFrame({"single_p50_ms": [4.5]}, index=["lstm_decided"])])
    assert latency.target_lines(decided)[-1] == ("target decision layer at most 2x the tagger's predict: MISSED "
                                                 "(2.25x, single-instruction p50, median over the runs)")


def test_latency_judges_the_speed_targets_on_pairs_timed_alternately() -> None:
    latency = load_script("latency")
    runs = [{"paired": {"lstm_decided/lstm": r}} for r in (1.4, 1.7, 1.45)]
    assert latency.paired_target_lines(runs) == [
        "target decision layer at most 1.5x the tagger's predict, timed alternately: met (1.45x, median over the runs; "
        "1.40, 1.70, 1.45)"]
    assert latency.PAIRED == (("lstm", "lstm_decided"), ("lstm", "lstm_read"))
    # the shipped NLU against bert_base: bert_base over the tagger, divided by the front end's share timed alternately
    runs = [{"paired": {"lstm_read/lstm": r}} for r in (1.1, 1.3, 1.2)]
    medians = pd.DataFrame({"single_p50_ms": [3.0, 80.0]}, index=["lstm", "bert_base"])
    assert latency.paired_target_lines(runs, medians) == [
        "target lstm_read at least 20x faster than bert_base, the front end timed alternately with the tagger: met "
        "(22.2x: the front end 1.20x the tagger alone, median over the runs; 1.10, 1.30, 1.20)"]
    medians.loc["bert_base", "single_p50_ms"] = 60.0
    assert "MISSED (16.7x" in latency.paired_target_lines(runs, medians)[0]

    class Clock:
        def __init__(self, seconds):
            self.seconds = seconds

        def predict(self, sentences):
            time.sleep(self.seconds)
    times = latency.time_paired(Clock(0.002), Clock(0.05), [["a"], ["b"], ["c"]], passes=2)  # far apart: a loaded
    # machine oversleeps the short one by milliseconds
    assert times.shape == (2, 2, 3) and np.all(times[1] > times[0])


def test_placement_compares_the_physics_of_the_runs() -> None:
    placement = load_script("placement")
    first = pd.DataFrame([{c: 0.0 for c in placement.PHYSICS} | {"wall_s": 1.0}] * 2)
    assert placement.physics_differences([first, first.assign(wall_s=5.0)]) == []  # wall time may differ
    moved = first.copy()
    moved.loc[1, "pos_err_mm"] = 0.5
    assert placement.physics_differences([first, first, moved]) == ["run 3: pos_err_mm differ from run 1"]
    assert placement.physics_differences([first, first.iloc[:1]]) == ["run 2: 1 placements instead of 2"]


def written_by(text: str, command: str) -> None:
    """The provenance every results file must carry."""
    assert f"Written by `{command}`" in text
    machine = describe_machine()
    assert f"- cpu: {machine.cpu}" in text and f"- logical cores: {machine.logical_cores}" in text
    assert re.search(r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d UTC", text)


def test_latency_quick_writes_its_results(tmp_path, capsys) -> None:
    out = tmp_path / "latency.md"
    assert load_script("latency").main(["--quick", "--out", str(out)]) == 0
    text = out.read_text(encoding="utf-8")
    written_by(text, f"python benchmarks/latency.py --quick --out {out}")
    assert "`--quick`" in text and "these figures mean nothing" in text
    table = text.split("## Every run: load average and single-instruction p50 (ms)")[1].split("```")[1]
    rows = [line for line in table.splitlines() if re.match(r"\s+\d+ ", line)]
    assert len(rows) == 2 and all(line.count("(1, 5, 15 min)") == 2 for line in rows)  # load before and after
    p50s = [[float(x) for x in line.split()[-5:]] for line in rows]  # lstm, lstm_decided, minilm, bert_base, lstm_read
    line = re.search(r"lstm_p50_ms=(\S+) lstm_decided_p50_ms=(\S+) minilm_p50_ms=(\S+) bert_base_p50_ms=(\S+) "
                     r"lstm_read_p50_ms=(\S+)", text)
    for i in range(5):  # the reported figure is the median of the runs (rounded as printed)
        assert float(line.group(i + 1)) == pytest.approx(statistics.median(r[i] for r in p50s), abs=0.011)
    assert capsys.readouterr().out.rstrip().splitlines()[-2] == line.group(0)


def test_placement_quick_writes_its_results(tmp_path, capsys) -> None:
    out = tmp_path / "placement.md"
    assert load_script("placement").main(["--quick", "--out", str(out)]) == 0
    text = out.read_text(encoding="utf-8")
    written_by(text, f"python benchmarks/placement.py --quick --out {out}")
    assert "Physics: identical in every run" in text
    runs = text.split("## Every run")[1].split("```")[1]
    rows = [line for line in runs.splitlines() if re.match(r"\s+\d+ ", line)]
    assert len(rows) == 2 and all(line.count("(1, 5, 15 min)") == 2 for line in rows)
    factors = [float(line.split()[-1]) for line in rows]
    summary = re.search(r"success_rate=1\.000 max_pos_err_mm=\S+ max_ang_err_deg=\S+ realtime_factor=(\S+)", text)
    assert float(summary.group(1)) == pytest.approx(statistics.median(factors), abs=0.051)
    assert summary.group(0) in capsys.readouterr().out


# --- the README quotes what the scripts wrote ---------------------------------------------------
def last_summary(text: str, pattern: str) -> str:
    found = re.findall(pattern, text)
    assert found, f"no line like {pattern!r}"
    return found[-1]


def test_results_page_quotes_the_latency_results() -> None:
    text = (REPO / "benchmarks" / "results" / "latency.md").read_text(encoding="utf-8")
    assert "Written by `python benchmarks/latency.py" in text and "--quick" not in text.split("\n", 3)[2]
    line = last_summary(text, r"lstm_p50_ms=\S+ lstm_decided_p50_ms=\S+ minilm_p50_ms=\S+ bert_base_p50_ms=\S+(?: lstm_read_p50_ms=\S+)?")
    assert f"`{line}`" in RESULTS_PAGE.read_text(encoding="utf-8")


def test_results_page_quotes_the_placement_results() -> None:
    text = (REPO / "benchmarks" / "results" / "placement.md").read_text(encoding="utf-8")
    assert "Written by `python benchmarks/placement.py" in text and "--quick" not in text.split("\n", 3)[2]
    line = last_summary(text, r"success_rate=\S+ max_pos_err_mm=\S+ max_ang_err_deg=\S+ realtime_factor=\S+")
    assert f"`{line}`" in RESULTS_PAGE.read_text(encoding="utf-8")


def test_field_seeds_quick_trains_missing_seeds_and_scores_each(tmp_path) -> None:
    """benchmarks/field_seeds.py trains a seed only when its model is missing, and its figures are the field
    benchmark's play of that model."""
    from drywall_lab.nlu import load_tagger

    script = load_script("field_seeds")
    field = load_script("field")
    models, out = tmp_path / "models", tmp_path / "seeds.md"
    assert script.main(["--quick", "--seeds", "5", "--models", str(models), "--out", str(out)]) == 0
    first = out.read_text(encoding="utf-8")
    assert "seed 5: trained here" in first and (models / "seed5" / "tagger.json").is_file()
    assert f"- cpu: {describe_machine().cpu}" in first
    tagger = load_tagger(models / "seed5")
    assert tagger.training_info["n_train_instructions"] == script.QUICK["train_size"]
    played = field.run_set(field.FIELD_DIR, tagger)[1].loc["ALL"]
    for figure in ("accuracy", "wrong_action_rate"):
        value = float(re.search(rf"data_field_{figure}_mean=(\S+)", first).group(1))
        assert value == pytest.approx(played[figure], abs=5e-5)
    assert script.main(["--quick", "--seeds", "5", "--models", str(models), "--out", str(out)]) == 0
    second = out.read_text(encoding="utf-8")
    assert f"seed 5: found in {models / 'seed5'}" in second
    assert second.split("## Summary")[1] == first.split("## Summary")[1]
    # a model trained from another field corpus or recipe is never taken for the recipe's: the script asks for a
    # retrain
    assert (models / "seed5" / script.STAMP).read_text(encoding="utf-8").strip() == script.recipe_fingerprint(True)
    assert script.recipe_fingerprint(True) != script.recipe_fingerprint(False)
    (models / "seed5" / script.STAMP).write_text("a fingerprint of another generator\n", encoding="utf-8")
    with pytest.raises(SystemExit, match="trained from another field corpus or recipe.*delete it"):
        script.main(["--quick", "--seeds", "5", "--models", str(models), "--out", str(out)])
    assert out.read_text(encoding="utf-8") == second
    with pytest.raises(SystemExit):
        script.main(["--quick"])  # a quick run never overwrites the recorded results


def test_field_seeds_trains_another_averaging_only_apart(capsys) -> None:
    """--swa-epochs is another recipe: never into the shipped recipe's models or results file; its fingerprint
    differs, so its models are never taken for the recipe's."""
    script = load_script("field_seeds")
    for argv in (["--swa-epochs", "0"], ["--swa-epochs", "0", "--out", "other.md"]):
        with pytest.raises(SystemExit) as stop:
            script.main(argv)
        assert stop.value.code == 2 and "its own --models and --out" in capsys.readouterr().err
    assert script.recipe_with(None) == script.DEFAULT_FIELD_TAGGER
    assert script.recipe_fingerprint(False, script.recipe_with(0)) != script.recipe_fingerprint(False)
    assert "--swa-epochs" not in script.train_command(0, Path("out"), False, script.recipe_with(0))


def test_results_page_quotes_the_field_seeds_results() -> None:
    text = (REPO / "benchmarks" / "results" / "field_seeds.md").read_text(encoding="utf-8")
    assert "**Command:** `python benchmarks/field_seeds.py" in text and "--quick" not in text
    assert re.search(r"^shipped\b.*\bTrue\b", text, re.M), "one of the seeds must be the shipped tagger, byte for byte"
    readme = " ".join(RESULTS_PAGE.read_text(encoding="utf-8").split())
    for line in text.split("## Summary")[1].split("```")[1].split():
        if "_mean=" in line or "_max=" in line:
            assert line in readme, line
    # the same recipe without weight averaging, as the README compares them
    plain = (REPO / "benchmarks" / "results" / "field_seeds_no_averaging.md").read_text(encoding="utf-8")
    assert "--swa-epochs 0" in plain and "--quick" not in plain
    for line in plain.split("## Summary")[1].split("```")[1].split():
        if line.startswith(("data_field_accuracy_mean=", "shared_field_accuracy_mean=",
                            "shared_field_wrong_action_rate_mean=")):
            assert line in readme, line


def test_readme_glance_table_is_the_field_benchmarks() -> None:
    """Each hand-written set's row of the README's 'Results at a glance' is benchmarks/results/field.md's summary,
    and every set that benchmark plays has a row."""
    field = (REPO / "benchmarks" / "results" / "field.md").read_text(encoding="utf-8").split("## Summary")[1]
    figures = dict(re.findall(r"(\w+)=(\S+)", field))
    names = sorted({k.rsplit("_accuracy", 1)[0] for k in figures if k.endswith("_accuracy")})
    assert {"data_field", "first_sight_2026_12_05"} <= set(names)
    lines = README.read_text(encoding="utf-8").splitlines()
    for name in names:
        path = {"data_field": "data/field", "shared_field": "../shared/field"}.get(
            name, "data/first_sight/" + name.removeprefix("first_sight_").replace("_", "-", 2))
        row = [line for line in lines if line.startswith(f"| `{path}`")]
        assert len(row) == 1, path
        cells = [c.strip() for c in row[0].strip("|").split("|")]
        assert cells[1:3] == [f"{float(figures[name + '_accuracy']):.1%}",
                              f"{float(figures[name + '_wrong_action_rate']):.1%}"], path


def test_results_page_quotes_the_field_and_ensemble_results() -> None:
    """The README's field figures are benchmarks/results/field.md's summary, and its ensemble figures
    benchmarks/results/ensemble.md's."""
    readme = " ".join(RESULTS_PAGE.read_text(encoding="utf-8").split())
    field = (REPO / "benchmarks" / "results" / "field.md").read_text(encoding="utf-8")
    assert "**Command:** `python benchmarks/field.py`" in field
    for line in field.split("## Summary")[1].split("```")[1].split():
        if "over_refusal" not in line:
            assert line in readme, line
    ensemble = (REPO / "benchmarks" / "results" / "ensemble.md").read_text(encoding="utf-8")
    summary = ensemble.split("## Summary")[1].split("```")[1].split()
    chosen = summary[-1]
    assert f"`{chosen}`" in readme
    for name in ("seed0", "seed1", chosen.split("=")[1]):
        line = next(x for x in summary if x.startswith(f"{name}_cost="))
        assert f"`{line}`" in readme, line


def test_decision_fits_weights_and_records_them(tmp_path, capsys) -> None:
    """benchmarks/decision.py --quick fits the weights on the fit halves, calibrates the options floor, and records
    the settings as a literal that builds the same DecisionSettings it printed, with the best path, each feature
    switched off and other costs of a question; the recorded full run is DEFAULT_SETTINGS (tests/test_decision.py)."""
    from drywall_lab import decision
    from drywall_lab.decision import FEATURES

    script = load_script("decision")
    out = tmp_path / "decision.md"
    argv = ["--quick", "--out", str(out)]
    assert script.main(argv) == 0
    text = out.read_text(encoding="utf-8")
    assert f"**Command:** `python benchmarks/decision.py {' '.join(argv)}`" in text
    literal = re.search(r"^chosen=(DecisionSettings\(.*\))$", text, re.M).group(1)
    settings = eval(literal, vars(decision))  # noqa: S307 (our own results file)
    assert [n for n, _ in settings.weights] == list(FEATURES) and 0 <= settings.option_floor <= 1
    assert f"chosen={literal}" in capsys.readouterr().out
    ablation = text.split("## Each feature switched off")[1].split("```")[1]
    assert all(name in ablation for name in FEATURES)
    for section in ("## Fitted weights", "## The coordinate search", "## Best path", "## The options",
                    "## Other costs of a question"):
        assert section in text


def test_the_shipped_tagger_is_the_recorded_choice() -> None:
    """The shipped tagger is the ensemble of the seed models DEFAULT_ENSEMBLE_SEEDS, which
    benchmarks/results/ensemble.md chose: of the candidates (each seed model and every ensemble of them) that keep the
    paper's test split at the issue's Acc_inst (99.4% or more), the one of least decision cost on the generated
    splits; and make default-tagger trains those seeds with the recipe benchmarks/field_seeds.py trains."""
    from drywall_lab.nlu import DEFAULT_TAGGER_DIR, load_tagger
    from drywall_lab.nlu.field_study import DEFAULT_ENSEMBLE_SEEDS, DEFAULT_FIELD_TAGGER

    text = (REPO / "benchmarks" / "results" / "ensemble.md").read_text(encoding="utf-8")
    assert "**Command:** `python benchmarks/ensemble.py" in text and "--quick" not in text.split("\n", 3)[2]
    generated = text.split("Generated splits, where the field sets play no part:")[1].split("```")[1].splitlines()
    names = generated[1].split()
    row = {line.rsplit(None, len(names))[0]: list(map(float, line.split()[-len(names):])) for line in generated[2:]}
    table = pd.DataFrame({"cost": row["cost"], "test acc_inst": row["test acc_inst"]}, index=names)
    chosen = re.search(r"^chosen=(\S+)$", text, re.M).group(1)
    assert load_script("ensemble").choose(table) == chosen
    assert len(names) >= 7 and chosen == "+".join(f"seed{seed}" for seed in DEFAULT_ENSEMBLE_SEEDS)
    shipped = load_tagger(DEFAULT_TAGGER_DIR)
    assert [m.training_info["seed"] for m in shipped.members] == list(DEFAULT_ENSEMBLE_SEEDS)
    makefile = (REPO / "Makefile").read_text(encoding="utf-8")
    assert re.search(r"^ENSEMBLE_SEEDS := (.+)$", makefile, re.M).group(1).split() == [str(s) for s in DEFAULT_ENSEMBLE_SEEDS]
    recipe = " ".join(makefile.split("default-tagger:")[1].split("tagger-scores")[0].split())
    assert "--seed $$seed" in recipe and "ensemble $(foreach seed,$(ENSEMBLE_SEEDS),--member" in recipe
    # the Makefile trains the recipe that benchmarks/field_seeds.py trains for each seed
    seed_command = " ".join(load_script("field_seeds").train_command(0, Path("out"), quick=False))
    for option in ("--char-features", f"--batch-size {DEFAULT_FIELD_TAGGER['batch_size']}",
                   f"--epochs {DEFAULT_FIELD_TAGGER['epochs']}", f"--swa-epochs {DEFAULT_FIELD_TAGGER['swa_epochs']}"):
        assert option in recipe and option in seed_command, option


def test_the_ensemble_benchmark_quick(tmp_path) -> None:
    """benchmarks/ensemble.py --quick on the shipped tagger's two members: both alone and their ensemble scored, the
    choice by the recorded rule, the results file written where asked (never over the recorded one)."""
    from drywall_lab.nlu import DEFAULT_TAGGER_DIR

    out = tmp_path / "ensemble.md"
    script = load_script("ensemble")
    members = ["--member", str(DEFAULT_TAGGER_DIR / "member0"), "--member", str(DEFAULT_TAGGER_DIR / "member1")]
    assert script.main(["--quick", "--out", str(out), *members]) == 0
    text = out.read_text(encoding="utf-8")
    costs = dict(re.findall(r"^(\S+)_cost=(\S+)$", text, re.M))
    assert list(costs) == ["member0", "member1", "member0+member1"]
    assert re.search(r"^chosen=(member0|member1|member0\+member1)$", text, re.M)
    assert "data_field accuracy" in text
    with pytest.raises(SystemExit):
        script.main(["--quick"])  # a quick run never overwrites the recorded results
