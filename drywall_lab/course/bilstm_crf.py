"""Notebook 02 (BiLSTM-CRF): the CRF's transition scores and the "most forbidden transitions" exercise; the CRF
from scratch on a three-word toy (path score, partition function by enumeration and by the forward algorithm,
log-likelihood, and the "Viterbi" exercise's check); the transitions as a heatmap and the network's layers
(the paper's "BiLSTM-CRF" section, Figs. 3 and 8(a))."""
from __future__ import annotations

import itertools
from typing import TYPE_CHECKING, Callable, Sequence

import numpy as np
import pandas as pd

from drywall_lab.corpus.tags import TAGS
from drywall_lab.course.common import solution_file
from drywall_lab.exercise import ExerciseCheck, call_student, is_unattempted

if TYPE_CHECKING:
    import matplotlib.pyplot as plt
    from torchcrf import CRF

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



# --- the CRF from scratch, on a three-word toy (the paper's "BiLSTM-CRF" section, Fig. 3) -------------------------
#: The toy's three words and three tags (a tag is a column of the emission table, an index 0, 1, 2).
TOY_WORDS: tuple[str, ...] = ("the", "third", "stud")
TOY_TAGS: tuple[str, ...] = ("O", "St_loc1", "ID_stud")
#: The toy's emission scores, one row a word, one column a tag: what the BiLSTM's linear layer would give.
#: Word by word, "third" is a little more ``ID_stud`` than ``St_loc1``: the transitions decide.
TOY_EMISSIONS = np.array([[1.2, 0.1, -0.4],
                          [-0.3, 0.6, 0.8],
                          [0.9, -0.2, 0.5]])


def toy_crf(seed: int = 73, n_tags: int = 3) -> "CRF":
    """A tiny ``torchcrf.CRF`` of ``n_tags`` tags whose start, end and transition scores are drawn (normal, scale
    1) with a fixed ``seed``; torchcrf's own start values (uniform in +-0.1) are too small to matter."""
    import torch
    from torchcrf import CRF

    generator = torch.Generator().manual_seed(seed)
    crf = CRF(n_tags)
    with torch.no_grad():
        for parameter in (crf.start_transitions, crf.end_transitions, crf.transitions):
            parameter.copy_(torch.randn(parameter.shape, generator=generator))
    return crf


def crf_scores(crf: "CRF") -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A CRF's ``(transitions, start, end)`` as numpy arrays; ``transitions[a, b]``: tag ``b`` right after ``a``."""
    return tuple(p.detach().cpu().numpy().astype(float)
                 for p in (crf.transitions, crf.start_transitions, crf.end_transitions))


def path_score(emissions: np.ndarray, transitions: np.ndarray, start: np.ndarray, end: np.ndarray,
               path: Sequence[int]) -> float:
    """The CRF's score of one tag path (paper, "BiLSTM-CRF"): start score of the first tag, plus each word's
    emission score for its tag, plus the transition score of each neighbouring pair, plus the end score of the last."""
    path = [int(t) for t in path]
    score = start[path[0]] + end[path[-1]] + sum(emissions[i, t] for i, t in enumerate(path))
    return float(score + sum(transitions[a, b] for a, b in zip(path, path[1:])))


def all_paths(n_words: int, n_tags: int) -> list[tuple[int, ...]]:
    """Every tag path of ``n_words`` words over ``n_tags`` tags: ``n_tags ** n_words`` of them."""
    return list(itertools.product(range(n_tags), repeat=n_words))


def path_scores(emissions: np.ndarray, transitions: np.ndarray, start: np.ndarray,
                end: np.ndarray) -> pd.Series:
    """Every path's score, by enumeration, indexed by the path (a tuple of tag indices)."""
    paths = all_paths(*emissions.shape)
    return pd.Series([path_score(emissions, transitions, start, end, p) for p in paths],
                     index=pd.Index(paths, tupleize_cols=False, name="path"), name="score")


