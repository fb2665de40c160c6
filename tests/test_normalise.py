"""The front end before tagging (drywall_lab/nlu/normalise.py): forms read, alignment kept, nothing invented."""
from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from drywall_lab.corpus import field_generator as FG
from drywall_lab.corpus.io import tokenize
from drywall_lab.nlu import normalise as N


@pytest.mark.parametrize("said, read", [
    ("put it on stud five oh oh one oh four", "put it on stud 500104"),
    ("five hundred one-oh-eight", "500108"),
    ("five double-oh one one two", "500112"),
    ("five oh oh three twenty", "500320"),
    ("on 500 104 please", "on 500104 please"),
    ("500-104", "500104"),
    ("#500104", "500104"),
    ("stud no. 500103", "stud 500103"),
    ("radio two, five double-oh three one two", "radio two 500312"),
    ("ON NUMBER 500 107 TEN MINUTES AGO", "ON NUMBER 500107 TEN MINUTES AGO"),
    # digits as radio operators say them, alone and inside an id
    ("stud five-zero-zero-one-zero-fife, tree studs over", "stud 500105 three studs over"),
    ("five zero zero tree wun niner", "500319"),
    # two numbers of hundreds
    ("start from stud five hundred one hundred six", "start from stud 500106"),
    ("five hundred three hundred twenty standing", "500320 standing"),
    ("five hundred one hundred twelve", "500112"),
    ("stud five hundred four", "stud five hundred four"),  # a number, not an id
])
def test_ids_as_people_say_and_type_them_are_six_digits(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said, read", [
    ("stud five oh oh one one- no, one one one", "stud 500111"),
    ("five oh oh one seven- sorry one one one", "500111"),
    ("on five oh oh one oh- I mean one one two", "on 500112"),
])
def test_an_id_broken_off_and_repaired_is_the_repair(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said, read", [
    ("the two-by-eights", "the two-by-eight"),
    ("one of the 4x6s", "one of the 4x6"),
    ("the four by eights", "the four by eight"),
    ("two studs over", "two studs over"),  # counts stay as said
    ("the third pile", "the third pile"),
    ("one of those", "one of those"),
    ("the one you just used", "the one you just used"),
])
def test_sizes_in_the_plural_name_one_panel_and_counts_stay_as_said(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said, read", [
    ("hang a 1200x2400 sheet on 500104", "hang a 4x8 sheet on 500104"),
    ("a sheet of 600 millimetres by 2400", "a sheet of 2 ft by 8"),
    ("the 1.2 m x 1.8 m board", "the 4 ft x 6 ft board"),
    ("120 cm by 240 cm", "4 ft by 8 ft"),
    ("2400 mm long by 1200 wide", "8 ft long by 4 wide"),
    ("a 1,200 by 2,400 one", "a 4 by 8 one"),
    ("one 1.2m wide", "one 4ft wide"),
    ("fix with 25 mm screws at 406 mm centres", "fix with 25 mm screws at 406 mm centres"),  # no board's side
    ("keep 1200 clear of the door", "keep 1200 clear of the door"),  # a lone number without a unit
    ("two by 4 x 8 then", "two by 4 x 8 then"),  # feet stay feet
    ("2nd frm r", "2nd frm right"),  # a texted "from" before a side letter
])
def test_metric_sides_are_read_as_the_feet_they_stand_for(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said, read", [
    ("a twelve hundred by twenty four hundred sheet", "a 4 by 8 sheet"),
    ("the twelve hundred by twenty-four hundred", "the 4 by 8"),
    ("six hundred mil wide", "2 ft wide"),
    ("one point two by one point eight metres", "4 by 6 ft"),
    ("the one point two two by two point four four", "the 4 by 8"),
    ("point six by two point four", "2 by 8"),
    ("twelve hundred", "twelve hundred"),  # a lone number, said in words
    ("one point two", "one point two"),
    ("two point five by eight", "two point five by eight"),  # no board's side
    ("stud five hundred one twelve", "stud 500112"),  # an id, not a side
    ("the one point on the left", "the one point on the left"),
])
def test_metric_sides_said_in_words_are_read_too(said, read):
    assert N.normalise_text(said) == read


