"""The contact core from numpy: a problem built from arrays is solved to its closed form; the
collection's problem files solved through Python give the status, iterations and forces that
`epicycle contact solve` prints; every available back end can be called."""

import glob
import os

import numpy as np
import pytest

import epicycle
from conftest import SOURCE_DIR, run_cli

COLLECTION = os.path.join(SOURCE_DIR, "verification", "data", "contact")


def test_uncoupled_contacts_from_numpy_meet_their_closed_form():
    # C diagonal, no equalities, no local terms: F_j = max(0, δ0_j / C_jj).
    c = np.diag([2e-9, 1e-9, 4e-9])
    overlap = np.array([1e-6, -1e-6, 2e-6])
    problem = epicycle.ContactProblem(c, overlap, name="diagonal")
    assert problem.num_contacts == 3 and problem.num_equalities == 0
    r = epicycle.solve_contact(problem)
    assert r.converged and r.status == "converged" and r.residual <= 1e-10
    expected = np.array([500.0, 0.0, 500.0])
    # the residual is nondimensional (forces over their scale, here ~500 N)
    assert np.abs(r.force_N - expected).max() <= 1e-10 * 500.0 * 10
    assert r.active_contacts == 2
    gap = problem.gap_m(r.force_N, r.multiplier)
    assert gap[1] == pytest.approx(1e-6, rel=1e-9)


def test_bad_arrays_raise_value_error_naming_the_field():
    with pytest.raises(ValueError, match="overlap"):
        epicycle.ContactProblem(np.eye(2) * 1e-9, np.zeros(3))
    with pytest.raises(ValueError, match="compliance"):
        epicycle.ContactProblem(np.array([[1e-9, 0.0], [0.0, -1e-9]]), np.zeros(2))
    with pytest.raises(ValueError, match="no-such"):
        epicycle.solve_contact(epicycle.ContactProblem(np.eye(1) * 1e-9, np.zeros(1)),
                               backend="no-such")


def printed(stdout, heading):
    """The numbers listed under a heading of `contact solve` ('forces [N]', 'multipliers')."""
    lines = stdout.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(heading))
    values = []
    for line in lines[start + 1:]:
        if not line.startswith("  "):
            break
        values.append(line.split()[1])
    return values


@pytest.mark.parametrize("path", sorted(glob.glob(os.path.join(COLLECTION, "cf_*.json"))) +
                         sorted(glob.glob(os.path.join(COLLECTION, "gear_*.json")))[:2])
def test_collection_problem_equals_the_program(path):
    p = run_cli("contact", "solve", path, "--backend", "newton", check=False)
    f = epicycle.read_contact_problem(path)
    r = epicycle.solve_contact(f.problem, backend="newton")
    assert f"status       {r.status}" in p.stdout
    assert f"iterations   {r.iterations} " in p.stdout
    assert printed(p.stdout, "forces [N]") == ["%.9e" % v for v in r.force_N]
    if f.problem.num_equalities:
        assert printed(p.stdout, "multipliers") == ["%.9e" % v for v in r.multiplier]


def test_every_available_backend_solves_an_open_contact():
    f = epicycle.read_contact_problem(os.path.join(COLLECTION, "cf_one_contact_open.json"))
    for backend in epicycle.contact_backends():
        r = epicycle.solve_contact(f.problem, backend=backend)
        assert r.backend == backend
        assert r.status in ("converged", "converged-inaccurate"), (backend, r.message)


def test_a_solver_of_ones_own_is_judged_by_the_same_residual():
    # The diagonal problem of the first test: F* = max δ0⁺ / max C_jj = 500 N and
    # ℓ* = F* max C_jj = 2 µm (docs/solvers.md). An answer with F_1 = 400 N instead of 500 N has
    # x_1 = 0.8 and gap g_1 = (2e-9·400 − 1e-6)/2e-6 = −0.1, so its natural map
    # |x_1 − max(0, x_1 − g_1)| = 0.1; the exact answer has none (to rounding).
    c = np.diag([2e-9, 1e-9, 4e-9])
    problem = epicycle.ContactProblem(c, np.array([1e-6, -1e-6, 2e-6]))
    exact = epicycle.contact_residuals(problem, np.array([500.0, 0.0, 500.0]))
    assert exact.residual <= 1e-15
    off = epicycle.contact_residuals(problem, np.array([400.0, 0.0, 500.0]))
    assert off.residual_complementarity == pytest.approx(0.1, rel=1e-12)
    assert off.residual_equilibrium == 0.0 and off.residual == off.residual_complementarity
    # A projected Gauss-Seidel of a few lines, judged as every back end is, against newton.
    f = np.zeros(3)
    for _ in range(50):
        for j in range(3):
            f[j] = max(0.0, f[j] + (problem.overlap_m[j] - c[j] @ f) / c[j, j])
    mine = epicycle.contact_residuals(problem, f)
    ours = epicycle.solve_contact(problem)
    assert mine.residual <= 1e-10 and ours.residual <= 1e-10
    # A natural-map residual r bounds a diagonal problem's force error by r / min_j C̃_jj = 4 r
    # (C̃_jj = C_jj / max C: 0.5, 0.25, 1), so two answers within 1e-10 differ by at most 8e-10 F*.
    d = epicycle.compare_solutions(problem, f, None, ours.force_N, None)
    assert d.force <= 8e-10
