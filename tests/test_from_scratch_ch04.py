"""Notebook 04's from-scratch exercise, rule T2 of Fig. 10 (``check_stacks_of_size`` in
``drywall_lab.course.information_mapping``): the reference solution passes, the stub is "not attempted", each usual
slip fails with the message that names it, the committed notebook holds the stub; and the IM rule path drawn as a
flowchart (``rule_path``, ``draw_rule_path``)."""
from __future__ import annotations

import contextlib
import io
from pathlib import Path

import matplotlib
import nbformat
import pytest

from drywall_lab.course.common import solution_file
from drywall_lab.course.information_mapping import (RULE_MAPS, SIZE_SITES, check_stacks_of_size, draw_rule_path,
                                                    draw_rule_paths, library_stacks_of_size, rule_path, rule_t2,
                                                    site_with_sizes, stacks_of_size_cases, words_and_tags)
from drywall_lab.course.solutions import ch04
from drywall_lab.im import interpret

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parent.parent
NOTEBOOK = ROOT / "notebooks" / "04_information_mapping.ipynb"
MARKER = "# from scratch: your code here"


def _matching(sizes, width, length):
    return [s for s, (w, l) in sizes.items() if (width is None or w == width) and (length is None or l == length)]


def test_the_solution_passes():
    check = check_stacks_of_size(ch04.stacks_of_size)
    assert check.passed and check.attempted, str(check)
    assert str(check).startswith("PASSED:\n- all 504 cases agree with rule T2 (3 sites")


def test_the_grader_asks_what_the_rules_do():
    """The stacks the check wants give, on every case, what the target rules decide: the one stack's top panel,
    ``ambiguous_size`` for two or more, ``no_matching_size`` for none."""
    seen = set()
    for site, width, length in stacks_of_size_cases():
        want = library_stacks_of_size(site.sizes, width, length)
        kind, value = rule_t2(width, length, site)
        if len(want) == 1:
            assert (kind, value) == ("stack", want[0]), (width, length, site.sizes)
        else:
            reason = "ambiguous_size" if want else "no_matching_size"
            assert kind == "refusal" and value.startswith(reason), (width, length, site.sizes, value)
        seen.add(min(len(want), 2))
    assert seen == {0, 1, 2}
    assert rule_t2(8, 4) == ("stack", "left") and rule_t2(2, None) == ("stack", "middle")
    assert site_with_sizes(SIZE_SITES[1]).sizes == {"left": (2.0, 4.0), "middle": (4.0, 8.0), "right": (4.0, 12.0)}
    assert site_with_sizes().sizes == {"left": (4.0, 8.0), "middle": (2.0, 8.0), "right": (4.0, 6.0)}


def test_the_stub_is_not_attempted():
    def stub(sizes, width, length):
        raise NotImplementedError("your code here")

    check = check_stacks_of_size(stub)
    text = str(check)
    assert not check.passed and not check.attempted, text
    assert text.startswith("NOT ATTEMPTED YET:\n- fill in ") and solution_file(4) in text


@pytest.mark.parametrize("answer, says", [
    (lambda s, w, l: _matching(s, w, l), "try it turned (width and length swapped)"),
    (lambda s, w, l: list(dict.fromkeys(_matching(s, w, l) + _matching(s, l, w))),
     "try the size turned only when nothing has it as said"),
    (lambda s, w, l: (_matching(s, w, l) or _matching(s, l, w))[:1], "it asks which one (ambiguous_size)"),
    (lambda s, w, l: _matching(s, l, w) or _matching(s, w, l), "the width is the first number said"),
    (lambda s, w, l: [x for x, (sw, sl) in s.items() if (sw, sl) in ((w, l), (l, w))],
     "None matches every width"),
    (lambda s, w, l: 1 / 0, "never raise"),
    (lambda s, w, l: "left", "return a list of stack names"),
    (lambda s, w, l: None, "return a list of stack names"),  # a body left as ``...`` is an answer, and a wrong one
])
def test_each_slip_fails_with_its_message(answer, says):
    check = check_stacks_of_size(answer)
    assert not check.passed and check.attempted, str(check)
    assert says in str(check) and "disagree with rule T2" in str(check), str(check)