def test_a_side_said_in_words_keeps_the_workers_words_for_its_tag():
    n = N.normalise("put the twelve hundred by twenty four hundred sheet on 500104")
    assert n.words == ("put", "the", "4", "by", "8", "sheet", "on", "500104")
    assert [str(c) for c in n.changes] == ["metric: 'twelve hundred' -> '4'", "metric: 'twenty four hundred' -> '8'"]
    assert n.tags_of_said(["O", "O", "width", "O", "length", "O", "O", "ID_stud"]) == \
        ["O", "O", "width", "width", "O", "length", "length", "length", "O", "O", "ID_stud"]


@pytest.mark.parametrize("said, read", [
    ("PNL: 2x8 | STUD: 500106 | BTM", "panel 2x8 | STUD 500106 | bottom"),
    ("Stud:500104 -> vert w/ CL", "Stud 500104 -> vertical with centre line"),
    # a program's fields: "=", brackets, "_" and a leading "--" glue words; alone they stay
    ("place(panel=500321, stud=500100, edge=centre_line)", "place panel 500321 stud 500100 edge centre line"),
    ("hang --stack middle --stud 500104", "hang stack middle stud 500104"),
    ("stud = 500104", "stud = 500104"),
    # a position typed as one word with hyphens; a hyphenated word that is no position stays
    ("--stud 3rd-from-right", "stud 3rd from right"),
    ("the second-to-last stud, one-to-the-left of 500105", "the second to last stud one to the left of 500105"),
    ("the left-hand pile, a four-by-eight", "the left-hand pile a four-by-eight"),
    ("2nd from R", "2nd from right"),
    ("one to the r of 500301", "one to the right of 500301"),
    ("u r fast", "u r fast"),  # a texted "are" is no side
    ("on the c/l", "on the centre line"),
])
def test_shorthand_is_read_from_the_lexicon(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said, read", [
    ("um put it, you know, on 500104", "put it on 500104"),
    ("grab, like, the 2x8", "grab the 2x8"),
    ("like the previous one", "like the previous one"),  # a back-reference, not a filler
    ("the- the four-by-six on 500101", "the four-by-six on 500101"),
    ("the four by- no, the two by eight", "the two by eight"),
    ("take a 4x- sorry 2x8", "take a 2x8"),
])
def test_fillers_and_false_starts_go_the_final_intention_stays(said, read):
    assert N.normalise_text(said) == read


def test_a_repair_starts_again_only_from_the_words_just_before_the_break():
    text = "I said the 4 feet wide one but I meant one of the 6 feet long x six- I mean 4 feet wide boards"
    assert N.normalise_text(text).endswith("I meant one of the 6 feet long x 4 feet wide boards")


def test_the_alignment_gives_the_workers_words_their_tags_and_the_trace_says_what_changed():
    n = N.normalise("uh put it on five oh oh one oh four CL")
    assert n.said == tuple(tokenize("uh put it on five oh oh one oh four CL"))
    assert n.words == ("put", "it", "on", "500104", "centre", "line")
    tags = ["O", "O", "O", "ID_stud", "Vr_md", "Vr_md"]
    assert n.tags_of_said(tags) == ["O", "O", "O", "O"] + ["ID_stud"] * 6 + ["Vr_md"]
    assert n.tags_of_words(n.tags_of_said(tags)) == tags
    kinds = [step.conclusion.split(":")[0] for step in n.trace_steps()]
    assert kinds == ["shorthand", "filler", "id"]
    with pytest.raises(ValueError, match="tags for"):
        n.tags_of_said(["O"])


