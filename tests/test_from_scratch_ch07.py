"""Notebook 07's from-scratch exercise, the least expected cost (``drywall_lab.course.decision``): the reference
solution passes, the stub is "not attempted", each usual slip fails with the message that names it, the committed
notebook holds the stub; and the field ablation's bar chart."""
from __future__ import annotations

import contextlib
import io
from pathlib import Path

import matplotlib
import nbformat
import numpy as np
import pandas as pd
import pytest

from drywall_lab.course.common import solution_file
from drywall_lab.course.decision import (ACTIONS, check_expected_cost, decision_inputs, expected_cost_cases,
                                         library_decision, plot_ablation)
from drywall_lab.course.solutions import ch07
from drywall_lab.decision import DecisionCosts

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parent.parent
NOTEBOOK = ROOT / "notebooks" / "07_corpus_to_field.ipynb"
MARKER = "# from scratch: your code here"


@pytest.fixture(scope="module")
def example():
    """A decision that asks: one instruction read two ways by an unsure tagger (no tagger needed)."""
    from drywall_lab.corpus.tags import TAGS
    from drywall_lab.course.information_mapping import words_and_tags
    from drywall_lab.decision import decide

    words, centre = words_and_tags("put the full-size/dim panel on stud 500104/ID_stud in the middle/Vr_md")
    default = ["O" if t == "Vr_md" else t for t in centre]
    return decide(words, [(centre, np.log(0.55)), (default, np.log(0.45))], np.zeros((len(words), len(TAGS))), TAGS)


def _variant(slip: str = ""):
    """The reference decision with one slip."""
    def least(probabilities, costs, floor):
        commands = sorted(probabilities, key=lambda c: -probabilities[c])
        p_commands = sum(probabilities.values())
        refuse = costs.refuse * (1.0 if slip == "flat refusal" else p_commands)
        if not commands:
            return "refuse", None, refuse
        best = commands[0]
        above = [c for c in commands if slip == "no floor" or probabilities[c] >= floor]
        options = (above if slip == "no cap" else above[:3]) or [best]
        act = costs.wrong * (probabilities[best] if slip == "wrong for right" else 1.0 - probabilities[best])
        ask = (0.0 if slip == "no ask cost" else costs.ask) + costs.refuse * (
            p_commands - sum(probabilities[c] for c in options))
        if slip == "likeliest":
            return "act", best, act
        if slip == "reckless ties":
            return min([("act", best, act), ("ask", options, ask), ("refuse", None, refuse)],
                       key=lambda a: (a[2], -ACTIONS.index(a[0])))
        return min([("refuse", None, refuse), ("ask", options, ask), ("act", best, act)],
                   key=lambda a: (a[2], ACTIONS.index(a[0])))
    return least


def test_the_solution_passes_on_the_worked_example_and_every_case(example):
    check = check_expected_cost(ch07.least_expected_cost, example)
    assert check.passed and check.attempted, str(check)
    assert str(check).startswith("PASSED:\n- all 309 cases agree")
    assert check_expected_cost(_variant()).passed  # the tests' own reference agrees too


def test_the_library_decision_is_what_decide_did(example):
    assert example.action == "ask"
    inputs = decision_inputs(example)
    assert list(inputs) == sorted(inputs, key=lambda c: -inputs[c]) and all(c.startswith("panel ") for c in inputs)
    action, options, cost = library_decision(inputs)
    assert action == example.action and cost == pytest.approx(min(example.costs.values()))
    assert ch07.least_expected_cost(inputs, DecisionCosts(10, 1, 0.3), 0.0) == (action, options, cost)


def test_the_cases_reach_every_action_and_have_no_near_ties():
    cases = expected_cost_cases()
    taken = [library_decision(*c.args())[0] for c in cases]
    assert {a: taken.count(a) > 10 for a in ACTIONS} == dict.fromkeys(ACTIONS, True)
    assert any(c.name == "a tie of all three" for c in cases)


def test_the_stub_is_not_attempted(example):
    def stub(probabilities, costs, option_floor):
        raise NotImplementedError("your code here")

    check = check_expected_cost(stub, example)
    text = str(check)
    assert not check.passed and not check.attempted, text
    assert text.startswith("NOT ATTEMPTED YET:\n- fill in ") and solution_file(7) in text


