"""benchmarks/novel_redraws.py: the novel split drawn again from other seeds, and what the README quotes of it."""
from __future__ import annotations

import re
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
RESULTS = REPO / "benchmarks" / "results" / "novel_redraws.md"


def test_the_redraws_are_other_seeds_than_the_committed_split_and_the_fit(benchmark_script):
    from drywall_lab.corpus.field_generator import FIELD_SEED

    script = benchmark_script("novel_redraws")
    seeds = script.draw_seeds(3)
    assert seeds == [FIELD_SEED + 1, FIELD_SEED + 2, FIELD_SEED + 3] and FIELD_SEED not in seeds


def test_a_redraw_is_the_novel_split_of_another_seed():
    from drywall_lab.corpus.channels import held_back_combinations
    from drywall_lab.corpus.field_generator import generate_field_split

    rows = generate_field_split("novel", n=30, seed=2027)
    committed = generate_field_split("novel", n=30)
    assert [r["text"] for r in rows] != [r["text"] for r in committed]
    assert all(any(set(h) <= set(r["channels"]) for h in held_back_combinations()) for r in rows)


def test_the_readme_quotes_the_redraws():
    text = RESULTS.read_text(encoding="utf-8")
    assert "**Command:** `python benchmarks/novel_redraws.py`" in text
    figures = dict(re.findall(r"(redraws_\w+)=(\S+)", text.split("## Summary")[1]))
    row = next(line for line in (REPO / "README.md").read_text(encoding="utf-8").splitlines()
               if line.startswith("| generated field-novel drawn again"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert cells[1:3] == [f"{float(figures['redraws_accuracy_mean']):.1%}",
                          f"{float(figures['redraws_wrong_action_rate_mean']):.1%}"]