@pytest.mark.parametrize("said, read", [
    ("agarra la placa de la derecha y ponla en el poste 500105, línea central",
     "grab the board on the right and put it on the stud 500105 centre line"),
    ("pues the 2x8 en la fila de abajo, desde el 500100", "the 2x8 on the bottom row from the 500100"),  # a filler goes
    ("una HOJA de cuatro por ocho, parada, linea del centro", "a sheet of four by eight upright centre line"),  # any case, no accents
    ("stud cinco cero cero uno cero seis", "stud 500106"),  # a Spanish id is read as one
    ("la misma size, dos studs a la izquierda del anterior", "the same size two studs to the left of the previous one"),
    ("nimm die Platte vom linken Stapel, hochkant auf Ständer 500103", "take the panel from the left pile upright on stud 500103"),
    ("eine schmale, quer in der unteren Reihe, ab dem ersten Staender", "a narrow lying flat in the bottom row from the first stud"),
    ("pogne une feuille quatre par huit pis mets-la debout", "grab a sheet four by eight and put it upright"),
    ("sur le montant cinq zéro zéro un zéro six", "on the stud 500106"),  # "zéro" is "zero", "un" one
    ("en likadan, tre stolpar åt vänster", "another of the same size three studs to the left"),  # Swedish
    ("fem noll noll ett noll fyra", "500104"),  # Swedish digits, read as an id
    ("hent en halv plate fra høyre stabel", "grab a half panel from the right pile"),  # Norwegian
    ("læg en gipsplade på stolpe 500105 i øverste række", "lay a drywall panel on stud 500105 in the top row"),  # Danish
])
def test_another_language_mixed_in_is_read_in_english(said, read):
    assert N.normalise_text(said) == read


def test_a_spanish_phrase_keeps_the_workers_words_for_its_tag():
    n = N.normalise("la pila de la izquierda")
    assert n.words == ("the", "pile", "on", "the", "left")
    tags = ["O", "O", "Dw_loc1", "Dw_loc1", "Dw_loc1"]
    assert n.tags_of_said(tags) == ["O", "O", "Dw_loc1", "Dw_loc1", "Dw_loc1"]
    assert [step.conclusion for step in n.trace_steps()][-1] == "code switch: 'de la izquierda' -> 'on the left'"


def test_no_code_switch_form_is_a_word_of_the_training_corpus():
    """The code-switch lexicon holds no word an English instruction uses: no training row says one of its forms, in
    its text as written or in the words the tagger reads."""
    table = N._code_switch_table()
    longest = max(map(len, table))
    for row in FG.field_split("train"):
        for words in (tokenize(row["text"]), row["words"]):
            folded = [N.fold(w) for w in words]
            written = [N.as_written(w) for w in words]
            for i in range(len(folded)):
                if folded[i] in N.DIGITS_ONLY_IN_A_RUN:  # "um" is a filler there, and the front end reads it so
                    assert not N._in_foreign_number(folded, i), (row["id"], folded[i])
                    continue
                assert not any(tuple(f[i:i + n]) in table for n in range(1, longest + 1) for f in (folded, written)), \
                    (row["id"], folded[i])


@pytest.mark.parametrize("said, read", [
    ("stud cinco zero zero um zero cinco", "stud 500105"),  # Portuguese "um" is one inside a Portuguese number
    ("stud cinco zero zero um zero meia", "stud 500106"),  # and "meia" six
    ("stud five oh oh one um oh three", "stud 500103"),  # an English filler inside an English number
    ("stud five zero zero one zero um three", "stud 500103"),
    ("um put it on um um stud 500104", "put it on stud 500104"),
    ("meia folha", "meia sheet"),  # "half", not six, outside a number
])
def test_a_digit_word_that_means_something_else_is_read_as_a_digit_only_in_its_languages_number(said, read):
    assert N.normalise_text(said) == read


def test_a_bad_lexicon_line_is_named(tmp_path):
    bad = tmp_path / "lexicon.tsv"
    bad.write_text("CL\tcentre line\n", encoding="utf-8")
    with pytest.raises(ValueError, match="entry 1"):
        N.read_lexicon(bad)
    bad.write_text("pila\n", encoding="utf-8")
    with pytest.raises(ValueError, match="entry 1 must be FORM<TAB>READING<TAB>LANGUAGE"):
        N.read_code_switch(bad)
    bad.write_text("pila\tpile\tes\npila\tstack of sheets\tit\n", encoding="utf-8")
    with pytest.raises(ValueError, match="'pila' is read as 'pile' and as 'stack of sheets'"):
        N._code_switch_table(bad)



def test_a_language_whose_accents_tell_words_apart_is_matched_only_as_written(tmp_path):
    lexicon = tmp_path / "lexicon.tsv"
    lexicon.write_text("năm\tfive\tvi\nnằm\tflat\tvi\nbảy\tseven\tvi\npila\tpile\tes\n", encoding="utf-8")
    N._code_switch_table(lexicon)  # "năm" and "nằm" fold alike and read differently: no conflict

    def read(text):
        return " ".join(p.word for p in N.translate_code_switch([N.Piece(w, (k,)) for k, w in enumerate(text.split())],
                                                                [], lexicon))
    assert read("NĂM nằm bảy Pila píla") == "five flat seven pile pile"
    assert read("nam bay") == "nam bay"  # without its accents a Vietnamese form is another word ("bay" in English)


