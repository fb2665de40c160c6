"""The batch contract carried through the robot: ``python -m drywall_lab simulate EPISODES.jsonl``.

Spec section 6 defines ``run``: one episode a line in, one JSON line per instruction out with the
episode, the step, the words, the tags, the command (or null) and the refusal (or null). ``simulate``
writes the same fields and adds ``placement``, what the simulated robot did with the instruction
(``drywall_lab.rc.episode``: tagged, interpreted and carried out one instruction at a time, each
episode from the fresh site):

- ``status``: ``placed``, ``failed``, ``refused`` (IM refused it: nothing moved) or ``not carried out``
  (an earlier failure stopped the robot; the instruction was neither tagged nor interpreted, so its
  ``tags``, ``command`` and ``refusal`` are null);
- ``success``: the panel was placed within tolerance (``POSITION_TOLERANCE``, ``ANGLE_TOLERANCE_DEG``)
  with no unexpected contact;
- ``position_error_mm``, ``angle_error_deg``: measured on the simulated panel at the end of the step
  (null when nothing moved);
- ``collisions``: the unexpected contacts, each ``{"between": [geom, geom], "stage", "time_s", "depth_mm"}``;
- ``failure``: why it failed (``drywall_lab.rc.placement``'s reason, e.g. ``off_pose``, or
  ``unreachable: ...``), or why it was not carried out; null otherwise;
- ``sim_time_s``: simulated seconds the step took.
"""
from __future__ import annotations

from typing import Iterable, Iterator, Mapping

from drywall_lab.corpus.io import tokenize
from drywall_lab.pipeline import WordTagger, contract_record
from drywall_lab.rc.contacts import ContactEvent
from drywall_lab.rc.episode import NOT_CARRIED_OUT, EpisodeRun, EpisodeStep, simulate_episode


def collision_record(event: ContactEvent) -> dict:
    """One unexpected contact as JSON: the two geoms, the stage, when it was first seen and how deep it went."""
    return {"between": [event.geom1, event.geom2], "stage": event.stage, "time_s": round(event.first_time, 3),
            "depth_mm": round(1000 * event.max_depth, 3)}


def placement_record(step: EpisodeStep, stopped_after: int | None = None) -> dict:
    """What the robot did with one instruction (see the module's docstring)."""
    status, result = step.status, step.result
    record = {"status": status, "success": bool(result is not None and result.success),
              "position_error_mm": None, "angle_error_deg": None, "collisions": [], "failure": None,
              "sim_time_s": round(step.sim_time_after - step.sim_time_before, 3)}
    if status == NOT_CARRIED_OUT:
        record["failure"] = f"not carried out: the robot stopped after step {stopped_after}"
    elif result is not None:
        record.update(position_error_mm=round(result.position_error_mm, 3),
                      angle_error_deg=round(result.angle_error_deg, 4),
                      collisions=[collision_record(e) for e in result.unexpected_contacts], failure=result.failure)
    return record


def simulation_records(run: EpisodeRun, episode_id: str | int | None = None) -> list[dict]:
    """The output lines of ``simulate`` for one simulated episode: the ``run`` fields and ``placement``.

    ``episode_id`` is written as given (a number stays a number); the run's own id when None.
    """
    episode_id = run.episode_id if episode_id is None else episode_id
    records = []
    for step in run.steps:
        if step.interpretation is None:
            record = {"episode": episode_id, "step": step.step, "words": tokenize(step.text), "tags": None,
                      "command": None, "refusal": None}
        else:
            record = contract_record(episode_id, step.step, step.interpretation)
        record["placement"] = placement_record(step, run.stopped_after)
        records.append(record)
    return records


def simulate_episodes(episodes: Iterable[Mapping], tagger: WordTagger,
                      record_fps: float | None = None) -> Iterator[EpisodeRun]:
    """Each episode through the tagger, the IM rules and the simulated robot, from the fresh site; every run
    is yielded as soon as it is done (recorded at ``record_fps`` frames a second, if given)."""
    for episode in episodes:
        yield simulate_episode(episode, tagger, record_fps=record_fps)

