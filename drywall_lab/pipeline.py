"""Instructions to commands: the NLU tagger, then the IM rules, episode by episode (the paper's Fig. 1).

This is the batch contract of spec section 6 (``python -m drywall_lab run``): each
episode starts from the fresh site; a refused instruction leaves the state as it was
and the episode goes on; one JSON record per instruction.

It also holds the paper's three demonstration layouts (Figs. 15-18), written as
episodes with hand-checked tags and the commands they must give
(``data/layouts/paper_layouts.jsonl``).
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Iterable, Iterator, Mapping, Protocol, Sequence

from drywall_lab.corpus.io import read_jsonl, tokenize
from drywall_lab.corpus.markup import parse
from drywall_lab.errors import Refusal
from drywall_lab.im import ActionHistory, InformationMapper, Interpretation
from drywall_lab.nlu.normalise import Normalised, normalise
from drywall_lab.site import DATA_DIR, Site

if TYPE_CHECKING:
    from drywall_lab.decision import DecisionSettings

LAYOUTS_PATH = DATA_DIR / "layouts" / "paper_layouts.jsonl"


class WordTagger(Protocol):
    """Anything that tags word lists: the project's taggers (``drywall_lab.nlu``)."""

    def predict(self, sentences: Sequence[Sequence[str]]) -> list[list[str]]: ...


def load_tagger_option(option: str | Path | None) -> WordTagger:
    """The tagger a ``--tagger`` option names: a saved tagger's directory; the default tagger when None."""
    from drywall_lab import nlu

    return nlu.default_tagger() if option is None else nlu.load_tagger(option)


# --- episodes ---------------------------------------------------------------------------------
def parse_episode(obj: object, where: str = "episode") -> dict:
    """Check one episode ``{"id": ..., "instructions": [...]}`` (spec section 6); a ``ValueError`` saying what
    is wrong, starting with ``where``.

    The id may be a string or a number (it is written back as given); extra keys are kept.
    An instruction must be Unicode text: a JSON escape of half a surrogate pair (``"\\ud800"``)
    is not, and could not be written back as UTF-8.
    """
    if not isinstance(obj, dict):
        raise ValueError(f"{where}: an episode must be a JSON object with \"id\" and \"instructions\", "
                         f"not {type(obj).__name__}")
    missing = [k for k in ("id", "instructions") if k not in obj]
    if missing:
        raise ValueError(f"{where}: the episode has no {' or '.join(repr(k) for k in missing)}")
    if not isinstance(obj["id"], (str, int)) or isinstance(obj["id"], bool):
        raise ValueError(f"{where}: the episode id must be a string or a number, not {obj['id']!r}")
    if isinstance(obj["id"], str) and not _is_unicode_text(obj["id"]):
        raise ValueError(f"{where}: the episode id is not Unicode text (it holds half a surrogate pair)")
    instructions = obj["instructions"]
    if not isinstance(instructions, list) or not all(isinstance(i, str) for i in instructions):
        raise ValueError(f"{where}: \"instructions\" must be a list of strings")
    for number, text in enumerate(instructions, start=1):
        if not _is_unicode_text(text):
            raise ValueError(f"{where}: instruction {number} is not Unicode text (it holds half a surrogate pair)")
    return obj


def _is_unicode_text(text: str) -> bool:
    """False for a string holding a lone surrogate (JSON allows ``"\\ud800"``; UTF-8 cannot carry it)."""
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        return False
    return True


def read_episodes(path: Path | str) -> list[dict]:
    """Episodes from a JSON-lines file (spec section 6), one per line, read by ``corpus.io.read_jsonl``:
    UTF-8 with or without a byte-order mark, blank lines skipped, every error naming its line."""
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"no episodes file at {path}")
    if path.is_dir():
        raise ValueError(f"{path} is a folder, not an episodes file")
    return read_jsonl(path, parse_episode)


def contract_record(episode_id: str | int, step: int, result: Interpretation, said: Normalised | None = None) -> dict:
    """One output line of ``run`` (spec section 6): the worker's own words (``said``, the front end's reading of
    the instruction) with the tags of the words they became; without ``said``, the words as interpreted."""
    return {
        "episode": episode_id,
        "step": step,
        "words": list(said.said) if said else list(result.words),
        "tags": said.tags_of_said(result.tags) if said else list(result.tags),
        "command": result.command.as_contract() if result.command else None,
        "refusal": None if result.command else result.refusal.message,
    }