_WORDS = st.sampled_from(["put", "the", "2x8s", "on", "five", "oh", "one", "double", "hundred", "-", "|", "no", "um",
                          "CL", "r", "L", "by-", "the-", "500", "104", "#500104", "like,", "stud", "eight", "twenty",
                          "sorry", "I", "mean", "4x", "x", "you", "know", "", "!", "->", "la", "de", "izquierda",
                          "al", "lado", "pues", "noch", "eine", "Ständer", "cinco", "cero", "por"])


@settings(max_examples=300, deadline=None)
@given(st.lists(_WORDS, max_size=14))
def test_every_word_read_comes_from_the_workers_words_in_order(words):
    n = N.normalise(" ".join(words))
    assert n.said == tuple(tokenize(" ".join(words)))
    assert len(n.words) == len(n.sources)
    # in order: a word read comes from no earlier words than the one before it (the words of a phrase read as a
    # phrase, "la de" -> "the one", all come from the whole phrase; only ``anchor_last`` and ``read_star_corrections``
    # move words, an anchor said before its step and a starred value, which these words never make)
    assert all(0 <= i < len(n.said) for sources in n.sources for i in sources)
    assert all(list(s) == sorted(s) for s in n.sources)
    assert all(a[0] <= b[0] and a[-1] <= b[-1] for a, b in zip(n.sources, n.sources[1:]) if a and b)
    assert all(w and not w.isspace() for w in n.words)
    assert len(n.tags_of_said(["O"] * len(n.words))) == len(n.said)


@pytest.mark.parametrize("split", FG.COMMITTED_SPLITS)
def test_a_corpus_row_holds_the_words_the_front_end_reads_from_its_text(split):
    """Training and prediction read the same words: each committed row is its text through the front end."""
    rows = FG.field_split(split)
    assert all(list(N.normalise(r["text"]).words) == r["words"] for r in rows)


@pytest.mark.parametrize("said, read", [
    ("stud=prev+2", "stud 2 to the right of the previous stud"),
    ("on prev + 3", "on 3 to the right of the previous stud"),
    ("last -1", "1 to the left of the last stud"),
    ("500104-1", "1 to the left of 500104"),
    ("500104 +2", "2 to the right of 500104"),
    ("- 500321 - 1 back", "500321 1 back"),  # dashes between a form's fields: no sum
    ("+2", "+2"),  # counted from what? left as written
    ("prev stud +5", "5 to the right of the previous stud"),  # "stud" between the anchor and the sign
    ("last stud - 2", "2 to the left of the last stud"),
])
def test_a_stud_written_as_a_sum_is_read_in_words(said, read):
    assert N.normalise_text(said) == read


def test_the_words_of_a_sum_take_their_parts_tags_in_a_corpus_row():
    n = N.normalise("on prev+2")
    assert n.tags_of_words(["O", "St_loc1"]) == ["O", "St_loc1", "St_loc1", "St_loc1", "St_loc1", "O", "O",
                                                  "St_loc2", "O"]
    assert n.tags_of_said(n.tags_of_words(["O", "St_loc1"])) == ["O", "St_loc1"]  # the worker's word: its first tag
    n = N.normalise("500104-1")
    assert n.tags_of_words(["St_loc1"])[-1] == "St_loc2"  # the id keeps its part through read_ids


