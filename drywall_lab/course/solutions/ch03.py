"""Notebook 03 (BERT), exercises "word tags to token labels, from scratch" and "the vote yourself": reference
solutions, and answer keys of the chapter's closing questions.

Reference solutions: try the exercise first (``check_align_labels(align_labels)`` in the notebook names the first
token your alignment labels wrongly and the slip it looks like; ``check_vote(my_vote)`` explains the first case
your vote gets wrong, word by word).
"""
from __future__ import annotations

from collections import Counter


def align_labels(word_ids: list[int | None], word_labels: list[int]) -> list[int]:
    """One label id per token: the label id of the token's word for every sub-word of it (``BertTagger`` trains
    them all), -100 (ignored by the loss) for the special tokens, whose word id is ``None``."""
    return [-100 if word is None else word_labels[word] for word in word_ids]


def my_vote(token_tags: list[str], word_ids: list[int | None], n_words: int) -> list[str]:
    """One tag per word from its tokens' tags: the tag of more than half of the word's tokens, else the first
    token's tag; ``"O"`` for a word with no token. Special tokens (word id ``None``) vote for no word."""
    per_word = [[tag for tag, word in zip(token_tags, word_ids) if word == w] for w in range(n_words)]
    out = []
    for tags in per_word:
        if not tags:
            out.append("O")
            continue
        tag, count = Counter(tags).most_common(1)[0]
        out.append(tag if 2 * count > len(tags) else tags[0])
    return out


#: The answer keys of the closing "Questions" (figures of the committed study, ``results/paper``; if you re-run
#: it, read your own figures: the reasoning stays).
ANSWERS: dict[int, str] = {
    1: """At 316 training instructions the study gives the BiLSTM-CRF 92.41% and MiniLM 98.10% validation Acc_inst
(9 more instructions right of 158); the paper 48.73% and 79.11% (bert-base about 48 instructions ahead). The
direction holds: the pre-trained encoder is ahead with little data. But the gap is far smaller, and only at the
smallest size: at 632 instructions the BiLSTM-CRF is ahead (98.10% against 96.84%), at 948 and 1,268 it gets 100%.
The corpus is generated from templates with a small vocabulary, so the validation instructions reuse the training
ones' words and phrasings: a BiLSTM-CRF learns from few examples which tag each of those words takes, and needs
little of the general English that pre-training brings. Over three seeds (``results/paper/seeds.md``) even the gap at 316 is
not firm: BERT-M4 97.05% against LSTM-M4 94.73% on the mean (2.32 points), and the ranges overlap (LSTM-M4's best
seed, 96.84%, is above BERT-M4's worst, 96.20%); on the novel split the two are level within the seeds' spread
(33.67% and 34.50%). At the other sizes the BiLSTM-CRF is ahead on the validation mean (by 0.42, 0.42 and 1.27
points at 1,268, 948 and 632 instructions), again within what the seed alone moves.""",
    2: """By Acc_inst BERT-M1 is ahead on the novel split (54.00% against LSTM-M1's 50.50%), and by acc_task too
(89.00% against 80.50%). At the other sizes the orders do differ: M3 has the BiLSTM-CRF ahead on Acc_inst (40.50%
against 40.00%) but BERT ahead on acc_task (79.50% against 71.00%); M2 has the BiLSTM-CRF ahead on Acc_inst and
the two level on acc_task. One run each does not settle any of it: over three seeds (``results/paper/seeds.md``)
BERT-M1 has 48.33% on the novel split's mean against LSTM-M1's 48.67%, and at every size the two models' seeds
overlap on the novel split. Acc_inst counts any wrong tag; acc_task only the mistakes that change the robot's
command. A tagger may make more mistakes that do not matter to the robot and fewer that do: Acc_inst measures the
tagging, acc_task what the robot does, and for the robot acc_task is the figure that counts.""",
    3: """No. Table 5's co-reference models (BERT-C) are below BERT-M at 3 of the 4 sizes and level at 632:
1,268 instructions 98.73% against 99.37% (1 instruction), 948 98.10% against 99.37% (2), 632 both 96.84%, 316
92.41% against 98.10% (9 fewer). Only at 316 is the difference more than one or two of the 158 validation
instructions; the paper also found the labels cost at the smallest size (11 fewer). On the novel split the
co-reference models fall much further still (Acc_inst 9-10%).""",
    4: """A learning rate chosen because it scored best on the test split is chosen partly for that split's
particular 158 instructions and their noise; the test figure then reported is the best of several noisy scores,
biased upwards, and no longer an estimate on unseen data. Choosing on validation keeps the test split unseen; but
validation and test come from the same generator and templates, so a choice that suits the generator's phrasings
would look good on both. The novel split holds phrasings the generator withheld from training and validation, so
it tells whether a choice made on validation still holds on language the choice never saw.""",
}
