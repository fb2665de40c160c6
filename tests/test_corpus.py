"""The instruction corpus, checked against the spec's sections 1-3 and the paper's Table 2.

The committed files ``data/corpus/*.jsonl`` are what the project ships; the first
test regenerates them (``python -m drywall_lab corpus generate``, once for the whole
session: the ``regenerated_corpus`` fixture of ``tests/conftest.py``) and compares bytes,
so a change to the generator (or to a phrase bank) shows up here without anyone having to
regenerate the data. The other tests read the committed files.

The information mapping used in ``test_meaning_gives_expected`` is written here
from the spec's section 3 on purpose, independently of the project's own mapping,
so that the corpus's ``meaning`` and ``expected`` fields are checked against the
spec rather than against the code that produced them.
"""
from __future__ import annotations

import re
from collections import Counter
from itertools import groupby

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from drywall_lab.corpus import (
    CORPUS_DIR,
    COREF_TAGS,
    SEED,
    SPLITS,
    TAGS,
    check_against_paper,
    from_conll,
    generate_corpus,
    load_corpus,
    read_corpus,
    sentence_groups,
    tag_table,
    to_conll,
    tokenize,
)
from drywall_lab.corpus import phrases as P
from drywall_lab.corpus.markup import parse
from drywall_lab.errors import REFUSAL_REASONS, Refusal
from drywall_lab.site import STACK_NAMES, Placement, default_site