@pytest.mark.parametrize("said, read", [
    ("place(size=same, stud=first)", "place same size first stud"),
    ("row: top", "row top"),  # apart, not glued: left alone
    ("row:top", "top row"),
    ("stud=500104", "stud 500104"),
    ("edge=five", "edge five"),  # a number is a value, not a word that says which
])
def test_a_label_typed_before_a_one_word_value_is_read_in_spoken_order(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said, read", [
    ("stand it on stud 500101, er, 500100, sorry", "stand it on stud 500100"),  # a pause and a cue after
    ("stud 500101 er 500100 sorry", "stud 500100"),  # a filler is a pause
    ("four studs to the left— right, I mean right— of the last stud", "four studs to the right of the last stud"),
    ("flat in the bottom row— top row", "flat in the top row"),  # broken off, no cue: the value and its noun
    ("the third, no, the fourth stud", "the fourth stud"),
    ("top or the- the bottom row", "top or the bottom row"),  # two things offered: a question, not a repair
    ("on stud 500105— no, one more over to the right, 500106", "on stud 500106"),  # and how the new lies from it
    ("stud 500109 no two over to the left 500107", "stud 500107"),
    ("on stud 500104, 500105", "on stud 500104 500105"),  # no break, no cue: two studs, for the IM to ask
    ("put it on the left, right?", "put it on the left right"),  # a tag question, not a repair
])
def test_a_value_taken_back_by_another_of_its_kind_is_dropped(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said, read", [
    ("line;panel;stud;orientation\n1;500320;500100;vertical", "panel 500320 stud 500100 vertical orientation"),
    ("qty, size, from_stack, stud\n1, 2x8, middle, 500104\nthanks", "size 2x8 middle stack stud 500104 thanks"),
    ("item\tdate\tsize\tstud\tedge\n6\t07/12\t2x8\tprev stud +5\tcentre line",
     "size 2x8 stud 5 to the right of the previous stud edge centre line"),
    ("pasted from the sheet:\nline|panel|stud\n3|500321|500106", "pasted from the sheet panel 500321 stud 500106"),
    ("stud 500,104 please\nand the 4x8", "stud 500104 please and the 4x8"),  # two lines, no table
    ("put it on 500104, centre line, then go", "put it on 500104 centre line then go"),  # commas in a sentence
])
def test_a_table_pasted_from_a_spreadsheet_is_read_as_a_forms_words(said, read):
    assert N.normalise_text(said) == read


def test_a_tables_header_gives_its_words_to_the_labels_and_a_row_number_is_dropped():
    n = N.normalise("line;panel;stud\n2;500321;500103")
    assert n.said == ("line;panel;stud", "2;500321;500103")
    assert n.words == ("panel", "500321", "stud", "500103")
    assert n.sources == ((0,), (1,), (0,), (1,))
    assert [c.kind for c in n.changes].count("table") == 4  # the header, the row number dropped, two fields


@pytest.mark.parametrize("said, read", [
    ("from the previous stud, two studs to the right", "two studs to the right of the previous stud"),
    ("starting at 500104 go three right", "three right of 500104"),
    ("counting from 500102 stud two to the left", "two to the left of 500102 stud"),
    ("from the 4th stud three over to the left", "three over to the left of the 4th stud"),
    ("from the fourth from the right end one to the right", "one to the right of the fourth from the right end"),
    ("the last one, two to the left", "two to the left of the last one"),  # no lead: an anchor that points back
    ("500104 two to the left", "500104 two to the left"),  # no lead, an id: the end of another field
    ("on the last stud two more right", "on the last stud two more right"),  # inside "on the ...": no anchor
    ("take it from the left stack two studs right", "take it from the left stack two studs right"),  # a stack
    ("the fourth stud from the right", "the fourth stud from the right"),  # no step after it
    ("from the previous stud two to the right of 500104", "from the previous stud two to the right of 500104"),
])
def test_an_anchor_said_before_its_step_is_read_after_it(said, read):
    assert N.normalise_text(said) == read


def test_an_anchor_moved_after_its_step_keeps_its_words_tags():
    n = N.normalise("from the previous stud two studs to the right")
    said_tags = ["O", "O", "St_loc2", "O", "St_loc1", "O", "St_loc1", "St_loc1", "St_loc1"]
    assert n.words == ("two", "studs", "to", "the", "right", "of", "the", "previous", "stud")
    assert n.tags_of_words(said_tags) == ["St_loc1", "O", "St_loc1", "St_loc1", "St_loc1", "O", "O", "St_loc2", "O"]
    assert n.tags_of_said(n.tags_of_words(said_tags)) == said_tags  # "from" was dropped: O
    assert [c.kind for c in n.changes] == ["anchor first"]