#: The longest instruction read (words, characters): a longer one is refused before tagging (``run``, ``chat``,
#: ``dialogue``), so that a pasted page costs neither time nor memory.
MAX_INSTRUCTION_WORDS = 200
MAX_INSTRUCTION_CHARS = 2000


def too_long(text: str) -> Refusal | None:
    """The refusal of an instruction too long to be one instruction, or None."""
    n_words = len(text.split())
    if n_words > MAX_INSTRUCTION_WORDS or len(text) > MAX_INSTRUCTION_CHARS:
        return Refusal("undetermined", f"That is {n_words:,} words ({len(text):,} characters): I read one instruction "
                                       f"of at most {MAX_INSTRUCTION_WORDS} words and {MAX_INSTRUCTION_CHARS:,} "
                                       "characters. Which panel should I pick, and which stud does it go on?")
    return None


def read_instructions(instructions: Sequence[str]) -> list[Normalised]:
    """Each instruction read by the front end (``drywall_lab.nlu.normalise``): what the tagger and the IM read; an
    instruction that is ``too_long`` is only split into words, as said (it is refused, never tagged)."""
    return [_as_said(text) if too_long(text) else normalise(text) for text in instructions]


def _as_said(text: str) -> Normalised:
    words = tuple(tokenize(text))
    return Normalised(words, words, tuple((i,) for i in range(len(words))), ())


def run_episode(episode: Mapping, tagger: WordTagger, site: Site | None = None,
                settings: "DecisionSettings | None" = None,
                read: Sequence[Normalised] | None = None) -> list[Interpretation]:
    """Read every instruction of the episode through the front end, tag them (one batch), then decide them in
    order on a fresh site. Each interpretation's trace starts with what the front end changed.

    A tagger with confidence (``predict_confidence``, both of the project's taggers) goes through the
    decision layer (``drywall_lab.decision``: IM-aware decoding; a question, refusal reason ``unclear``,
    instead of a guess) with ``settings`` (default ``DEFAULT_SETTINGS``; ``BEST_PATH`` acts on the single
    best tag sequence, as the paper does). Any other tagger's tags are mapped as they are.
    ``read``: the instructions already read by ``read_instructions``.
    """
    from drywall_lab.decision import DEFAULT_SETTINGS, decide_episode

    read = read_instructions(episode["instructions"]) if read is None else read
    long = [too_long(text) for text in episode["instructions"]]
    words = [[] if refusal else list(n.words) for n, refusal in zip(read, long)]  # a refused one is never tagged
    if hasattr(tagger, "predict_confidence"):
        history = ActionHistory(site)
        results = [d.interpretation for d in decide_episode(words, tagger, settings or DEFAULT_SETTINGS, history)]
    else:
        tags = tagger.predict(words) if words else []
        mapper = InformationMapper(site)
        results = [mapper.apply(w, t) for w, t in zip(words, tags)]
    for k, (n, result) in enumerate(zip(read, results)):
        result.trace.steps[:0] = n.trace_steps()
        if long[k] is not None:
            results[k] = Interpretation(list(n.words), ["O"] * len(n.words), result.trace, None, long[k])
    return results


def run_episodes(episodes: Iterable[Mapping], tagger: WordTagger, site: Site | None = None,
                 settings: "DecisionSettings | None" = None) -> Iterator[dict]:
    """The ``run`` output records, episode after episode (spec section 6)."""
    for episode in episodes:
        read = read_instructions(episode["instructions"])
        for step, result in enumerate(run_episode(episode, tagger, site, settings, read=read)):
            yield contract_record(episode["id"], step, result, read[step])


# --- the paper's layouts ---------------------------------------------------------------------------
def paper_layouts(path: Path | str = LAYOUTS_PATH) -> list[dict]:
    """The three layouts of Figs. 15-18 as episodes, with gold ``words``/``tags`` and ``expected`` outcomes.

    Each step's ``expected`` is a command ``{"drywall_id", "stud_id", "placement"}`` or
    ``{"refusal": reason}``.
    """
    layouts = read_episodes(path)
    for layout in layouts:
        tokens = [[t for t in parse(markup) if t.is_word] for markup in layout["tagged"]]
        layout["words"] = [[t.word for t in ts] for ts in tokens]
        layout["tags"] = [[t.tag for t in ts] for ts in tokens]
    return layouts


def map_gold_episode(layout: Mapping, site: Site | None = None) -> tuple[list[Interpretation], ActionHistory]:
    """Map a layout's gold-tagged instructions in order: the IM on its own, no tagger."""
    mapper = InformationMapper(site)
    results = [mapper.apply(w, t) for w, t in zip(layout["words"], layout["tags"])]
    return results, mapper.history