def _logsumexp(values: np.ndarray, axis: int | None = None) -> np.ndarray:
    top = np.max(values, axis=axis, keepdims=True)
    out = top + np.log(np.sum(np.exp(values - top), axis=axis, keepdims=True))
    return out.squeeze() if axis is None else np.squeeze(out, axis=axis)


def brute_force_log_partition(emissions: np.ndarray, transitions: np.ndarray, start: np.ndarray,
                              end: np.ndarray) -> float:
    """log Z: the log of the sum of ``exp(score)`` over every tag path, by enumerating them all."""
    return float(_logsumexp(path_scores(emissions, transitions, start, end).to_numpy()))


def brute_force_best_path(emissions: np.ndarray, transitions: np.ndarray, start: np.ndarray,
                          end: np.ndarray) -> tuple[list[int], float]:
    """The highest-scoring tag path and its score, by enumerating every path (what Viterbi finds faster)."""
    scores = path_scores(emissions, transitions, start, end)
    best = scores.idxmax()
    return list(best), float(scores[best])


def forward_table(emissions: np.ndarray, transitions: np.ndarray, start: np.ndarray, end: np.ndarray,
                  tags: Sequence[str] | None = None, words: Sequence[str] | None = None) -> pd.DataFrame:
    """The forward algorithm's table: ``alpha[t, j]`` = log of the summed ``exp(score)`` of every path of the
    first ``t + 1`` words that ends in tag ``j``. ``alpha[0] = start + emissions[0]``, then
    ``alpha[t, j] = logsumexp_i(alpha[t - 1, i] + transitions[i, j]) + emissions[t, j]``; log Z is
    ``logsumexp_j(alpha[-1, j] + end[j])`` (:func:`forward_log_partition`)."""
    alpha = [start + emissions[0]]
    for t in range(1, len(emissions)):
        alpha.append(_logsumexp(alpha[-1][:, None] + transitions, axis=0) + emissions[t])
    n_words, n_tags = emissions.shape
    return pd.DataFrame(np.array(alpha), index=pd.Index(list(words or range(n_words)), name="word"),
                        columns=pd.Index(list(tags or range(n_tags)), name="alpha (ends in tag)"))


def forward_log_partition(emissions: np.ndarray, transitions: np.ndarray, start: np.ndarray,
                          end: np.ndarray) -> float:
    """log Z by the forward algorithm: the last row of :func:`forward_table` plus the end scores, log-sum-exp'd.
    It visits ``n_words * n_tags ** 2`` pairs where enumeration scores ``n_tags ** n_words`` paths."""
    last = forward_table(emissions, transitions, start, end).to_numpy()[-1]
    return float(_logsumexp(last + end))


def torchcrf_log_likelihood(crf: "CRF", emissions: np.ndarray, path: Sequence[int]) -> float:
    """torchcrf's ``crf(emissions, tags)`` for one sentence: the path's log-likelihood, ``score(path) - log Z``."""
    import torch

    em = torch.as_tensor(emissions, dtype=torch.float32).unsqueeze(1)  # (words, batch of 1, tags)
    tags = torch.as_tensor(list(path), dtype=torch.long).unsqueeze(1)
    with torch.no_grad():
        return float(crf(em, tags, mask=torch.ones(tags.shape, dtype=torch.bool), reduction="sum"))


def torchcrf_decode(crf: "CRF", emissions: np.ndarray) -> list[int]:
    """torchcrf's Viterbi decoding (``crf.decode``) of one sentence: its best tag path."""
    import torch

    em = torch.as_tensor(emissions, dtype=torch.float32).unsqueeze(1)
    return list(crf.decode(em, mask=torch.ones(em.shape[:2], dtype=torch.bool))[0])


def _crf_with(transitions: np.ndarray, start: np.ndarray, end: np.ndarray) -> "CRF":
    """A ``torchcrf.CRF`` holding the given scores."""
    import torch
    from torchcrf import CRF

    crf = CRF(len(start))
    with torch.no_grad():
        for parameter, value in ((crf.transitions, transitions), (crf.start_transitions, start),
                                 (crf.end_transitions, end)):
            parameter.copy_(torch.as_tensor(value, dtype=torch.float32))
    return crf