@pytest.mark.parametrize("said, read", [
    ("[07:09] Kev: full sheet off the left\n[07:10] Kev: stand it on 500104", "full sheet off the left stand it on 500104"),
    ("12/07/2026, 07:09:11 - Sam Ortiz: grab the 2x8", "grab the 2x8"),
    ("Dave (12:30): grab the 2x8", "grab the 2x8"),
    ("at 12:30 put it on 500104", "at 12 30 put it on 500104"),  # a time inside the instruction stays
    ("12:30 Put the 2x8 on 500104", "12 30 Put the 2x8 on 500104"),  # no colon after a name: no header
    ("Note: put the 2x8 on 500104", "Note put the 2x8 on 500104"),  # a label with no time: no header
])
def test_a_chat_messages_header_is_dropped(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said, read", [
    ("stand it on the centre line of 500104\n*500105", "stand it on the centre line of 500105"),
    ("the left pile, fourth stud *third", "the left pile third stud"),
    ("grab a 2x8 *4x8 from the middle", "grab a 4x8 from the middle"),
    ("*500105 is the stud", "500105 is the stud"),  # nothing of its kind before it: the star goes
])
def test_a_starred_value_takes_the_place_of_the_last_of_its_kind(said, read):
    assert N.normalise_text(said) == read


def test_a_phrase_of_the_lexicon_never_runs_across_a_comma(tmp_path):
    lexicon = tmp_path / "lexicon.tsv"
    lexicon.write_text("hàng trên cùng\ttopmost row\tvi\nhàng trên\ttop row\tvi\ncùng stud\tthe same stud\tvi\n",
                       encoding="utf-8")

    def read(text):
        return " ".join(p.word for p in N.translate_code_switch(N._pieces(text)[1], [], lexicon))
    assert read("hàng trên cùng") == "topmost row"
    assert read("hàng trên, cùng stud") == "top row the same stud"


