"""Notebook 07 (from the corpus to the field): the decision's least expected cost from scratch, with its check, and
the field ablation as a bar chart.

The decision layer (``drywall_lab.decision``, step 3 of its docstring) takes, from each outcome's probability, the
least expected cost of three actions: act on the likeliest command *c* (``wrong x (1 - P(c))``), ask about the
options (``ask + refuse x P(a command outside them)``; the options are the commands whose probability reaches the
options floor, at most three, the likeliest first, the likeliest alone when none does) and refuse
(``refuse x P(any command)``); on a tie the more careful action (refuse, then ask, then act).
:func:`check_expected_cost` compares a student's function with the library's ``expected_costs`` on the notebook's
worked example and on many random probability vectors and costs.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

import numpy as np

from drywall_lab.course.common import solution_file
from drywall_lab.decision import DEFAULT_SETTINGS, DecisionCosts, expected_costs
from drywall_lab.exercise import ExerciseCheck, call_student, is_unattempted

if TYPE_CHECKING:
    import matplotlib.pyplot as plt
    import pandas as pd

    from drywall_lab.decision import Decision

#: The actions, the more careful first: a tie goes to the earlier one (as ``drywall_lab.decision.decide`` breaks it).
ACTIONS = ("refuse", "ask", "act")
#: An answer: ("act", the command, cost), ("ask", [the options, the likeliest first], cost) or ("refuse", None, cost).
Answer = tuple[str, Any, float]
#: How close two expected costs must be to count as the same.
TOLERANCE = 1e-9

#: The commands the random cases draw their names from.
_COMMANDS = [f"panel {p} on stud {s}, {how}" for p, s, how in [
    ("500320", "500100", "vertical_left"), ("500321", "500104", "vertical_middle"),
    ("500322", "500104", "vertical_left"), ("500321", "500105", "vertical_middle"),
    ("500320", "500103", "horizontal_top"), ("500311", "500107", "horizontal_bottom")]]


@dataclass(frozen=True)
class CostCase:
    """One case of the check: each command's probability (what is left of 1 is no command), the costs and the
    options floor."""

    name: str
    probabilities: dict[str, float]
    costs: DecisionCosts
    option_floor: float

    def args(self) -> tuple[dict[str, float], DecisionCosts, float]:
        """The student's function's arguments (a copy of the probabilities, so that a function may change them)."""
        return dict(self.probabilities), self.costs, self.option_floor


def command_label(outcome: Sequence) -> str:
    """A command outcome ``("command", panel, stud, placement)`` as the exercise names it:
    ``"panel 500321 on stud 500104, vertical_middle"``."""
    _, panel, stud, placement = outcome
    return f"panel {panel} on stud {stud}, {placement}"


def decision_inputs(decision: "Decision") -> dict[str, float]:
    """The probability of each command of a decision (``Decision.probabilities``, commands only, the likeliest
    first): the exercise's input for the notebook's worked example."""
    mass = decision.probabilities
    commands = sorted((o for o in mass if o[0] == "command"), key=lambda o: -mass[o])
    return {command_label(o): float(mass[o]) for o in commands}


def _library(case: CostCase) -> tuple[dict[str, float], str | None, list[str]]:
    """The library's ``expected_costs`` for a case: (the costs of the actions it has, the likeliest command, the
    options); what no command claims is one refusal outcome."""
    mass: dict[tuple, float] = {("command", name): p for name, p in case.probabilities.items()}
    rest = 1.0 - sum(case.probabilities.values())
    if rest > 0:
        mass[("refusal", "no command")] = rest
    costs, best, options = expected_costs(mass, case.costs, case.option_floor)
    return costs, (best[1] if best else None), [o[1] for o in options]


def _choose(costs: Mapping[str, float], best: str | None, options: list[str]) -> Answer:
    action = min(costs, key=lambda k: (costs[k], ACTIONS.index(k)))
    about = best if action == "act" else list(options) if action == "ask" else None
    return action, about, float(costs[action])


def library_decision(probabilities: Mapping[str, float], costs: DecisionCosts = DEFAULT_SETTINGS.costs,
                     option_floor: float = DEFAULT_SETTINGS.option_floor) -> Answer:
    """What ``drywall_lab.decision`` does with these probabilities: its ``expected_costs``, then the least,
    the more careful action on a tie (``ACTIONS``)."""
    return _choose(*_library(CostCase("", dict(probabilities), costs, option_floor)))


def expected_cost_cases(example: "Decision | None" = None, n_random: int = 300, seed: int = 7) -> list[CostCase]:
    """The check's cases: the worked example (a ``Decision``, with the default costs and floor), cases built to
    catch the usual slips, then ``n_random`` random probability vectors, costs and floors."""
    default, floor = DEFAULT_SETTINGS.costs, DEFAULT_SETTINGS.option_floor
    c = _COMMANDS
    cases: list[CostCase] = []
    if example is not None:
        cases.append(CostCase("the worked example", decision_inputs(example), default, floor))
    cases += [
        CostCase("one command, almost sure", {c[0]: 0.98}, default, floor),
        CostCase("two commands, close", {c[1]: 0.48, c[2]: 0.44}, default, floor),
        CostCase("four commands, one likely", {c[0]: 0.55, c[1]: 0.2, c[2]: 0.12, c[3]: 0.08}, default, floor),
        CostCase("a question as dear as a refusal", {c[1]: 0.5, c[2]: 0.3}, DecisionCosts(10, 1, 1), floor),
        CostCase("an options floor", {c[0]: 0.5, c[1]: 0.3, c[2]: 0.1}, default, 0.25),
        CostCase("a cheap wrong move", {c[0]: 0.8, c[1]: 0.1}, DecisionCosts(1, 1, 0.3), floor),
        CostCase("no command at all", {}, default, floor),
        CostCase("a tie of all three", {c[0]: 0.5}, DecisionCosts(1, 1, 0.5), floor),
    ]
    n_built = len(cases)
    rng = np.random.default_rng(seed)
    while len(cases) < n_built + n_random:
        k = int(rng.integers(1, 6))
        p = rng.dirichlet(np.full(k + 1, 0.7))
        if rng.random() < 0.25:
            p = p[:k] / p[:k].sum()  # every bit of probability on a command
        names = [c[i] for i in rng.permutation(len(c))[:k]]
        probabilities = {name: float(q) for name, q in zip(names, p)}
        costs = default if rng.random() < 0.4 else DecisionCosts(round(float(rng.uniform(0.5, 20)), 2),
                                                                 round(float(rng.uniform(0.2, 3)), 2),
                                                                 round(float(rng.uniform(0, 1.5)), 2))
        case = CostCase(f"random case {len(cases) - n_built + 1}", probabilities, costs,
                        float(rng.choice([0.0, 0.0, 0.05, 0.15, 0.3])))
        least = sorted(_library(case)[0].values())
        if len(least) < 2 or least[1] - least[0] > 1e-6:  # no near tie: the order of the sums cannot decide it
            cases.append(case)
    return cases


# --- the usual slips, each as the answer it gives -------------------------------------------------------------
def _slips(case: CostCase) -> dict[str, Answer]:
    """The answer each known slip gives on ``case`` (built from the library's costs), by what to tell the student."""
    costs, best, options = _library(case)
    if best is None:
        return {}
    p = case.probabilities
    p_best, p_commands = p[best], sum(p.values())
    out = {}
    reckless = min(costs, key=lambda k: (costs[k], ACTIONS[::-1].index(k)))
    out["on a tie take the more careful action: refuse before ask, ask before act"] = \
        (reckless, best if reckless == "act" else list(options) if reckless == "ask" else None,
         float(costs[reckless]))
    wrong_for_right = dict(costs, act=case.costs.wrong * p_best)
    out["acting costs a wrong move with the probability that the command is wrong, 1 - P(c), not P(c): the "
        "likeliest command is the right one with probability P(c)"] = _choose(wrong_for_right, best, options)
    no_question = dict(costs, ask=costs["ask"] - case.costs.ask)
    out["a question costs the worker a turn: add the cost of asking (costs.ask) to the refusal of the commands "
        "outside the options"] = _choose(no_question, best, options)
    out["the likeliest command is not always worth acting on: compare the three expected costs and take the least"] \
        = ("act", best, float(costs["act"]))
    out["refusing costs a refusal only where a command was meant: refuse x P(any command), the sum of the "
        "commands' probabilities"] = _choose(dict(costs, refuse=case.costs.refuse), best, options)
    every = [o for o in sorted(p, key=lambda o: -p[o])][:3]
    out["an option must reach the options floor (option_floor); the likeliest command alone when none does"] = \
        _choose(dict(costs, ask=case.costs.ask + case.costs.refuse * (p_commands - sum(p[o] for o in every))),
                best, every)
    above = [o for o in sorted(p, key=lambda o: -p[o]) if p[o] >= case.option_floor] or [best]
    out["a question has at most three options, the likeliest first"] = \
        _choose(dict(costs, ask=case.costs.ask + case.costs.refuse * (p_commands - sum(p[o] for o in above))),
                best, above)
    return out


def _same(got: Any, want: Answer) -> bool:
    action, about, cost = got
    return (action == want[0] and (list(about) if want[0] == "ask" and about is not None else about) == want[1]
            and abs(float(cost) - want[2]) <= TOLERANCE * max(1.0, abs(want[2])))


def _shape_problem(got: Any, names: Sequence[str]) -> str | None:
    """What is wrong with the shape of an answer, or None: a 3-tuple (action, what, cost)."""
    if not isinstance(got, (tuple, list)) or len(got) != 3:
        return f"returned {got!r}: return a tuple (action, what, expected cost)"
    action, about, cost = got
    if action not in ACTIONS:
        return f"returned the action {action!r}: the action is 'act', 'ask' or 'refuse'"
    if not isinstance(cost, (int, float, np.floating)) or isinstance(cost, bool):
        return f"returned the cost {cost!r}: the expected cost is a number"
    if action == "act" and about not in names:
        return f"acted on {about!r}: 'act' comes with the command acted on, one of the probabilities' keys"
    if action == "ask" and (isinstance(about, str) or not isinstance(about, (list, tuple))):
        return f"asked about {about!r}: 'ask' comes with the list of the options, the likeliest first"
    if action == "refuse" and about is not None:
        return f"refused with {about!r}: 'refuse' comes with None"
    return None


def _describe(answer: Answer) -> str:
    action, about, cost = answer
    what = f" on {about!r}" if action == "act" else f" about {list(about)!r}" if action == "ask" else ""
    return f"{action}{what} (expected cost {float(cost):.4f})"


def check_expected_cost(least_expected_cost: Callable[[dict[str, float], DecisionCosts, float], Answer],
                        example: "Decision | None" = None, n_random: int = 300) -> ExerciseCheck:
    """Notebook 07's from-scratch exercise: ``least_expected_cost(probabilities, costs, option_floor)`` against the
    library's decision (``library_decision``: ``drywall_lab.decision.expected_costs``, the least cost, ties to the
    more careful action) on the worked example (``example``), cases built to catch the usual slips and ``n_random``
    random probability vectors, costs and floors. The first disagreement is explained: acting costed with P(c)
    instead of 1 - P(c), the question's cost forgotten, the likeliest command whatever the cost, ... A function that
    raises ``NotImplementedError`` (the notebook's stub) is "not attempted yet"."""
    cases = expected_cost_cases(example, n_random)
    if is_unattempted(least_expected_cost, *cases[0].args()):
        return ExerciseCheck.not_attempted(
            "least_expected_cost(probabilities, costs, option_floor): return ('act', command, cost), "
            "('ask', options, cost) or ('refuse', None, cost), the action of least expected cost",
            solution_file(7))
    wrong = []
    for case in cases:
        want = library_decision(*case.args())
        got, error = call_student(least_expected_cost, *case.args())
        problem = f"raised {error}" if error else _shape_problem(got, list(case.probabilities))
        if problem or not _same(got, want):
            wrong.append((case, want, got, problem))
    if not wrong:
        actions = {a: sum(library_decision(*c.args())[0] == a for c in cases) for a in ACTIONS}
        return ExerciseCheck(True, [f"all {len(cases)} cases agree with the library's decision (acting on "
                                    f"{actions['act']}, asking on {actions['ask']}, refusing on "
                                    f"{actions['refuse']})"])
    case, want, got, problem = wrong[0]
    costs, _, _ = _library(case)
    shown = ", ".join(f"{k} {costs[k]:.4f}" for k in ACTIONS if k in costs)
    messages = [f"{len(wrong)} of {len(cases)} cases disagree with the library's decision; the first, "
                f"{case.name}: probabilities {case.probabilities}, costs {case.costs}, option_floor "
                f"{case.option_floor}",
                f"the library's expected costs are {shown}: it would {_describe(want)}"]
    if problem:
        messages.append(f"your function {problem}")
        return ExerciseCheck(False, messages)
    messages.append(f"your function would {_describe(got)}")
    hint = next((why for why, slip in _slips(case).items() if not _same(slip, want) and _same(got, slip)), None)
    if hint is None and got[0] == want[0] and want[0] == "ask" and list(got[1]) != want[1]:
        hint = "the options are the commands that reach the floor, at most three, the likeliest first"
    elif hint is None and got[0] == want[0] and got[1] == want[1]:
        hint = "the right action, but not its expected cost"
    if hint:
        messages.append(hint)
    return ExerciseCheck(False, messages)


# --- the field ablation as a bar chart ------------------------------------------------------------------------
#: The ablation's columns the chart compares: the share right on each set, and the wrong moves on the hand-written
#: set, of the best reading and of the decision (``results/field/ablation.csv``).
ABLATION_COLUMNS = ("test acc_task", "novel acc_task", "field-novel acc_task", "data/field best",
                    "data/field decided", "data/field best wrong", "data/field decided wrong")


def plot_ablation(ablation: "pd.DataFrame", columns: Sequence[str] = ABLATION_COLUMNS) -> "plt.Figure":
    """The field ablation (``read_ablation``) as grouped bars, one group per model: on the left the share right on
    each set (``acc_task``, and the hand-written set's best reading and decision), on the right the share of wrong
    moves on the hand-written set (columns with "wrong" in their name)."""
    import matplotlib.pyplot as plt

    columns = [c for c in columns if c in ablation]
    right = [c for c in columns if "wrong" not in c]
    wrong = [c for c in columns if "wrong" in c]
    fig, axes = plt.subplots(1, 2 if wrong else 1, figsize=(13, 4.2), squeeze=False,
                             gridspec_kw={"width_ratios": [3, 1]} if wrong else None)
    for ax, group, title in ((axes[0][0], right, "right (share of the set)"),
                             (axes[0][-1] if wrong else None, wrong, "wrong moves (share of the set)")):
        if ax is None or not group:
            continue
        x = np.arange(len(ablation.index))
        width = 0.8 / len(group)
        for i, column in enumerate(group):
            ax.bar(x + (i - (len(group) - 1) / 2) * width, 100 * ablation[column].astype(float), width, label=column)
        ax.set_xticks(x, ablation.index, rotation=30, ha="right")
        ax.set_ylabel("%")
        ax.set_ylim(0, 100 * float(ablation[group].astype(float).max().max()) * 1.3 + 1e-9)
        ax.set_title(title)
        ax.legend(fontsize=8, loc="upper center", ncol=3 if group is right else 1)
        ax.grid(axis="y", alpha=0.3)
    fig.suptitle("The field ablation: paper corpus against field corpus, with and without characters, BiLSTM-CRF "
                 "against MiniLM")
    fig.tight_layout()
    return fig
