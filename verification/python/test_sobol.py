"""Sobol indices (epicycle.sobol_indices, studies::EstimateSobol; docs/studies.md "Sensitivity:
Sobol indices") against OpenTURNS (Debian's python3-openturns) on the same samples.

OpenTURNS 1.20 takes the design as the blocks A, B, E_1 … E_d (E_i = A with column i from B),
centres the outputs on the mean of the whole design (as epicycle does) and divides by V_A, the
sample variance of A's outputs (epicycle: of A's and B's). Its JansenSensitivityAlgorithm's total
index is Σ (y_A − y_Ei)² / (2N − 1) / V_A, epicycle's Σ (y_A − y_ABi)² / (2N) / V; its
MauntzKucherenkoSensitivityAlgorithm's first-order index is Σ y_B (y_Ei − y_A) / (N − 1) / V_A,
epicycle's (Saltelli 2010) the same sum / N / V. So on the same samples

    OT Jansen total     = epicycle total · (V / V_A) · 2N / (2N − 1)
    OT MK first order   = epicycle first · (V / V_A) · N / (N − 1)

to round-off (sums of the same terms in another order: relative 1e-10 allowed for 1e5 terms of
double precision). OpenTURNS's SaltelliSensitivityAlgorithm is Saltelli's 2002 product estimator
((Σ y_B y_Ei)/(N − 1) − μ_A μ_B)/V_A, a different estimator of the same index: it is compared
with the closed form only, like epicycle's.
"""

import os

import numpy as np
import openturns as ot

import epicycle
from conftest import SCENES

A_ISHIGAMI, B_ISHIGAMI = 7.0, 0.1


def ishigami(x):
    return (np.sin(x[:, 0]) + A_ISHIGAMI * np.sin(x[:, 1]) ** 2
            + B_ISHIGAMI * x[:, 2] ** 4 * np.sin(x[:, 0]))


def closed_form():
    """S_i and S_Ti of Ishigami's function (Saltelli et al. 2008, The Primer, §4.9)."""
    a, b, pi = A_ISHIGAMI, B_ISHIGAMI, np.pi
    v = a * a / 8 + b * pi**4 / 5 + b * b * pi**8 / 18 + 0.5
    v1 = 0.5 * (1 + b * pi**4 / 5) ** 2
    v2 = a * a / 8
    v13 = b * b * pi**8 * (1 / 18 - 1 / 50)
    return np.array([v1, v2, 0]) / v, np.array([v1 + v13, v2, v13]) / v


def blocks_to_case_order(blocks):
    """[A, B, E_1 … E_d] (each N values) as y[j (d + 2) + m]."""
    return np.stack(blocks, axis=1).reshape(-1)


def compare_with_openturns(x_blocks, y_blocks, n):
    """epicycle's indices of one output and OpenTURNS's on the same design; checks the relations
    of the module docstring; returns epicycle's Result."""
    d = len(y_blocks) - 2
    e = epicycle.sobol_indices(blocks_to_case_order(y_blocks), d, bootstrap=300, seed=1)
    assert e.rows == n
    x = ot.Sample(np.vstack(x_blocks))
    y = ot.Sample(np.concatenate(y_blocks).reshape(-1, 1))
    v_a = np.var(y_blocks[0], ddof=1)
    jansen = ot.JansenSensitivityAlgorithm(x, y, n)
    mk = ot.MauntzKucherenkoSensitivityAlgorithm(x, y, n)
    scale = e.variance / v_a
    np.testing.assert_allclose(np.array(jansen.getTotalOrderIndices()),
                               e.total * scale * 2 * n / (2 * n - 1), rtol=1e-10, atol=1e-13)
    np.testing.assert_allclose(np.array(mk.getFirstOrderIndices()),
                               e.first * scale * n / (n - 1), rtol=1e-10, atol=1e-13)
    return e