Scores = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]  # emissions, transitions, start, end


def _viterbi_cases() -> list[tuple[str, Scores]]:
    """The cases ``check_viterbi`` tries: the notebook's toy, then random small CRFs (1 to 5 words, 2 to 4 tags)."""
    cases = [("the notebook's toy (3 words, 3 tags)", (TOY_EMISSIONS.copy(), *crf_scores(toy_crf())))]
    rng = np.random.default_rng(31)
    for n_words, n_tags in [(1, 3), (2, 2), (4, 3), (5, 2), (3, 4), (5, 4), (1, 4), (4, 4)]:
        scores = (rng.normal(size=(n_words, n_tags)), rng.normal(size=(n_tags, n_tags)) * 1.5,
                  rng.normal(size=n_tags) * 1.5, rng.normal(size=n_tags) * 1.5)
        cases.append((f"a random CRF ({n_words} word{'s' * (n_words > 1)}, {n_tags} tags)", scores))
    return cases


def _best_prefix_scores(emissions: np.ndarray, transitions: np.ndarray, start: np.ndarray) -> np.ndarray:
    """``delta[t, j]``: the best score of the first ``t + 1`` words' paths that end in tag ``j`` (no end score),
    by enumeration."""
    n_words, n_tags = emissions.shape
    delta = np.full((n_words, n_tags), -np.inf)
    for t in range(n_words):
        for prefix in all_paths(t + 1, n_tags):
            delta[t, prefix[-1]] = max(delta[t, prefix[-1]],
                                       path_score(emissions[:t + 1], transitions, start, np.zeros(n_tags), prefix))
    return delta


def _misread_back_pointers(emissions: np.ndarray, transitions: np.ndarray, start: np.ndarray,
                           end: np.ndarray) -> list[int]:
    """The path a back-pointer read one word off gives: the tag before word ``t``'s is looked up in the
    back-pointers of word ``t - 1`` (those of word 0 being zeros) instead of word ``t``'s."""
    delta = _best_prefix_scores(emissions, transitions, start)
    back = np.zeros(delta.shape, dtype=int)
    for t in range(1, len(delta)):
        back[t] = np.argmax(delta[t - 1][:, None] + transitions, axis=0)
    path = [int(np.argmax(delta[-1] + end))]
    for t in range(len(delta) - 1, 0, -1):
        path.insert(0, int(back[t - 1, path[0]]))
    return path


def _viterbi_slip(got_path: list[int], got_score: float, scores: Scores, want_path: list[int],
                  want_score: float) -> str:
    """What is wrong with a (path, score) that is not the best one: the known slips first, then in general."""
    emissions, transitions, start, end = scores
    zeros = np.zeros_like(start)

    def same(path: list[int], score: float) -> bool:
        return got_path == path and bool(np.isclose(got_score, score, atol=1e-5))

    if len(got_path) != len(emissions):
        return f"your path has {len(got_path)} tags for {len(emissions)} words: return one tag index per word"
    if got_path == want_path[::-1] != want_path:
        return ("your path is backwards: following the back-pointers goes from the last word to the first, "
                "so reverse the path at the end")
    slips = [((zeros, zeros), "you left out both the start and the end scores: add start[tag] at the first word "
                              "and end[tag] after the last"),
             ((zeros, end), "you left out the start scores: the first word's tag j also scores start[j]"),
             ((start, zeros), "you left out the end scores: the last word's tag j also scores end[j] (add it "
                              "before choosing the last tag)")]
    for (s, e), message in slips:
        if same(*brute_force_best_path(emissions, transitions, s, e)):
            return message
    if same(*brute_force_best_path(emissions, transitions.T, start, end)):
        return ("your transitions are transposed: transitions[a, b] is the score of tag b right AFTER tag a "
                "(row = the tag before, column = the tag after), you read it as [to, from]")
    greedy = [int(j) for j in np.argmax(emissions, axis=1)]
    if got_path == greedy != want_path:
        return ("that is each word's highest emission score on its own (greedy): the best path must weigh the "
                "transitions too, keep for every tag the best score of a path ending in it, word by word")
    misread = _misread_back_pointers(emissions, transitions, start, end)
    if got_path == misread != want_path:
        return ("your back-pointers are read one word off: the tag of word t - 1 is back[t][tag of word t], "
                "the pointer stored when word t was scored")
    try:
        score_of_yours = path_score(emissions, transitions, start, end, got_path)
    except IndexError:
        return f"your path {got_path} has tags outside 0..{len(start) - 1}"
    if np.isclose(got_score, want_score, atol=1e-5):
        return (f"your score is the best one, but your path scores {score_of_yours:.4f}: the back-pointers do not "
                f"lead back along the best path; the tag of word t - 1 is back[t][tag of word t]")
    if got_path == want_path:
        return (f"the path is right, but its score is {want_score:.4f}, not {got_score:.4f}: start + emissions "
                "+ transitions + end")
    return (f"your path {got_path} scores {score_of_yours:.4f} (you said {got_score:.4f}); the best path "
            f"{want_path} scores {want_score:.4f}")


