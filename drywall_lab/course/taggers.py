"""A trained tagger in tables and words (notebooks 02, 03 and 07, ``benchmarks/field.py``): the paper's Table 3
row (plus ``acc_task``), scores on the named sets, its training curves and what it is.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Mapping, Sequence

import pandas as pd

if TYPE_CHECKING:
    from drywall_lab.nlu.base import Tagger


def table_3_row(name: str, tagger: "Tagger", rows: Sequence[Mapping]) -> dict:
    """The paper's Table 3 row for ``tagger`` on ``rows`` (N_w, Acc_word, N_l, Acc_inst), plus ``acc_task``:
    the share of instructions whose predicted tags lead the IM rules to the intended command or refusal."""
    from drywall_lab.im import task_accuracy
    from drywall_lab.nlu.metrics import score_tagging

    if not rows:
        raise ValueError(f"no instructions to score {name!r} on")
    predicted = tagger.predict([r["words"] for r in rows])
    s = score_tagging(tagger.gold_tags(rows), predicted)
    return {"model": name, "N_w": s.n_word_errors, "Acc_word": s.acc_word, "N_l": s.n_instruction_errors,
            "Acc_inst": s.acc_inst, "acc_task": task_accuracy(rows, predicted)}


def table_3(taggers: Mapping[str, "Tagger"], rows: Sequence[Mapping]) -> pd.DataFrame:
    """Table 3 (plus ``acc_task``) for several taggers on the same instructions, one row per tagger."""
    return pd.DataFrame([table_3_row(name, tagger, rows) for name, tagger in taggers.items()]).set_index("model")


def describe_tagger(tagger: "Tagger") -> str:
    """One sentence saying what a trained tagger is and what it was trained on, from its own record
    (``training_info``, saved with it): the notebooks never assume which tagger is shipped. An ensemble
    (``CrfEnsembleTagger``) is described by its members."""
    members = getattr(tagger, "members", None)
    if not members:
        return _describe_one(tagger, tagger.n_parameters()) + "."
    seeds = ", ".join(str(m.training_info.get("seed", "?")) for m in members)
    one = _describe_one(members[0], None, wall_time=False).removeprefix("a ")
    return (f"an ensemble of {len(members)} taggers whose CRF scores are averaged ({tagger.n_parameters():,} parameters "
            f"in all; seeds {seeds}), each {one}.")


def _describe_one(tagger: "Tagger", n_parameters: int | None, wall_time: bool = True) -> str:
    info = tagger.training_info
    kind = {"bilstm-crf": "a BiLSTM-CRF", "bert": "a fine-tuned BERT-family encoder"}.get(tagger.kind, tagger.kind)
    features = " reading characters as well as words" if getattr(tagger, "uses_characters", False) else ""
    text = f"{kind}{features}" + (f" with {n_parameters:,} parameters" if n_parameters is not None else "")
    if "n_train_instructions" in info and "epochs" in info:
        text += f", trained on {info['n_train_instructions']:,} instructions for {info['epochs']} epochs"
        if "n_validation_instructions" in info:
            text += f" (validated on {info['n_validation_instructions']:,})"
        if wall_time and info.get("wall_seconds") is not None:
            text += f" in {info['wall_seconds']:.0f} s"
    return text


def training_curves(tagger: "Tagger", name: str) -> dict[str, pd.DataFrame]:
    """A trained tagger's per-epoch history for ``plot_training_curves``, named ``name`` and the number of
    instructions it was trained on; an ensemble gives one curve per member (its seed in the name)."""
    members = getattr(tagger, "members", None) or [tagger]
    curves = {}
    for member in members:
        info = member.training_info
        label = f"{name} ({info.get('n_train_instructions', '?')} instructions"
        label += f", seed {info['seed']})" if len(members) > 1 and "seed" in info else ")"
        curves[label] = member.history
    return curves


def scores_on_sets(tagger: "Tagger", sets: Sequence[str], limit: int | None = None) -> pd.DataFrame:
    """Table 3 (plus ``acc_task``) of one tagger on named sets (``drywall_lab.splits``), one row per set; on the
    first ``limit`` instructions of each set when given (the notebooks' fast mode)."""
    from drywall_lab.splits import split_rows

    if limit is not None and limit < 1:
        raise ValueError(f"limit must be at least 1, got {limit}")
    records = []
    for name in sets:
        rows = split_rows(name)[:limit]
        records.append({"instructions": len(rows)} | table_3_row(name, tagger, rows))
    frame = pd.DataFrame(records)
    return frame.rename(columns={"model": "set"}).set_index("set")
