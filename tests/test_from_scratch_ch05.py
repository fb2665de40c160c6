"""Notebook 05's from-scratch exercise: one damped least-squares step of differential IK (``check_ik_step``).

The reference solution passes, the notebook's stub is "not attempted yet", the usual slips fail with a message
that names them, and the committed notebook holds the stub (not the solution) under a markdown cell that names
the solution file. The library's pieces the notebook shows (the TCP Jacobian, the repeated step) are checked
against finite differences and against the target.
"""
from __future__ import annotations

from pathlib import Path

import nbformat
import numpy as np
import pytest

from drywall_lab.course.common import solution_file
from drywall_lab.course.solutions import ch05
from drywall_lab.rc.exercises import (check_ik_step, ik_example, ik_iterations, reference_ik_step,
                                      tcp_position_and_jacobian)

ROOT = Path(__file__).resolve().parent.parent
NOTEBOOK = ROOT / "notebooks" / "05_robot_control.ipynb"
MARKER = "# from scratch: your code here"


def _stub(jacobian, error, damping):
    # from scratch: your code here
    raise NotImplementedError("your code here")


def _damped(J, e, damping):
    return J @ J.T + damping**2 * np.eye(J.shape[0])


@pytest.fixture(scope="module")
def example():
    return ik_example()


def test_the_solution_passes_and_brings_the_tcp_nearer():
    check = check_ik_step(ch05.ik_step)
    assert check.passed and check.attempted, str(check)
    assert "singular" in str(check) and "on the robot" in str(check)


def test_the_stub_is_not_attempted_and_names_the_solution_file():
    check = check_ik_step(_stub)
    text = str(check)
    assert not check.passed and not check.attempted
    assert text.startswith("NOT ATTEMPTED YET:\n- fill in "), text
    assert solution_file(5) in text


@pytest.mark.parametrize("wrong, says", [
    (lambda J, e, d: -J.T @ np.linalg.solve(_damped(J, e, d), e), "wrong way"),
    (lambda J, e, d: J.T @ np.linalg.solve(J @ J.T, e), "no damping"),
    (lambda J, e, d: np.linalg.pinv(J) @ e, "no damping"),
    (lambda J, e, d: J @ np.linalg.solve(_damped(J, e, d), e), "J where J^T belongs"),
    (lambda J, e, d: J.T @ np.linalg.solve(J @ J.T + d * np.eye(J.shape[0]), e), "enters squared"),
    (lambda J, e, d: J.T @ e, "Jacobian-transpose step"),
    (lambda J, e, d: J.T @ np.linalg.solve(J @ J.T + d**2 * np.eye(3), e), "np.eye(J.shape[0])"),
    (lambda J, e, d: np.zeros(3), "one entry per joint"),
])
def test_the_usual_slips_fail_with_a_message_that_names_them(wrong, says):
    check = check_ik_step(wrong)
    assert check.attempted and not check.passed
    assert says in str(check), str(check)


def test_a_step_without_damping_fails_on_the_singular_jacobian_even_if_right_elsewhere():
    def undamped_where_tiny(J, e, d):  # right wherever J J^T is well invertible, undamped where it is not
        if np.linalg.cond(J @ J.T) > 1e8:
            return J.T @ np.linalg.solve(J @ J.T, e)
        return reference_ik_step(J, e, d)

    check = check_ik_step(undamped_where_tiny)
    assert not check.passed and "singular" in str(check), str(check)


def test_the_jacobian_is_the_tcps_position_derivative(example):
    """mj_jacSite's columns agree with finite differences of the TCP's position, joint by joint."""
    tcp, J = tcp_position_and_jacobian(example.model, example.q)
    assert J.shape == (3, example.model.nv) and np.allclose(tcp, example.tcp)
    h = 1e-6
    for j in range(example.model.nv):
        q = example.q.copy()
        q[j] += h
        moved, _ = tcp_position_and_jacobian(example.model, q)
        assert np.allclose((moved - tcp) / h, J[:, j], atol=1e-4)


def test_repeated_steps_reach_the_target(example):
    table = ik_iterations(example, reference_ik_step, damping=0.05, step_size=0.5, iterations=8)
    distances = table["distance to target (mm)"].to_numpy()
    assert distances[0] == pytest.approx(np.linalg.norm(example.error) * 1000, rel=1e-3)
    assert np.all(np.diff(distances) < 0) and distances[-1] < 0.01 * distances[0]


def _cells():
    return nbformat.read(NOTEBOOK, as_version=4).cells


def test_the_committed_notebook_holds_the_stub_under_a_cell_naming_the_solution():
    cells = _cells()
    found = [i for i, c in enumerate(cells) if c.cell_type == "code" and MARKER in c.source]
    assert len(found) == 1
    source = cells[found[0]].source
    assert 'raise NotImplementedError("your code here")' in source
    assert "np.linalg.solve" not in source and "J.T" not in source  # not the solution
    assert source.rstrip().endswith("check = check_ik_step(ik_step)\nprint(check)\n"
                                    "assert check.passed or not check.attempted")
    above = next(c for c in reversed(cells[:found[0]]) if c.cell_type == "markdown")
    assert f"`{solution_file(5)}`" in above.source and "try the exercise first" in above.source


def test_the_committed_stub_runs_and_says_not_attempted():
    source = next(c.source for c in _cells() if c.cell_type == "code" and MARKER in c.source)
    namespace = {"np": np, "check_ik_step": check_ik_step}
    exec(compile(source, "notebook 05's from-scratch cell", "exec"), namespace)  # noqa: S102
    assert not namespace["check"].attempted
