"""The rule ablation (benchmarks/rule_ablation.py, issue 29 item 3): its registry names real attributes, switching a
rule off reaches every module that reads it, and the script keeps to the results-file conventions. No tagger is
loaded here: the measurement itself is the script's full run (benchmarks/results/rule_ablation.md)."""
from __future__ import annotations

import ast
import importlib
import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

REPO = Path(__file__).resolve().parent.parent


def load_script() -> ModuleType:
    spec = importlib.util.spec_from_file_location("benchmark_rule_ablation", REPO / "benchmarks" / "rule_ablation.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def script() -> ModuleType:
    module = load_script()
    module.import_project()
    return module


def test_every_entry_names_an_existing_attribute(script) -> None:
    names = [rule.name for rule in script.REGISTRY]
    assert len(names) == len(set(names)), "a rule is listed twice"
    assert 15 <= len(script.REGISTRY) <= 45
    for rule in script.REGISTRY:
        module = importlib.import_module(rule.module)
        assert hasattr(module, rule.attribute), rule.path
        original = getattr(module, rule.attribute)
        assert callable(original) == callable(rule.off), f"{rule.path}: the replacement is not of the same kind"
        if not callable(original):
            assert type(original) is type(rule.off), rule.path
        assert rule.what and rule.off_text and rule.group
    assert set(script.QUICK_RULES) <= set(names)
    assert {u.name for u in script.UNSWITCHABLE}.isdisjoint(names)
    assert "the decision's features" in {u.name for u in script.UNSWITCHABLE}  # switched by settings, not faked


@pytest.fixture(scope="module")
def top_level_imports() -> dict[tuple[str, str], list[str]]:
    """(module, name) -> the project modules that import it with a module-level ``from <module> import name``."""
    out: dict[tuple[str, str], list[str]] = {}
    for path in sorted((REPO / "drywall_lab").rglob("*.py")):
        parts = path.relative_to(REPO).with_suffix("").parts
        importer = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, ast.ImportFrom) and node.module:
                for alias in node.names:
                    if alias.asname is None:
                        out.setdefault((node.module, alias.name), []).append(importer)
    return out


def test_switching_off_reaches_every_module_that_reads_it(script, top_level_imports) -> None:
    for rule in script.REGISTRY:
        importers = top_level_imports.get((rule.module, rule.attribute), [])
        for name in importers:
            importlib.import_module(name)
        home = importlib.import_module(rule.module)
        original = getattr(home, rule.attribute)
        holders = script.holders(rule)
        assert {m.__name__ for m in holders} >= {rule.module, *importers}, rule.path
        with script.switched_off(rule) as patched:
            assert patched == holders
            for module in holders:
                assert getattr(module, rule.attribute) is rule.off, f"{rule.path} in {module.__name__}"
        for module in holders:
            assert getattr(module, rule.attribute) is original, f"{rule.path} not restored in {module.__name__}"
    taken_back = script.rule_named("taken_back")  # read through `from ... import taken_back` in im/trace.py
    assert "drywall_lab.im.trace" in {m.__name__ for m in script.holders(taken_back)}


def test_a_rule_switched_off_changes_what_the_rules_see(script) -> None:
    from drywall_lab import decision
    from drywall_lab.im.trace import TaggedInstruction

    words = "the one at the bottom of the stack is cracked".split()
    tags = ["O"] * len(words)
    tags[4] = "Hr_btm"
    assert TaggedInstruction(words, tags).in_stack == (4,)
    with script.switched_off(script.rule_named("stack_place")):
        assert TaggedInstruction(words, tags).in_stack == ()
    assert TaggedInstruction(words, tags).in_stack == (4,)

    words = "the second stud from the right , no , the fourth from the right".split()
    tags = ["O", "St_loc1", "O", "St_loc1", "St_loc1", "St_loc1", "O", "O", "O", "O", "St_loc1", "St_loc1", "St_loc1",
            "St_loc1"]
    assert TaggedInstruction(words, tags).taken_back
    with script.switched_off(script.rule_named("taken_back")):
        assert TaggedInstruction(words, tags).taken_back == {}
        assert decision.two_meanings is not script.rule_named("two_meanings").off
    with script.switched_off(script.rule_named("two_meanings")):
        assert decision.two_meanings(("command", "500320", "500100", "vertical_left"), [], [], None) is None


def test_verdicts_come_from_the_numbers(script) -> None:
    sets = [script.EvalSet("validation", "generated", "rows", 3, None),
            script.EvalSet("validation", "generated", "episodes", 3, None),
            script.EvalSet("data/field", "hand-written", "episodes", 2, None)]
    base = script.Played([("command", "1", "2", "vertical_left"), ("refusal", "unclear"), ("refusal", "undetermined")],
                         ["right", "right", "over_refusal"])
    same = script.compare(base, base)
    assert (same.moved, same.rescored, same.d_right, same.d_wrong) == (0, 0, 0, 0)
    now = script.Played([("command", "1", "3", "vertical_left"), ("refusal", "unclear"), ("refusal", "no_history")],
                        ["wrong_action", "right", "over_refusal"])
    moved = script.compare(base, now)
    assert (moved.moved, moved.rescored, moved.d_right, moved.d_wrong) == (2, 1, -1, 1)
    assert moved.examples == [(0, base.outcomes[0], now.outcomes[0]), (2, base.outcomes[2], now.outcomes[2])]
    assert script.describe_outcome(now.outcomes[0]) == "1 on 3, vertical_left"
    assert script.describe_outcome(now.outcomes[2]) == "refused (no_history)"
    assert script.verdict(sets, [same, moved, same]) == script.EARNS
    assert script.verdict(sets, [same, same, moved]) == script.HAND_ONLY
    assert script.verdict(sets, [same, same, same]) == script.NOTHING
    lines = script.report_lines(sets, [base, base, base], [(script.REGISTRY[0], [same, moved, same], 1.0)],
                                "python benchmarks/rule_ablation.py", ["- cpu: X"], "a tagger", 2.0, 1.0, False)
    text = "\n".join(lines)
    assert "Written by `python benchmarks/rule_ablation.py`" in text and "- cpu: X" in text
    assert f"| 1 | `{script.REGISTRY[0].path}` | {script.REGISTRY[0].off_text} | 0 / 2 | 0 | {script.EARNS} |" in text
    assert "the decision's features" in text
    assert '- data/field (episodes): "?": refused (undetermined) -> refused (no_history)' not in text  # not moved there
    assert '  - validation (episodes): "?": 1 on 2, vertical_left -> 1 on 3, vertical_left' in text


def test_quick_figures_never_replace_the_recorded_results(script, capsys) -> None:
    with pytest.raises(SystemExit) as stop:
        script.main(["--quick"])
    assert stop.value.code == 2
    assert "give --out FILE" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        script.main(["--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "benchmarks/results/rule_ablation.md" in out and "--jobs" in out


def test_an_unknown_rule_is_refused(script, capsys) -> None:
    with pytest.raises(SystemExit) as stop:
        script.main(["--rule", "no_such_rule", "--out", "unused.md"])
    assert stop.value.code == 2
    assert "no_such_rule" in capsys.readouterr().err
