"""benchmarks/front_end.py: each step of the front end switched off, and what it moves."""
from __future__ import annotations

from pathlib import Path

from drywall_lab.nlu import normalise as N

RESULTS = Path(__file__).resolve().parent.parent / "benchmarks" / "results" / "front_end.md"


def test_a_step_switched_off_reads_without_it_and_is_put_back(benchmark_script):
    script = benchmark_script("front_end")
    shipped = N.STEPS
    said = "pon la placa de la izquierda en el poste cinco cero cero uno cero dos"
    off = script.read_with(script.without(N.translate_code_switch), said)
    assert off[:4] == ["pon", "la", "placa", "de"] and N.STEPS is shipped
    assert script.read_with(N.STEPS, said) == "put the board on the left on the stud 500102".split()
    assert script.without(None) == shipped


def test_a_cell_says_the_change_and_a_step_that_changes_nothing_is_a_dot(benchmark_script):
    script = benchmark_script("front_end")
    assert script.cell({"rows": 0, "right_on": 3, "right_off": 3, "wrong_on": 0, "wrong_off": 0}) == "·"
    assert script.cell({"rows": 9, "right_on": 9, "right_off": 4, "wrong_on": 0, "wrong_off": 2}) == \
        "9 rows: -5 right, +2 wrong"


def test_the_results_file_lists_every_step_and_the_code_switch_earns_its_keep():
    text = RESULTS.read_text(encoding="utf-8")
    assert "**Command:** `python benchmarks/front_end.py`" in text
    for step in N.STEPS:
        assert f"| `{step.__name__}` |" in text
    line = next(line for line in text.splitlines() if line.startswith("| `translate_code_switch` |"))
    assert line.endswith("| earns its keep |")
