"""Notebook 02 (BiLSTM-CRF): the CRF's transition scores and the "most forbidden transitions" exercise."""
from __future__ import annotations

from typing import TYPE_CHECKING, Callable, Sequence

import numpy as np
import pandas as pd

from drywall_lab.corpus.tags import TAGS
from drywall_lab.course.common import solution_file
from drywall_lab.exercise import ExerciseCheck, call_student, is_unattempted

if TYPE_CHECKING:
    from drywall_lab.nlu.base import Tagger


def crf_transitions(tagger: "Tagger") -> pd.DataFrame:
    """A trained BiLSTM-CRF's transition scores as a table: row = the tag before, column = the tag after.

    The CRF adds ``transitions[a, b]`` to a tag sequence's score wherever tag ``b`` follows tag ``a``; the most
    negative entries are the transitions it has learned to (almost) forbid. For an ensemble of BiLSTM-CRFs
    (``CrfEnsembleTagger``), the members' mean, which is what it decodes with.
    """
    from drywall_lab.nlu.ensemble import CrfEnsembleTagger

    if isinstance(tagger, CrfEnsembleTagger):
        crf = tagger.crf
    else:
        crf = getattr(getattr(tagger, "network", None), "crf", None)
    if crf is None:
        raise ValueError("crf_transitions needs a trained BiLstmCrfTagger (or an ensemble of them)")
    scores = crf.transitions.detach().cpu().numpy().astype(float)
    labels = list(tagger.labels)
    return pd.DataFrame(scores, index=pd.Index(labels, name="from (tag before)"),
                        columns=pd.Index(labels, name="to (tag after)"))


def reference_most_forbidden(transitions: pd.DataFrame, k: int) -> list[tuple[str, str]]:
    """The reference answer: the ``k`` (before, after) tag pairs with the lowest transition scores, lowest first."""
    stacked = transitions.stack()
    return [(str(a), str(b)) for a, b in stacked.nsmallest(k, keep="first").index]


def _exercise_matrices(tagger: "Tagger | None") -> list[tuple[str, pd.DataFrame, int]]:
    """The tables the check tries: the trained tagger's, then small ones built to catch the usual slips."""
    cases = []
    if tagger is not None:
        cases.append(("the trained tagger's transitions", crf_transitions(tagger), 5))
    labels = ["O", "ID_stud", "St_loc1", "St_loc2"]
    asymmetric = pd.DataFrame([[0.5, 1.0, 0.2, -0.1], [0.3, -4.0, 2.5, -9.0], [0.0, -2.0, 1.5, 0.8],
                               [0.7, -6.0, -1.0, 1.2]], index=labels, columns=labels)
    cases.append(("a small table whose rows and columns are not interchangeable", asymmetric, 3))
    cases.append(("the same small table", asymmetric, 1))
    rng = np.random.default_rng(13)
    cases.append(("a random 13 x 13 table", pd.DataFrame(rng.normal(size=(13, 13)), index=list(TAGS),
                                                        columns=list(TAGS)), 4))
    return cases


def check_most_forbidden(most_forbidden: Callable[[pd.DataFrame, int], Sequence[tuple[str, str]]],
                         tagger: "Tagger | None" = None) -> ExerciseCheck:
    """Notebook 02's exercise: ``most_forbidden(transitions, k)`` must return the ``k`` (before, after) tag
    pairs with the lowest scores, lowest first, on the trained tagger's table and on tables built to catch
    swapped rows and columns, the highest scores instead of the lowest, and the wrong order. The notebook's stub
    (a function that raises ``NotImplementedError``, or whose body is still ``...``) is "not attempted yet"."""
    cases = _exercise_matrices(tagger)
    _, first_table, first_k = cases[0]
    if is_unattempted(most_forbidden, first_table.copy(), first_k, none=True):
        return ExerciseCheck.not_attempted("most_forbidden(transitions, k): return the k (tag before, tag after) "
                                           "pairs with the lowest scores, lowest first", solution_file(2))
    messages = []
    for name, table, k in cases:
        want = reference_most_forbidden(table, k)
        got, error = call_student(most_forbidden, table.copy(), k)
        if error:
            return ExerciseCheck(False, messages + [f"on {name} (k = {k}) your function raised {error}"])
        try:
            returned, got = got, [tuple(str(t) for t in pair) for pair in got]
            assert not isinstance(returned, str) and all(len(pair) == 2 for pair in got)
        except (TypeError, AssertionError):
            return ExerciseCheck(False, messages + [f"on {name} (k = {k}) your function returned {returned!r}: "
                                                    "return a list of (tag before, tag after) pairs"])
        if got == want:
            messages.append(f"{name}, k = {k}: right")
            continue
        problem = f"on {name} (k = {k}) you returned {got}, the lowest scores are {want}"
        if len(got) != k:
            hint = f"return exactly k = {k} pairs"
        elif got == [(b, a) for a, b in want]:
            hint = "your pairs are (after, before): a row of the table is the tag before, a column the tag after"
        elif set(got) == set(reference_most_forbidden(-table, k)) or got == reference_most_forbidden(-table, k):
            hint = "those are the highest scores, the transitions the CRF favours most: forbidden means lowest"
        elif set(got) == set(want):
            hint = "the right pairs in the wrong order: the lowest score first"
        else:
            first = next(i for i, (g, w) in enumerate(zip(got, want)) if g != w)
            g, w = got[first], want[first]
            score = table.loc[g[0], g[1]] if g[0] in table.index and g[1] in table.columns else float("nan")
            hint = (f"pair {first + 1}: {g} scores {score:.3f}, but {w} scores {table.loc[w[0], w[1]]:.3f}")
        return ExerciseCheck(False, messages + [f"{problem}: {hint}"])
    return ExerciseCheck(True, messages)