PAPER_SPLITS = ("train", "validation", "test")
PUNCT = ".,?!"
NUMBER_WORDS = {"one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "twelve"}
ORDINAL_WORDS = {"first", "second", "third", "fourth", "fifth", "sixth", "seventh"}
ORDINAL_DIGITS = re.compile(r"^\d+(st|nd|rd|th)$")


@pytest.fixture(scope="module")
def corpus() -> dict[str, list[dict]]:
    """The committed corpus, all four splits."""
    return read_corpus()


def all_rows(corpus, splits=SPLITS):
    return [r for s in splits for r in corpus[s]]


# --- 1. determinism ------------------------------------------------------------------
@pytest.mark.parametrize("split", SPLITS)
def test_write_corpus_matches_committed_files(regenerated_corpus, split):
    assert regenerated_corpus.exit_code == 0
    fresh = (regenerated_corpus.out_dir / f"{split}.jsonl").read_bytes()
    committed = (CORPUS_DIR / f"{split}.jsonl").read_bytes()
    assert fresh == committed, f"{split}.jsonl: the generator no longer gives the committed data"


def test_other_seed_gives_other_text(corpus):
    other = generate_corpus(seed=SEED + 1, sizes={"train": 40})["train"]
    assert len(other) == 40
    same = sum(a["text"] == b["text"] for a, b in zip(other, corpus["train"]))
    assert same < 5


def test_same_seed_same_rows(corpus):
    again = generate_corpus(seed=SEED, sizes={"validation": 158})["validation"]
    assert again == corpus["validation"]


# --- 2. sizes and ids ------------------------------------------------------------------
def test_split_sizes(corpus):
    assert {s: len(corpus[s]) for s in PAPER_SPLITS} == {"train": 1268, "validation": 158, "test": 158}
    assert len(corpus["novel"]) >= 158


def test_ids_unique(corpus):
    ids = [r["id"] for r in all_rows(corpus)]
    assert len(ids) == len(set(ids))


# --- 3. every row --------------------------------------------------------------------
@pytest.mark.parametrize("split", SPLITS)
def test_rows_well_formed(corpus, split):
    site = default_site()
    for r in corpus[split]:
        rid = r["id"]
        assert r["words"] == tokenize(r["text"]), rid
        assert len(r["tags"]) == len(r["words"]) == len(r["coref_tags"]), rid
        assert set(r["tags"]) <= set(TAGS), rid
        assert set(r["coref_tags"]) <= set(COREF_TAGS), rid
        for t, c in zip(r["tags"], r["coref_tags"]):
            assert c == t or (c in ("Trg", "Dst") and t == "O"), (rid, t, c)
        assert 1 <= r["n_sentences"] <= 4, rid
        e = r["expected"]
        if e["refusal"] is None:
            assert e["drywall_id"] in site.panel_ids, rid
            assert e["stud_id"] in site.stud_ids, rid
            assert e["placement"] in {p.value for p in Placement}, rid
        else:
            assert e["refusal"] in REFUSAL_REASONS, rid
            assert e["drywall_id"] is None and e["stud_id"] is None and e["placement"] is None, rid


# --- 4. tags in every split --------------------------------------------------------------
@pytest.mark.parametrize("split", SPLITS)
def test_every_tag_in_every_split(corpus, split):
    tags = {t for r in corpus[split] for t in r["tags"]}
    coref = {t for r in corpus[split] for t in r["coref_tags"]}
    assert set(TAGS) - tags == set()
    assert {"Trg", "Dst"} - coref == set()


# --- 5. every meaning in every split -----------------------------------------------------
def _tagged_words(rows, tags):
    return {w.lower() for r in rows for w, t in zip(r["words"], r["tags"]) if t in tags}


def _is_asr(r):
    return r["text"] == r["text"].lower() and not any(p in r["text"] for p in PUNCT)


#: facet -> function of a split's rows giving the set of values that must all be present
FACETS = {
    "target kinds": (lambda rows: {r["meaning"]["target"]["kind"] for r in rows},
                     {"id", "size", "standard", "same", "absolute", "relative"}),
    "stud kinds": (lambda rows: {r["meaning"]["stud"]["kind"] for r in rows},
                   {"id", "absolute", "from_end", "ordinal", "relative"}),
    "target anchors": (lambda rows: {"id" if a[:1].isdigit() else a for r in rows
                                     if (a := r["meaning"]["target"].get("anchor"))},
                       {"id", "previous"}),
    "stud anchors": (lambda rows: {"id" if a[:1].isdigit() else a for r in rows
                                   if (a := r["meaning"]["stud"].get("anchor")) and r["meaning"]["stud"]["kind"] == "relative"},
                     {"id", "leftmost", "rightmost", "previous"}),
    # "rightmost" cannot name a destination: every panel put on the last stud reaches past the wall's end
    "stud absolute names": (lambda rows: {r["meaning"]["stud"].get("name") for r in rows} - {None},
                            {"leftmost", "middle"}),
    "target stacks": (lambda rows: {r["meaning"]["target"].get("stack") for r in rows} - {None},
                      set(STACK_NAMES)),
    "placements": (lambda rows: {r["meaning"]["placement"] for r in rows}, {p.value for p in Placement}),
    "size numbers": (lambda rows: {"digits" if w.isdigit() else "words" if w in NUMBER_WORDS else w
                                   for w in _tagged_words(rows, ("width", "length"))},
                     {"digits", "words"}),
    "ordinals": (lambda rows: {"words" if w in ORDINAL_WORDS else "digits" if ORDINAL_DIGITS.match(w) else "other"
                               for w in _tagged_words(rows, ("St_loc1", "Dw_loc1"))},
                 {"words", "digits"}),
    "styles": (lambda rows: {"asr" if _is_asr(r) else "typed" for r in rows}, {"asr", "typed"}),
    "sentences": (lambda rows: {r["n_sentences"] for r in rows}, {1, 2, 3, 4}),
    "outcomes": (lambda rows: {"command" if r["expected"]["refusal"] is None else "refusal" for r in rows},
                 {"command", "refusal"}),
}


@pytest.mark.parametrize("split", SPLITS)
@pytest.mark.parametrize("facet", sorted(FACETS))
def test_meaning_in_every_split(corpus, facet, split):
    values, wanted = FACETS[facet]
    assert wanted - values(corpus[split]) == set()


def test_same_stud_in_every_split(corpus):
    assert [s for s in SPLITS if "same" not in {r["meaning"]["stud"]["kind"] for r in corpus[s]}] == []


def test_single_number_sizes_somewhere(corpus):
    kinds = Counter(r["meaning"]["target"]["kind"] for r in all_rows(corpus))
    assert kinds["width"] > 0 and kinds["length"] > 0


def test_refusal_rate_and_reasons(corpus):
    paper = all_rows(corpus, PAPER_SPLITS)
    refused = [r for r in paper if r["expected"]["refusal"] is not None]
    assert 0.03 <= len(refused) / len(paper) <= 0.08
    reasons = {r["expected"]["refusal"] for r in all_rows(corpus)} - {None}
    assert len(reasons) >= 8, sorted(reasons)


# --- 6. the paper's confusions -------------------------------------------------------------
def _tags_of(rows, word):
    return {t for r in rows for w, t in zip(r["words"], r["tags"]) if w.lower() == word}


def test_middle_and_previous_are_ambiguous_in_train(corpus):
    assert {"Vr_md", "Dw_loc1", "St_loc1"} <= _tags_of(corpus["train"], "middle")
    assert {"dim", "Dw_loc2", "St_loc2"} <= _tags_of(corpus["train"], "previous")


def test_length_before_width_in_train(corpus):
    def length_first(r):
        tags = [t for t in r["tags"] if t in ("width", "length")]
        return tags[:2] == ["length", "width"]

    assert sum(map(length_first, corpus["train"])) >= 5


# --- 7. statistics ---------------------------------------------------------------------------
def test_statistics_against_paper(corpus):
    assert check_against_paper(corpus) == []
    paper = all_rows(corpus, PAPER_SPLITS)
    mean_words = sum(len(r["words"]) for r in paper) / len(paper)
    mean_sentences = sum(r["n_sentences"] for r in paper) / len(paper)
    assert abs(mean_words - 25.2) <= 3
    assert abs(mean_sentences - 1.94) <= 0.2


def test_test_split_sentence_groups(corpus):
    assert dict(Counter(r["n_sentences"] for r in corpus["test"])) == {1: 46, 2: 74, 3: 27, 4: 11}
    groups = sentence_groups(corpus["test"])
    assert (groups["ours"] == groups["paper_test"]).all()


def test_tag_table_shares(corpus):
    table = tag_table(corpus)
    assert list(table.index) == list(TAGS)
    assert table["share_%"].sum() == pytest.approx(100, abs=0.01)
    assert table["words"].sum() == sum(len(r["words"]) for r in all_rows(corpus, PAPER_SPLITS))


# --- 8. context -------------------------------------------------------------------------------
def _size_stack(site, kind, size):
    """Spec 3, target rule 2: the stack whose size matches; tried turned when nothing matches."""
    sizes = {s: (int(w), int(l)) for s, (w, l) in site.sizes.items()}
    a, b = size
    for turned in (False, True):
        if kind == "size":
            want = (b, a) if turned else (a, b)
            hits = [s for s, wl in sizes.items() if wl == want]
        elif kind == "width":
            hits = [s for s, (w, l) in sizes.items() if (l if turned else w) == a]
        else:  # length
            hits = [s for s, (w, l) in sizes.items() if (w if turned else l) == b]
        if len(hits) > 1:
            raise Refusal("ambiguous_size", f"{size} fits {hits}")
        if hits:
            return hits[0]
    raise Refusal("no_matching_size", f"{size}")


def _no_history(history):
    if not history:
        raise Refusal("no_history", "nothing installed yet")


def _resolve_target(state, history, t):
    site = state.site
    kind = t["kind"]
    if kind == "none":
        raise Refusal("undetermined", "no target")
    if kind == "id":
        return site.panel(t["panel_id"]).drywall_id
    if kind in ("size", "width", "length"):
        stack = _size_stack(site, kind, t["size"])
    elif kind == "standard":
        stack = next(s for s, (w, l) in site.sizes.items() if (w, l) == (4, 8))
    elif kind == "same":
        _no_history(history)
        stack = site.panel(history[-1]["drywall_id"]).stack
    elif kind == "absolute":
        stack = t["stack"]
    elif kind == "relative":
        if t["anchor"] == "previous":
            _no_history(history)
            anchor = site.panel(history[-1]["drywall_id"]).stack
        else:
            anchor = site.panel(t["anchor"]).stack
        i = STACK_NAMES.index(anchor) + (t["count"] if t["direction"] == "right" else -t["count"])
        if not 0 <= i < len(STACK_NAMES):
            raise Refusal("off_the_end", "no such stack")
        stack = STACK_NAMES[i]
    else:
        raise AssertionError(f"unknown target kind {kind!r}")
    top = state.top(stack)
    if top is None:
        raise Refusal("stack_empty", stack)
    return top


def _resolve_stud(site, history, s):
    n = len(site.studs)
    kind = s["kind"]
    if kind == "none":
        raise Refusal("undetermined", "no stud")
    if kind == "id":
        return site.stud(s["stud_id"]).stud_id
    if kind == "absolute":
        i = {"leftmost": 0, "rightmost": n - 1, "middle": 6}[s["name"]]
    elif kind == "from_end":
        i = s["nth"] - 1 if s["side"] == "left" else n - s["nth"]
    elif kind == "ordinal":
        i = s["nth"] - 1
    elif kind in ("same", "relative"):
        anchor = s["anchor"]
        if anchor == "previous":
            _no_history(history)
            a = site.stud(history[-1]["stud_id"]).index
        elif anchor in ("leftmost", "rightmost"):
            a = 0 if anchor == "leftmost" else n - 1
        else:
            a = site.stud(anchor).index
        count = 0 if kind == "same" else s["count"]
        i = a + (count if s.get("direction") == "right" else -count)
        if not 0 <= i < n:
            raise Refusal("off_the_end", "no such stud")
    else:
        raise AssertionError(f"unknown stud kind {kind!r}")
    return site.studs[i].stud_id


@pytest.mark.parametrize("split", SPLITS)
def test_meaning_gives_expected(corpus, split):
    """Replaying the history and mapping the meaning (spec section 3) gives the expected command or refusal."""
    site = default_site()
    for r in corpus[split]:
        history = r["context"]["history"]
        state = site.fresh().replay(history)
        m, e = r["meaning"], r["expected"]
        if e["refusal"] is None:
            command = (_resolve_target(state, history, m["target"]), _resolve_stud(site, history, m["stud"]), m["placement"])
            assert command == (e["drywall_id"], e["stud_id"], e["placement"]), r["id"]
            state.install(*command)  # raises a Refusal if the command cannot be carried out
        else:
            with pytest.raises(Refusal) as info:
                panel = _resolve_target(state, history, m["target"])
                state.check_pickable(panel)
                state.check_fits(panel, _resolve_stud(site, history, m["stud"]), m["placement"])
            assert info.value.reason == e["refusal"], (r["id"], info.value.message)


@pytest.mark.parametrize("split", SPLITS)
def test_episodes_are_consistent(corpus, split):
    rows = corpus[split]
    episodes = [k for k, _ in groupby(r["context"]["episode"] for r in rows)]
    assert len(episodes) == len(set(episodes)), "an episode's rows are not contiguous"
    for _, group in groupby(rows, key=lambda r: r["context"]["episode"]):
        group = list(group)
        assert [r["context"]["step"] for r in group] == list(range(len(group)))
        assert group[0]["context"]["history"] == []
        for prev, row in zip(group, group[1:]):
            expected = list(prev["context"]["history"])
            if prev["expected"]["refusal"] is None:
                expected.append({k: prev["expected"][k] for k in ("drywall_id", "stud_id", "placement")})
            assert row["context"]["history"] == expected, row["id"]


# --- 9. the novel split ---------------------------------------------------------------------
def _banks():
    """Every phrase bank in phrases.py: lists of templates, and dicts of such lists."""
    for name in dir(P):
        value = getattr(P, name)
        if not name.isupper():
            continue
        if isinstance(value, list) and value and all(isinstance(t, str) for t in value):
            yield name, value
        elif isinstance(value, dict) and value and all(isinstance(v, list) for v in value.values()):
            for key, bank in value.items():
                if all(isinstance(t, str) for t in bank):
                    yield f"{name}[{key}]", bank


def _template_words(template):
    return {piece.partition("/")[0].lower() for piece in template.lstrip("~").split()
            if not piece.startswith("{") and piece not in PUNCT}


def withheld_words() -> set[str]:
    """Words of withheld (``~``) templates that no shared template of any bank uses."""
    shared, withheld = set(), set()
    for _, bank in _banks():
        for t in bank:
            (withheld if t.startswith("~") else shared).update(_template_words(t))
    return withheld - shared


def test_withheld_words_found():
    words = withheld_words()
    assert {"plasterboard", "sheetrock", "fasten"} <= words
    assert len(words) >= 20


def test_novel_texts_not_in_train(corpus):
    train = {r["text"] for r in corpus["train"]}
    assert [r["id"] for r in corpus["novel"] if r["text"] in train] == []


def test_main_splits_never_use_withheld_words(corpus):
    words = withheld_words()
    leaks = Counter(w.lower() for r in all_rows(corpus, PAPER_SPLITS) for w in r["words"] if w.lower() in words)
    assert leaks == Counter()


def test_every_novel_row_uses_a_withheld_phrasing(corpus):
    words = withheld_words()
    assert [r["id"] for r in corpus["novel"] if not words & {w.lower() for w in r["words"]}] == []


def test_every_template_parses():
    slots = re.compile(r"\{(\w+)\}")
    for name, bank in _banks():
        for t in bank:
            body = t.lstrip("~")
            tokens = parse(body, **{s: parse("x") for s in slots.findall(body)})
            assert all(tok.tag in TAGS for tok in tokens if tok.is_word), (name, t)


# --- 10. the datasets loader ------------------------------------------------------------------
def test_load_corpus(corpus):
    ds = load_corpus()
    assert set(ds) == set(SPLITS)
    for split in SPLITS:
        assert ds[split].num_rows == len(corpus[split])
    tags = ds["train"].features["tags"]
    assert tags.feature.names == list(TAGS)
    assert ds["train"].features["coref_tags"].feature.names == list(COREF_TAGS)
    row = ds["train"][0]
    assert tags.feature.int2str(row["tags"]) == corpus["train"][0]["tags"]
    assert ds["train"].features["coref_tags"].feature.int2str(row["coref_tags"]) == corpus["train"][0]["coref_tags"]
    assert row["words"] == corpus["train"][0]["words"]
    assert row["expected"] == corpus["train"][0]["expected"]


# --- 11. CoNLL and tokenize ------------------------------------------------------------------
@pytest.mark.parametrize("split", SPLITS)
def test_conll_round_trip(corpus, split):
    assert from_conll(to_conll(corpus[split])) == corpus[split]


def test_conll_round_trip_through_file(corpus, tmp_path):
    path = tmp_path / "test.conll"
    to_conll(corpus["test"][:5], path)
    assert from_conll(path) == corpus["test"][:5]


def test_from_conll_by_hand():
    text = "put\tO\nit\tO\non\tO\nstud\tO\n500107\tID_stud\n\nthe\tO\nleftmost\tDw_loc1\npanel\tO\tTrg\n"
    rows = from_conll(text)
    assert len(rows) == 2
    assert rows[0]["words"] == ["put", "it", "on", "stud", "500107"]
    assert rows[0]["tags"] == ["O", "O", "O", "O", "ID_stud"]
    assert "coref_tags" not in rows[0]
    assert rows[1]["tags"] == ["O", "Dw_loc1", "O"]
    assert rows[1]["coref_tags"][2] == "Trg"
    assert rows[0]["id"] != rows[1]["id"]


def test_from_conll_unknown_tag_names_line():
    with pytest.raises(ValueError, match=r"line 3\b.*B-ID_stud"):
        from_conll("put\tO\nit\tO\n500107\tB-ID_stud\n")
    with pytest.raises(ValueError, match=r"line 2\b"):
        from_conll("put\tO\tO\nit\tO\tTarget\n")


def test_tokenize_example():
    assert tokenize("Pick up the full-size drywall, and put it on stud 500107.") == [
        "Pick", "up", "the", "full-size", "drywall", "and", "put", "it", "on", "stud", "500107"]


_word = st.from_regex(r"[A-Za-z0-9](?:[A-Za-z0-9'-]*[A-Za-z0-9])?", fullmatch=True)


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(_word, st.sampled_from(["", "", *PUNCT])), min_size=0, max_size=12),
       st.sampled_from([" ", "  ", "\t", "\n"]))
def test_tokenize_drops_edge_punctuation(pieces, sep):
    text = sep.join(w + p for w, p in pieces)
    words = [w for w, _ in pieces]
    assert tokenize(text) == words
    assert tokenize(" ".join(words)) == words


# --- 12. markup ---------------------------------------------------------------------------
def test_parse_rejects_unknown_tag():
    with pytest.raises(ValueError, match="B-ID_stud"):
        parse("put it on stud 500107/B-ID_stud")
    tokens = parse("put {it} on 500107/ID_stud .", it=parse("it/@T"))
    assert [t.word for t in tokens if t.is_word] == ["put", "it", "on", "500107"]
    assert [t.coref for t in tokens if t.is_word] == ["O", "Trg", "O", "ID_stud"]