def check_viterbi(viterbi: Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray], tuple[Sequence[int], float]]
                  ) -> ExerciseCheck:
    """Notebook 02's from-scratch exercise: ``viterbi(emissions, transitions, start, end)`` must return the best
    tag path (one tag index per word) and its score. Tried on the notebook's toy and on random small CRFs (1 to 5
    words, 2 to 4 tags), against enumerating every path and torchcrf's ``CRF.decode``. The slips it names: start
    or end scores left out, transitions read as [to, from], each word's best tag alone (greedy), back-pointers
    read one word off, a path backwards. The notebook's stub (raises ``NotImplementedError``) is not attempted."""
    cases = _viterbi_cases()
    if is_unattempted(viterbi, *(np.array(a, copy=True) for a in cases[0][1]), none=True):
        return ExerciseCheck.not_attempted("viterbi(emissions, transitions, start, end): return the best tag "
                                           "path and its score", solution_file(2))
    messages = []
    for name, scores in cases:
        want_path, want_score = brute_force_best_path(*scores)
        decoded = torchcrf_decode(_crf_with(*scores[1:]), scores[0])
        assert decoded == want_path, f"torchcrf and enumeration disagree on {name}"
        got, error = call_student(viterbi, *(np.array(a, copy=True) for a in scores))
        if error:
            return ExerciseCheck(False, messages + [f"on {name} your function raised {error}"])
        try:
            path, score = got
            path, score = [int(t) for t in path], float(score)
        except (TypeError, ValueError):
            return ExerciseCheck(False, messages + [f"on {name} your function returned {got!r}: return (path, "
                                                    "score), a list of tag indices and a number"])
        if path == want_path and np.isclose(score, want_score, atol=1e-5):
            messages.append(f"{name}: right, {path} scoring {score:.4f} (as enumerating all "
                            f"{scores[0].shape[1] ** len(path)} paths, and crf.decode)")
            continue
        hint = _viterbi_slip(path, score, scores, want_path, want_score)
        return ExerciseCheck(False, messages + [f"on {name} you returned {path} scoring {score:.4f}; the best "
                                                f"path is {want_path} scoring {want_score:.4f}: {hint}"])
    return ExerciseCheck(True, messages)