# --- the committed notebook ----------------------------------------------------------------------------------------
def _cells():
    return nbformat.read(NOTEBOOK, as_version=4).cells


def _from_scratch_cell() -> int:
    found = [i for i, c in enumerate(_cells()) if c.cell_type == "code" and MARKER in c.source]
    assert len(found) == 1
    return found[0]


def test_the_notebook_holds_the_stub_not_the_solution():
    source = _cells()[_from_scratch_cell()].source
    assert 'raise NotImplementedError("your code here")' in source and "# your code here" not in source
    assert source.rstrip().endswith("check = check_stacks_of_size(stacks_of_size)\nprint(check)\n"
                                    "assert check.passed or not check.attempted")
    assert "return matching(" not in source and "sw == w" not in source
    namespace = {"check_stacks_of_size": check_stacks_of_size}
    with contextlib.redirect_stdout(io.StringIO()) as printed:
        exec(compile(source, "notebook 04's from-scratch cell", "exec"), namespace)  # noqa: S102
    assert not namespace["check"].attempted and printed.getvalue().startswith("NOT ATTEMPTED YET:\n- fill in ")


def test_the_markdown_above_names_the_solution_file():
    cells = _cells()
    above = next(c for c in reversed(cells[:_from_scratch_cell()]) if c.cell_type == "markdown")
    assert f"`{solution_file(4)}`" in above.source and "try the exercise first" in above.source


def test_the_notebook_draws_the_worked_instructions_path():
    cells = _cells()
    trace = next(i for i, c in enumerate(cells) if c.cell_type == "code" and "result = interpret_row(row)" in c.source)
    drawn = [i for i, c in enumerate(cells) if c.cell_type == "code" and "draw_rule_paths(result)" in c.source]
    assert len(drawn) == 1 and drawn[0] > trace


# --- the rule path as a flowchart ------------------------------------------------------------------------------------
def _interpret(markup: str):
    return interpret(*words_and_tags(markup))


def test_rule_path_follows_the_trace():
    result = _interpret("the 8/width by 4/length panel on the stud two/St_loc1 to/St_loc1 the/St_loc1 "
                        "left/St_loc1 of 500109/St_loc2")
    target, none = rule_path(result, "target")
    assert none is None and [s.rule for s in target] == [r[0] for r in RULE_MAPS["target"][0]]
    assert [(s.tried, s.applies) for s in target] == [(True, False), (True, True)] + [(False, False)] * 3
    assert "turned" in target[1].conclusion
    studs, _ = rule_path(result, "destination")
    assert [s.applies for s in studs] == [False, False, True] and "stud 500107" in studs[2].conclusion
    placement, _ = rule_path(result, "placement")
    assert [s.applies for s in placement] == [False, True]


def test_rule_path_of_a_refusal_stops_where_the_rules_did():
    result = _interpret("the panel on stud 500104/ID_stud")  # no rule names the panel
    target, none = rule_path(result, "target")
    assert not any(s.applies for s in target) and all(s.tried for s in target)
    assert none is not None and none.startswith("refused (undetermined)")
    assert not any(s.tried for s in rule_path(result, "destination")[0])  # never reached


def test_draw_rule_path_colours_the_path_and_writes_the_conclusion():
    result = _interpret("the 8/width by 4/length panel on stud 500104/ID_stud")
    ax = draw_rule_path(result, "target")
    texts = [t.get_text() for t in ax.texts]
    assert any("turned" in t for t in texts)  # the deciding rule's conclusion, not what it gives in general
    assert any("the top panel of the stack there" in t for t in texts)  # a rule never reached: what it would give
    edges = {t.get_text().split("\n")[0]: t.get_bbox_patch().get_edgecolor() for t in ax.texts if t.get_bbox_patch()}
    assert edges["T1 panel id"] == edges["T2 width and length"] != edges["T3 size word or same as before"]
    fig = draw_rule_paths(result)
    assert len(fig.axes) == 3
    matplotlib.pyplot.close("all")