@pytest.mark.parametrize("slip, says", [
    ("likeliest", "the likeliest command is not always worth acting on"),
    ("no ask cost", "add the cost of asking (costs.ask)"),
    ("wrong for right", "1 - P(c), not P(c)"),
    ("flat refusal", "refuse x P(any command)"),
    ("no floor", "must reach the options floor"),
    ("no cap", "at most three options"),
    ("reckless ties", "on a tie take the more careful action"),
])
def test_each_slip_fails_with_its_message(slip, says, example):
    check = check_expected_cost(_variant(slip), example)
    assert not check.passed and check.attempted, str(check)
    assert says in str(check), str(check)
    assert "disagree with the library's decision" in str(check)


@pytest.mark.parametrize("answer, says", [
    (lambda p, c, f: "act", "return a tuple (action, what, expected cost)"),
    (lambda p, c, f: ("wait", None, 0.0), "the action is 'act', 'ask' or 'refuse'"),
    (lambda p, c, f: 1 / 0, "raised ZeroDivisionError"),
    (lambda p, c, f: None, "return a tuple"),  # a body left as ``...`` is an answer, and a wrong one
])
def test_malformed_answers_fail(answer, says):
    check = check_expected_cost(answer)
    assert not check.passed and check.attempted and says in str(check), str(check)


# --- the committed notebook ----------------------------------------------------------------------------------------
def _cells():
    return nbformat.read(NOTEBOOK, as_version=4).cells


def _from_scratch_cell() -> int:
    found = [i for i, c in enumerate(_cells()) if c.cell_type == "code" and MARKER in c.source]
    assert len(found) == 1
    return found[0]


def test_the_notebook_holds_the_stub_not_the_solution():
    source = _cells()[_from_scratch_cell()].source
    assert 'raise NotImplementedError("your code here")' in source
    assert source.rstrip().endswith("check = check_expected_cost(least_expected_cost, example)\nprint(check)\n"
                                    "assert check.passed or not check.attempted")
    for line in ("options = [c for c in commands", "act = costs.wrong", "ask = costs.ask", "refuse = costs.refuse"):
        assert line not in source
    namespace = {"check_expected_cost": check_expected_cost, "example": None}
    with contextlib.redirect_stdout(io.StringIO()) as printed:
        exec(compile(source, "notebook 07's from-scratch cell", "exec"), namespace)  # noqa: S102
    assert not namespace["check"].attempted and printed.getvalue().startswith("NOT ATTEMPTED YET:\n- fill in ")


def test_the_markdown_above_names_the_solution_file():
    cells = _cells()
    above = next(c for c in reversed(cells[:_from_scratch_cell()]) if c.cell_type == "markdown")
    assert f"`{solution_file(7)}`" in above.source and "try the exercise first" in above.source


def test_the_ablation_cell_draws_the_bar_chart():
    cell = next(c for c in _cells() if c.cell_type == "code" and "read_ablation()" in c.source)
    assert "plot_ablation(ablation)" in cell.source


# --- the ablation as a bar chart -------------------------------------------------------------------------------------
def test_plot_ablation_draws_one_bar_per_model_and_column():
    frame = pd.DataFrame({"test acc_task": [1.0, 0.99], "novel acc_task": [0.8, 0.95], "data/field decided": [0.4, 0.9],
                          "data/field decided wrong": [0.05, 0.0], "kind": ["bilstm-crf", "bert"]},
                         index=pd.Index(["LSTM paper", "MiniLM field"], name="model"))
    fig = plot_ablation(frame)
    right, wrong = fig.axes
    assert len(right.patches) == 2 * 3 and len(wrong.patches) == 2 * 1
    assert [t.get_text() for t in right.get_xticklabels()] == ["LSTM paper", "MiniLM field"]
    assert sorted(p.get_height() for p in wrong.patches) == pytest.approx([0.0, 5.0])
    assert plot_ablation(frame.drop(columns="data/field decided wrong")).axes[0].patches
    matplotlib.pyplot.close("all")
