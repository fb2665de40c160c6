"""Notebook 02 (BiLSTM-CRF), exercise "what has the CRF learned to forbid?": reference solution, and answer keys
of the chapter's closing questions.

Reference solutions: try the exercise first (``check_most_forbidden(most_forbidden, shipped)`` in the notebook
says what is wrong: swapped rows and columns, the highest scores, the wrong order). The from-scratch exercise,
``viterbi`` (the CRF's best path on the toy of section 9), is checked by ``check_viterbi(viterbi)``.
"""
from __future__ import annotations

import numpy as np
import pandas as pd


def most_forbidden(transitions: pd.DataFrame, k: int) -> list[tuple[str, str]]:
    """The ``k`` (tag before, tag after) pairs with the lowest transition scores, lowest first.

    ``stack`` turns the table into one score per (row, column) pair, that is (tag before, tag after);
    ``nsmallest`` keeps the ``k`` lowest, lowest first.
    """
    return list(transitions.stack().nsmallest(k).index)


#: The answer keys of the closing "Questions" (figures of the committed study, ``results/paper``; if you re-run
#: it, read your own figures: the reasoning stays).
ANSWERS: dict[int, str] = {
    1: """The study's Table 3 gives LSTM-M4 (316 instructions) 92.41% Acc_inst on the validation split (12 of 158
instructions wrong), against the paper's 48.73%. This corpus is generated: the validation instructions come from the
same templates, words and phrasings as the training ones, so 316 instructions already show nearly every pattern the
validation split uses, and the tagger has little to generalise. The paper's corpus (not public) evidently left
more to generalise from 316 instructions. The phrasings the generator held back show how much of the figure is
the generator's: on the novel split the study's BiLSTM-CRFs fall to 32-51% Acc_inst
(LSTM-M4 35.50%, LSTM-M1 50.50%), the study's MiniLMs alike (29.5-54%: BERT-M4 35.50%, BERT-M1 54.00%), while the
acc_task of all eight stays at 71-89%: many of the instructions they tag wrongly still lead to the right
command. Over three seeds (``results/paper/seeds.md``) LSTM-M4's validation Acc_inst runs from 92.41% to
96.84% (mean 94.73%): one run says little to within a few points, but no seed comes near the paper's 48.73%.""",
    2: """In the study's Fig. 13 (``training_history.csv``) LSTM-M1 reaches 100% validation Acc_inst at epoch 6,
LSTM-M2 is at 98.7-99.4% from epoch 6-8, LSTM-M3 at about 97% from epoch 8; after that they wobble by a few
instructions of the 158 either way, without a clear gain. LSTM-M4 (316 instructions) climbs slowest, over 90%
only from epoch 13, and levels off around epoch 15-16 (93.04%). So the paper's 20 epochs are more than the larger
models need (6-8 would do) and about what the smallest one needs: with fewer instructions an epoch is fewer
updates.""",
    3: """Acc_inst counts an instruction wrong for any wrong tag; acc_task asks only whether the IM rules give the
intended command (or refusal). The rules read only the words they need, in a fixed order, so many tag mistakes
change nothing: a word the rules do not use (a filler word tagged as something, or a tag on a second word that
says the same, "middle line" with only "middle" right); information said twice (a panel by its id and its size, a
stud by its id and its position: the first rule that applies decides). Only a mistake on a word the deciding rule
reads moves the robot elsewhere (or makes it refuse).""",
    4: """The study's Acc_inst against training size (its Table 3 and the figure of section 5), at the smallest
sizes: the M4 rows (316 instructions) and M3 (632) of the BiLSTM-CRF against MiniLM. "Learns more from little data"
means the gap at 316 instructions; the per-epoch validation curves of Fig. 13 show the "in fewer epochs" part, and
the novel split whether it also generalises better.""",
}


def viterbi(emissions: np.ndarray, transitions: np.ndarray, start: np.ndarray,
            end: np.ndarray) -> tuple[list[int], float]:
    """The best tag path (one tag index per word) and its score: Viterbi, the from-scratch exercise.

    ``best[j]`` is the best score of a path over the words so far that ends in tag ``j``; for the next word,
    ``best[i] + transitions[i, j]`` is the best path that goes from tag ``i`` to ``j``, so its maximum over ``i``
    (plus the word's emission score) is the new ``best[j]``, and its argmax the back-pointer. After the last word,
    add the end scores, take the best tag, and follow the back-pointers from the last word to the first.
    """
    best = start + emissions[0]
    back_pointers = []
    for word_scores in emissions[1:]:
        candidates = best[:, None] + transitions  # [tag before, tag after]
        back_pointers.append(np.argmax(candidates, axis=0))
        best = np.max(candidates, axis=0) + word_scores
    best = best + end
    path = [int(np.argmax(best))]
    for pointers in reversed(back_pointers):
        path.append(int(pointers[path[-1]]))
    return path[::-1], float(np.max(best))