def test_ishigami_same_samples_as_openturns_and_the_closed_form():
    n, d = 20000, 3
    rng = np.random.default_rng(2026)
    a = rng.uniform(-np.pi, np.pi, (n, d))
    b = rng.uniform(-np.pi, np.pi, (n, d))
    x_blocks = [a, b]
    for i in range(d):
        e_i = a.copy()
        e_i[:, i] = b[:, i]
        x_blocks.append(e_i)
    y_blocks = [ishigami(x) for x in x_blocks]
    e = compare_with_openturns(x_blocks, y_blocks, n)
    s, st = closed_form()
    np.testing.assert_allclose(s, [0.3139, 0.4424, 0.0], atol=5e-5)
    np.testing.assert_allclose(st, [0.5576, 0.4424, 0.2437], atol=5e-5)
    # Each estimate within 4 bootstrap standard errors of the closed form (a normal estimator
    # is that far off with probability 6e-5).
    assert np.all(np.abs(e.first - s) <= 4 * e.first_standard_error)
    assert np.all(np.abs(e.total - st) <= 4 * e.total_standard_error)
    # OpenTURNS's own Saltelli (2002) estimator on the same samples, with its own bootstrap
    # intervals (99.9 %): they hold the closed form too.
    saltelli = ot.SaltelliSensitivityAlgorithm(ot.Sample(np.vstack(x_blocks)),
                                               ot.Sample(np.concatenate(y_blocks).reshape(-1, 1)),
                                               n)
    saltelli.setBootstrapSize(200)
    saltelli.setConfidenceLevel(0.999)
    lo = np.array(saltelli.getFirstOrderIndicesInterval().getLowerBound())
    hi = np.array(saltelli.getFirstOrderIndicesInterval().getUpperBound())
    assert np.all((lo <= s) & (s <= hi)), (lo, hi)


def test_a_sobol_study_rows_give_the_openturns_indices():
    """A small Sobol study of the paper's stage through the bindings (the shipped
    sobol_pins_runout.toml with N = 12, 4 positions): its summary's indices of K_γ are those
    OpenTURNS gives from the study's own rows (the design read back from the case
    values: A_B^(i) equals A but for variable i's columns)."""
    path = os.path.join(SCENES, "studies", "sobol_pins_runout.toml")
    with open(path) as f:
        shipped = f.read()
    # The shipped study (pin holes of planets 1-3, the sun's run-out), made small.
    text = shipped.replace("samples = 4000", "samples = 12").replace("positions = 24",
                                                                       "positions = 4")
    assert text != shipped
    r = epicycle.study(path, text=text, threads=2,
                       cache_dir=os.environ.get("EPICYCLE_CACHE_DIR"))
    n, d = 12, 4
    assert r.cases == n * (d + 2) and r.ok.all()
    values = r.values.reshape(n, d + 2, -1)
    a, b = values[:, 0], values[:, 1]
    columns = [[0], [1], [2], [3, 4]]  # the run-out's amplitude and phase move together
    for i, cols in enumerate(columns):
        e_i = values[:, 2 + i]
        others = [k for k in range(5) if k not in cols]
        assert np.array_equal(e_i[:, cols], b[:, cols]) and np.array_equal(e_i[:, others],
                                                                           a[:, others])
    y = r.k_gamma.reshape(n, d + 2)
    # One input column per variable for OpenTURNS (the run-out by its amplitude).
    x_blocks = [values[:, m][:, [0, 1, 2, 3]] for m in range(d + 2)]
    y_blocks = [y[:, m] for m in range(d + 2)]
    e = compare_with_openturns(x_blocks, y_blocks, n)
    sobol = r.summary.sobol.outputs.K_gamma
    np.testing.assert_allclose(sobol.first, e.first, rtol=1e-12)
    np.testing.assert_allclose(sobol.total, e.total, rtol=1e-12)
    assert r.summary.sobol.variables == ["planet1.pin_tangential", "planet2.pin_tangential",
                                         "planet3.pin_tangential", "sun.runout"]