@pytest.mark.parametrize("said, read", [
    ("the top row from the first stud, no. bottom row", "the bottom row from the first stud"),
    ("on 500111... nah that'd hang past the end, 500110, centre line", "on 500110 centre line"),
    ("put the 4x8 on 500105, no wait that one is taken, 500106 then", "put the 4x8 on 500106 then"),
    ("on the second stud from the right. sorry, wrong one, the fourth from the right", "on the fourth stud from the right"),
    # a cue between commas is read where it is said, or left to the tagger; a "no" that is no cue stays
    ("the third stud from the left, no, from the right", "the third stud from the left no from the right"),
    ("the top row, no gaps, bottom edge flush", "the top row no gaps bottom edge flush"),
    # the nearest value that names the stud is an ordinal: the panel's id is not what was taken back
    ("the 2x8 500321 at stud 3rd from the right. no, 500108", "the 2x8 500321 at stud 3rd from the right no 500108"),
    ("stud no. 500104 please", "stud 500104 please"),  # "no." before a number is a label
])
def test_a_value_taken_back_late_gives_way_to_the_value_meant(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said, read", [
    ("Subject: RE: East wall, L4\n\nput the 2x8 on 500104\n\n> are we doing 500107 first?\n> Raj\n\nDana | PM",
     "put the 2x8 on 500104"),
    ("Subject: Level 2\n\nHi all,\nthe full sheet on 500100, upright.\n\nThanks,\nDana\nSent from my iPhone",
     "Hi all the full sheet on 500100 upright"),
    ("> top row or bottom?\n\nbottom row, 4x6 from the right, stud 500102\n\nP. Shah | Site Super\nOffice 555-0117",
     "bottom row 4x6 from the right stud 500102"),
    # no blank line before the last line: it is the instruction's, not a sign-off
    ("grab the 2x8 from the middle\nCentre Line", "grab the 2x8 from the middle Centre Line"),
])
def test_an_emails_header_quoted_lines_and_sign_off_are_dropped(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said, read", [
    ("MIKE: the full sheet on 500104, centre line. DAVE: nah, 500103. MIKE: ok.", "the full sheet on 500103 centre line"),
    ("Ana: 2x8 in the top row. Sam Ortiz: nope, wrong one, bottom", "2x8 in the bottom row"),
    ("Note: put the 2x8 on 500104. Also: centre line", "Note put the 2x8 on 500104 Also centre line"),  # notes
    ("Kev: put the 2x8 on 500104", "Kev put the 2x8 on 500104"),  # one label alone is no conversation
])
def test_a_conversations_speaker_labels_are_dropped_and_an_overruled_value_gives_way(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said", ["500104'e", "500104’ye", "500104-го", "500104-й"])
def test_an_id_with_a_case_ending_is_read_as_the_id(said):
    assert N.normalise_text(f"put it on {said} stud") == "put it on 500104 stud"


def test_an_ids_english_possessive_is_no_case_ending():
    assert N.normalise_text("500100's covered") == "500100's covered"


@pytest.mark.parametrize("said, read", [
    ("MIKE: the full sheet on 500104, centre line. DAVE: nah, 500103. MIKE: yeah fair, 500103.",
     "the full sheet on 500103 centre line"),
    ("DAVE: the 2x8, flat, top row, from 500106. MIKE: top row, yep.", "the 2x8 flat top row from 500106"),
    ("MIKE: the 2x8 on 500104. DAVE: uh, copy, on it.", "the 2x8 on 500104"),
    # a turn that says something new stays
    ("MIKE: the 2x8 on 500104. DAVE: yep, centre line.", "the 2x8 on 500104 yep centre line"),
])
def test_a_turn_that_only_agrees_or_says_a_value_again_is_dropped(said, read):
    assert N.normalise_text(said) == read


@pytest.mark.parametrize("said, read", [
    ("500320号板，竖着装在500100龙骨上。", "500320 panel install it upright on 500100 stud"),
    ("中间那摞拿一张窄的，竖着装在500106上", "the middle stack take a narrow one install it upright on 500106"),
    ("５００１０４", "500104"),  # full-width digits
    ("stud ٥٠٠١٠٤، ۵۰۰۱۰۴", "stud 500104 500104"),  # Arabic-Indic digits, the Arabic comma
    ("500104에", "500104"),  # a Korean particle written on the id
])
def test_chinese_typed_without_spaces_other_digits_and_particles_on_ids_are_read(said, read):
    assert N.normalise_text(said) == read


def test_a_script_without_spaces_is_cut_by_the_longest_form_and_where_scripts_meet(tmp_path):
    lexicon = tmp_path / "lexicon.tsv"
    lexicon.write_text("左边\tleft\tzh\n左边那摞\tthe left stack\tzh\n从\tfrom\tzh\n龙骨\tstud\tzh\n", encoding="utf-8")
    assert N.segment_unspaced("从左边那摞", lexicon) == ["从", "左边那摞"]  # the longest form wins
    assert N.segment_unspaced("从左边拿", lexicon) == ["从", "左边", "拿"]
    assert N.segment_unspaced("拿走从", lexicon) == ["拿走", "从"]  # characters no form starts stay together
    assert N.split_unspaced("在500106龙骨上,", lexicon) == ["在", "500106", "龙骨", "上,"]  # a mark stays with its word
    assert N.split_unspaced("stud#5", lexicon) == ["stud#5"]  # no such script: one word


def test_the_workers_words_in_chinese_are_the_words_the_front_end_cut():
    n = N.normalise("从左边那摞拿一张")
    assert len(n.said) > 1 and "".join(n.said) == "从左边那摞拿一张"


@pytest.mark.parametrize("said, read", [
    ("edge on the left-line of stud 500104", "edge on the left line of stud 500104"),
    ("the far-right stud, bottom-row", "the far right stud bottom row"),
    ("the stud-vert one", "the stud vertical one"),  # taken apart before the shorthand is read
    ("the left-hand pile", "the left-hand pile"),  # a word the IM reads whole
    ("the four-by-six", "the four-by-six"),  # a size: its parts are numbers (read as a size where one is due)
    ("re-hang the top-most sheet", "re-hang the top-most sheet"),  # bound parts
    ("an x-ray", "an x-ray"),  # a part of one letter
    ("pose-la sur 500104", "put it on 500104"),  # a lexicon form: read whole
])
def test_a_compound_typed_with_hyphens_is_read_as_its_words(said, read):
    assert N.normalise_text(said) == read


def test_a_compounds_words_come_from_the_workers_one_word():
    said = N.normalise("edge on the centre-line")
    assert said.said[-1] == "centre-line" and said.words[-2:] == ("centre", "line")
    assert said.sources[-2:] == ((3,), (3,))
    assert said.tags_of_said(["O", "O", "O", "Vr_md", "Vr_md"]) == ["O", "O", "O", "Vr_md"]
