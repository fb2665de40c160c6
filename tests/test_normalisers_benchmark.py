"""The table of site forms (data/normalisation/forms.tsv) and the normaliser comparison (benchmarks/normalisers.py).

The recorded comparison (benchmarks/results/normalisers.md) is run in a scratch environment that has the libraries;
here the script runs ``--quick`` with what this environment has (a second at most: NeMo, which compiles its grammars
for seconds, is left out), and a library it cannot import is reported rather than stopping it.
"""
from __future__ import annotations

import re
from pathlib import Path
from types import ModuleType

import pytest
from conftest import load_benchmark

REPO = Path(__file__).resolve().parent.parent
SITE_IDS = {str(i) for i in range(500100, 500113)} | {str(i) for i in range(500300, 500323)}


def load_script() -> ModuleType:
    return load_benchmark("normalisers")


@pytest.fixture(scope="module")
def script() -> ModuleType:
    return load_script()


def test_the_table_parses_and_covers_every_class(script) -> None:
    forms = script.read_forms()
    assert len(forms) >= 80
    assert set(script.classes_of(forms)) == {"id_digits", "id_grouped", "id_typed", "cardinal", "ordinal", "size",
                                            "metric", "keep"}
    assert len({f.spoken for f in forms}) == len(forms), "a form is listed twice"
    for form in forms:
        if form.cls.startswith("id_"):
            ids = re.findall(r"\b\d{6}\b", form.expected)
            assert ids and set(ids) <= SITE_IDS, form
        if form.cls == "keep":
            assert form.spoken == form.expected, form


def test_a_malformed_table_is_refused(script, tmp_path) -> None:
    table = tmp_path / "forms.tsv"
    table.write_text("# a comment\nclass\tspoken\texpected\nsize\tthe four by eight\n", encoding="utf-8")
    with pytest.raises(ValueError, match=":3:"):
        script.read_forms(table)


def test_comparison_ignores_case_spacing_and_sentence_punctuation_only(script) -> None:
    assert script.comparable("No,  the other ONE.") == "no the other one"
    assert script.comparable("stud 500,106") != script.comparable("stud 500106")
    assert script.comparable("stud #500104") != script.comparable("stud 500104")


def test_quick_figures_never_replace_the_recorded_results(script, capsys) -> None:
    with pytest.raises(SystemExit) as stop:
        script.main(["--quick"])
    assert stop.value.code == 2
    assert "give --out FILE" in capsys.readouterr().err


def test_a_partial_run_never_replaces_the_recorded_results(script, monkeypatch, capsys) -> None:
    monkeypatch.setattr(script, "missing_libraries", lambda: ["nemo"])
    with pytest.raises(SystemExit) as stop:
        script.main([])
    assert stop.value.code == 2
    assert "lacks nemo: give --out FILE" in capsys.readouterr().err
    monkeypatch.setattr(script, "missing_libraries", lambda: [])
    with pytest.raises(SystemExit):
        script.main(["--candidates", "project"])
    assert "--candidates leaves some out" in capsys.readouterr().err


def test_quick_runs_and_reports_a_missing_library(script, tmp_path, monkeypatch, capsys) -> None:
    def missing():
        raise ImportError("No module named 'numerizer'")

    monkeypatch.setitem(script.CANDIDATES, "numerizer", ("numerizer", missing))
    import drywall_lab.machine

    monkeypatch.setattr(drywall_lab.machine, "_torch_details", lambda: (None, None, None))  # no torch import: fast
    out = tmp_path / "normalisers.md"
    argv = ["--quick", "--out", str(out), "--candidates", "project", "number_parser", "numerizer", "identity"]
    assert script.main(argv) == 0
    text = out.read_text(encoding="utf-8")
    assert f"Written by `python benchmarks/normalisers.py {' '.join(argv)}`" in text
    assert "these figures mean nothing" in text
    assert "numerizer: not installed in this environment" in capsys.readouterr().out
    assert "| numerizer | not installed in this environment" in text
    assert "## Choice" in text and "## Machine" in text and "- logical cores:" in text
    assert re.search(r"^\| identity \| [\d.]+% \(\d+/16\) \|", text, re.M)  # two forms of each of 8 classes


def test_acceptable_outputs_are_any_of_the_alternatives(script) -> None:
    form = script.Form("cardinal", "two studs over", "two studs over || 2 studs over", 1)
    assert form.alternatives == ("two studs over", "2 studs over")
    assert form.accepts("Two  studs over") and form.accepts("2 studs over")
    assert not form.accepts("2 studs over || two studs over") and not form.accepts("two studs")
    forms = script.read_forms()
    assert all(len(f.alternatives) == 1 for f in forms if f.cls in script.STRICT_CLASSES)
    assert any(len(f.alternatives) > 1 for f in forms if f.cls == "cardinal")


@pytest.mark.parametrize("expected, message", [("one of those || 1 of those", "one acceptable output"),
                                               ("one of those ||  || x", "none is empty"),
                                               ("one of those || One  of those", "listed twice")])
def test_a_table_with_bad_alternatives_is_refused(script, tmp_path, expected, message) -> None:
    table = tmp_path / "forms.tsv"
    table.write_text(f"class\tspoken\texpected\nkeep\tone of those\t{expected}\n", encoding="utf-8")
    with pytest.raises(ValueError, match=message):
        script.read_forms(table)


def test_the_choice_says_where_a_library_wins_and_why_it_is_not_used(script) -> None:
    forms = [script.Form("size", "the two-by-eights", "the two-by-eight", 1),
             script.Form("size", "the 4x8s", "the 4x8", 2),
             script.Form("keep", "one of those", "one of those", 3)]

    def outcome(name, outputs):
        return script.Outcome(name, load_s=0.0, outputs=outputs, times_s=[0.001])

    outcomes = [outcome("project", ["the two-by-eights", "the 4x8", "one of those"]),
                outcome("numerizer", ["the two-by-eight", "the 4x8", "1 of those"]),
                outcome("identity", ["the two-by-eights", "the 4x8s", "one of those"])]
    text = "\n".join(script.choice_lines(outcomes, forms))
    assert "- `size`: numerizer wins with 100.0% (2/2) against project's 50.0% (1/2)" in text
    assert "`the two-by-eights` -> `the two-by-eight`" in text
    assert "The project does not use it" in text and "changes 1 of the 1 forms that must not change" in text
    assert "The grammar is still wrong on 1 of 3 forms (`size` 1" in text