# --- figures: the transition scores as a heatmap, the network's layers (the paper's Figs. 3 and 8(a)) ---------------
def plot_transitions(transitions: pd.DataFrame, ax: "plt.Axes | None" = None, annotate: bool = True) -> "plt.Figure":
    """A CRF's transition scores (:func:`crf_transitions`) as a heatmap: a row is the tag before, a column the
    tag after; a diverging colormap centred on 0, blue where the CRF favours the pair, red where it penalises it."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(0.62 * len(transitions.columns) + 2.5, 0.5 * len(transitions) + 1.5))
    values = transitions.to_numpy(dtype=float)
    limit = float(np.max(np.abs(values))) or 1.0
    image = ax.imshow(values, cmap="RdBu", vmin=-limit, vmax=limit)
    ax.set_xticks(range(len(transitions.columns)), [str(c) for c in transitions.columns], rotation=60, ha="right")
    ax.set_yticks(range(len(transitions.index)), [str(i) for i in transitions.index])
    ax.set_xlabel("tag after")
    ax.set_ylabel("tag before")
    if annotate:
        for (i, j), v in np.ndenumerate(values):
            ax.text(j, i, f"{v:.2f}".replace("-0.00", "0.00"), ha="center", va="center", fontsize=6,
                    color="white" if abs(v) > 0.6 * limit else "black")
    ax.figure.colorbar(image, ax=ax, label="transition score", shrink=0.8)
    ax.set_title("CRF transition scores: transitions[before, after]")
    return ax.figure


#: What each layer of :func:`draw_bilstm_crf` is called (bottom to top); the character CNN only where it is used.
ARCHITECTURE_LAYERS = ("word embedding", "character CNN", "forward LSTM", "backward LSTM", "concatenation",
                       "linear: emission scores", "CRF layer", "tags")


def tagged_window(words: Sequence[str], tags: Sequence[str], size: int = 4) -> tuple[list[str], list[str]]:
    """The ``size`` neighbouring words (and their tags) with the most tags other than ``O``, the first such window:
    a few words of an instruction worth drawing in :func:`draw_bilstm_crf`."""
    starts = range(max(1, len(words) - size + 1))
    best = max(starts, key=lambda i: (sum(t != "O" for t in tags[i:i + size]), -i))
    return list(words[best:best + size]), list(tags[best:best + size])


def draw_bilstm_crf(words: Sequence[str], tags: Sequence[str] | None = None, settings: dict | None = None,
                    n_tags: int = len(TAGS)) -> "plt.Figure":
    """The BiLSTM-CRF's layers for ``words`` (the paper's Fig. 3, with the sizes of its Fig. 8(a)), bottom to top:
    each word's embedding (and character CNN, where ``settings`` has ``char_filters`` > 0), the forward LSTM
    (left to right) and the backward LSTM (right to left), their outputs concatenated, a linear layer giving one
    emission score per tag, and the CRF layer, whose transition scores join neighbouring tags, giving ``tags``.
    ``settings``: a tagger's ``settings()`` (sizes in the boxes); the defaults are the paper's."""
    import matplotlib.pyplot as plt
    from matplotlib.patches import FancyBboxPatch

    settings = {"embedding_dim": 50, "hidden_size": 150, "num_layers": 2, "char_filters": 0, **(settings or {})}
    chars = int(settings.get("char_filters") or 0) > 0
    hidden, layers = int(settings["hidden_size"]), int(settings["num_layers"])
    n = len(words)
    fig, ax = plt.subplots(figsize=(2.3 * n + 2.6, 7.6))
    rows = {"word": 0.0, "embedding": 1.0, "forward": 2.2, "backward": 3.2, "concat": 4.4, "linear": 5.4,
            "crf": 6.5, "tag": 7.5}
    width, height = 1.6, 0.55

    def box(x: float, y: float, text: str, color: str, w: float = width, dashed: bool = False) -> None:
        ax.add_patch(FancyBboxPatch((x - w / 2, y - height / 2), w, height, boxstyle="round,pad=0.03",
                                    facecolor=color, edgecolor="0.3", linestyle="--" if dashed else "-"))
        ax.text(x, y, text, ha="center", va="center", fontsize=8)

    def arrow(x0: float, y0: float, x1: float, y1: float, color: str = "0.35") -> None:
        ax.annotate("", xy=(x1, y1), xytext=(x0, y0), arrowprops={"arrowstyle": "->", "color": color, "lw": 1.1})

    xs = [2.3 * i for i in range(n)]
    for i, (x, word) in enumerate(zip(xs, words)):
        ax.text(x, rows["word"], f'"{word}"', ha="center", va="center", fontsize=10, fontweight="bold")
        embedding = f"word embedding ({settings['embedding_dim']})"
        if chars:
            embedding += f"\n+ character CNN ({settings['char_filters']})"
        box(x, rows["embedding"], embedding, "#f3e6c4")
        box(x, rows["forward"], f"forward LSTM\n$\\vec{{h}}_{{{i + 1}}}$ ({hidden})", "#cfe3f7")
        box(x, rows["backward"], f"backward LSTM\n$\\overleftarrow{{h}}_{{{i + 1}}}$ ({hidden})", "#d9ecd0")
        box(x, rows["concat"], f"concatenation [$\\vec{{h}}$; $\\overleftarrow{{h}}$] ({2 * hidden})", "#e8dcf1")
        box(x, rows["linear"], f"linear: emission scores\n({n_tags} per word)", "#fbe0d0")
        arrow(x, rows["word"] + 0.2, x, rows["embedding"] - height / 2)
        arrow(x - 0.35, rows["embedding"] + height / 2, x - 0.35, rows["forward"] - height / 2)
        arrow(x + 0.6, rows["embedding"] + height / 2, x + 0.6, rows["backward"] - height / 2)
        arrow(x - 0.35, rows["forward"] + height / 2, x - 0.35, rows["concat"] - height / 2, "#3a78b5")
        arrow(x + 0.35, rows["backward"] + height / 2, x + 0.35, rows["concat"] - height / 2, "#4c9a3b")
        arrow(x, rows["concat"] + height / 2, x, rows["linear"] - height / 2)
        arrow(x, rows["linear"] + height / 2, x, rows["crf"] - 0.3)
        arrow(x, rows["crf"] + 0.3, x, rows["tag"] - 0.22)
        tag = tags[i] if tags is not None else "?"
        ax.text(x, rows["tag"], tag, ha="center", va="center", fontsize=10, fontweight="bold",
                bbox={"boxstyle": "round", "facecolor": "white", "edgecolor": "0.3"})
    for x0, x1 in zip(xs, xs[1:]):
        arrow(x0 + width / 2, rows["forward"], x1 - width / 2, rows["forward"], "#3a78b5")
        arrow(x1 - width / 2, rows["backward"], x0 + width / 2, rows["backward"], "#4c9a3b")
        ax.annotate("", xy=(x1 - 0.25, rows["tag"]), xytext=(x0 + 0.25, rows["tag"]),
                    arrowprops={"arrowstyle": "-", "color": "#b5443a", "lw": 1.5, "connectionstyle": "arc3,rad=-0.3"})
    ax.add_patch(FancyBboxPatch((xs[0] - width / 2, rows["crf"] - 0.3), xs[-1] - xs[0] + width, 0.6,
                                boxstyle="round,pad=0.03", facecolor="#f6d5d2", edgecolor="0.3"))
    ax.text((xs[0] + xs[-1]) / 2, rows["crf"], "CRF layer: emission scores + transitions[tag before, tag after] "
            "between neighbouring tags; Viterbi picks the best path", ha="center", va="center", fontsize=8)
    right = xs[-1] + width / 2 + 0.2
    notes = {"forward": f"left to right ({layers} layers)", "backward": f"right to left ({layers} layers)",
             "tag": "tags"}
    for row, note in notes.items():
        ax.text(right, rows[row], note, ha="left", va="center", fontsize=8, color="0.3")
    ax.set_xlim(xs[0] - width / 2 - 0.3, right + 2.0)
    ax.set_ylim(-0.5, rows["tag"] + 0.6)
    ax.axis("off")
    ax.set_title("BiLSTM-CRF (the paper's Figs. 3 and 8(a))" + (", with character features" if chars else ""))
    return fig
