"""The load across the face width per position through Python (docs/python.md, quasistatic;
docs/scenes.md, "Face width"): `epicycle.quasistatic(..., stresses=True)` of the radially tilted
pin (scenes/paper_stage_pin_tilt.toml, 20 slices of 25 mm) returns per position, mesh and slice
what `epicycle quasistatic --stresses` writes in quasistatic_face_load.csv, and the loads obey
the stage's statics: planet 1's sun mesh carries most at -z, and the sun meshes' forces balance
the sun torque."""

import math

import numpy as np
import pytest

import epicycle
from conftest import deg, num, read_csv, run_cli, scene_path

SCENE = scene_path("paper_stage_pin_tilt.toml")
POSITIONS = 4
SLICES = 20
WIDTH_MM = 25.0
# The sun: 16 teeth of module 4.23 mm at 25 deg; its base radius r_b = m z cos(alpha) / 2, the arm
# of every involute contact's normal force about the sun's centre.
SUN_BASE_RADIUS_MM = 4.23 * 16 * math.cos(math.radians(25.0)) / 2
SUN_TORQUE_NM = 600.0  # [load] sun_torque_Nm = -600


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    out = tmp_path_factory.mktemp("cli")
    run_cli("quasistatic", SCENE, "--positions", POSITIONS, "--stresses", "--threads", 1,
            "--quiet", "--out", out)
    with open(out / "quasistatic_face_load.csv") as f:
        header = [line for line in f if not line.startswith("#")][0].rstrip("\n").split(",")
    rows = read_csv(out / "quasistatic_face_load.csv")
    r = epicycle.quasistatic(epicycle.Scene.load(SCENE), positions=POSITIONS, stresses=True,
                             threads=1)
    return header, rows, r


def test_the_arrays_equal_the_face_load_csv(runs):
    header, rows, r = runs
    meshes = list(r.face_meshes)
    assert meshes == ["sun-planet1", "sun-planet2", "sun-planet3",
                      "planet1-ring", "planet2-ring", "planet3-ring"]
    m, s = len(meshes), SLICES
    assert r.k_hbeta.shape == r.largest_load_z_mm.shape == (POSITIONS, m)
    for name in ("line_load_N_per_mm", "root_stress_MPa", "hertz_pressure_MPa"):
        assert getattr(r, name).shape == (POSITIONS, m, s), name
    # The per-slice columns follow the largest ones: sigmaF1..S, then pH1..S.
    tail = header[-2 * s:]
    assert tail == ([f"sigmaF{k}_MPa" for k in range(1, s + 1)]
                    + [f"pH{k}_MPa" for k in range(1, s + 1)])
    assert header[-2 * s - 1] == "hertz_pressure_z_mm"
    assert len(rows) == POSITIONS * m
    # Every cell is {:.9g} of the same double (the program and Python run the same sweep with one
    # thread each): the text equals num() of Python's value, which is the file's printed digits,
    # a relative 5e-9 at most from the value, and nothing looser.
    for row_index, row in enumerate(rows):
        k, j = divmod(row_index, m)
        assert None not in row and None not in row.values(), f"row {row_index}: cells != header"
        assert row["carrier_deg"] == deg(r.carrier_deg[k])
        assert row["mesh"] == meshes[j]
        assert row["converged"] == "1" and r.converged[k]
        assert row["K_Hbeta"] == num(r.k_hbeta[k, j])
        assert row["largest_z_mm"] == num(r.largest_load_z_mm[k, j])
        for q in range(s):
            assert row[f"w{q + 1}_N_per_mm"] == num(r.line_load_N_per_mm[k, j, q])
            assert row[f"sigmaF{q + 1}_MPa"] == num(r.root_stress_MPa[k, j, q])
            assert row[f"pH{q + 1}_MPa"] == num(r.hertz_pressure_MPa[k, j, q])
        # The largest cells are the largest of the per-slice ones.
        assert row["root_stress_max_MPa"] == num(r.root_stress_MPa[k, j].max())
        assert row["hertz_pressure_max_MPa"] == num(r.hertz_pressure_MPa[k, j].max())
    assert np.isfinite(r.root_stress_MPa).all() and np.isfinite(r.hertz_pressure_MPa).all()


def test_the_tilted_sun_mesh_is_loaded_and_stressed_at_minus_z(runs):
    _, _, r = runs
    j = list(r.face_meshes).index("sun-planet1")
    z = -WIDTH_MM / 2 + (np.arange(SLICES) + 0.5) * WIDTH_MM / SLICES  # slice centres [mm]
    for k in range(POSITIONS):
        w = r.line_load_N_per_mm[k, j]
        # The radial tilt turns planet 1's axis so that its -z end approaches the sun: the line
        # load falls from -z to +z, and the root stress of a slice rises with its line load.
        assert z[np.argmax(w)] < 0 and z[np.argmax(r.root_stress_MPa[k, j])] < 0
        assert r.largest_load_z_mm[k, j] < 0
        assert w[: SLICES // 2].sum() > w[SLICES // 2:].sum()
        assert r.k_hbeta[k, j] > 1


def test_the_sun_meshes_balance_the_sun_torque(runs):
    _, _, r = runs
    b_s = WIDTH_MM / SLICES  # slice width [mm]
    meshes = list(r.face_meshes)
    sun = [j for j, name in enumerate(meshes) if name.startswith("sun-")]
    p = r.pairs
    involute_only = 0
    for k in range(POSITIONS):
        # F = sum_s w_s b/S [N], the mesh's normal force, is the sum of its loaded contacts' forces
        # (the pairs, from the contact solution itself); the sums differ in their order only:
        # 1e-12 bounds the round-off of some 60 terms (60 x 1.1e-16 = 7e-15) with room.
        force = r.line_load_N_per_mm[k].sum(axis=1) * b_s
        at = [i for i in range(len(p.force_N)) if p.carrier_deg[i] == r.carrier_deg[k]]
        for j, name in enumerate(meshes):
            total = sum(p.force_N[i] for i in at if p.mesh[i] == name)
            assert force[j] == pytest.approx(total, rel=1e-12), (k, name)
        # K_Hbeta is the largest slice over the mean F/b (the same round-off).
        mean = force / WIDTH_MM
        assert r.k_hbeta[k] * mean == pytest.approx(r.line_load_N_per_mm[k].max(axis=1), rel=1e-12)
        # The sun (held fixed, friction off) is in equilibrium: where every loaded contact of its
        # meshes lies on the involute, each normal force acts at the arm r_b, so the forces carry
        # the sun torque, and the load-sharing ratio (each planet's share of the sun-mesh torque)
        # is its force's share. A contact on a tip rounding has another arm: such positions are
        # left out. The solve's equilibrium residual (nondimensional by the load scale) bounds the
        # error besides round-off: asserted below 1e-12, which is then the tolerance.
        if any(p.kind[i] != "involute" for i in at if p.mesh[i].startswith("sun-")):
            continue
        involute_only += 1
        assert r.residual[k] < 1e-12
        torque = force[sun].sum() * SUN_BASE_RADIUS_MM * 1e-3
        assert torque == pytest.approx(SUN_TORQUE_NM, rel=1e-12)
        shares = force[sun] / force[sun].sum()
        assert list(r.lsr[k]) == pytest.approx(list(shares), rel=1e-12)
    assert involute_only >= 2  # 0, 2.77 and 4.15 deg here; 1.38 deg has a sun tip contact


def test_a_stage_of_one_slice_has_no_face_arrays():
    r = epicycle.quasistatic(epicycle.Scene.load(scene_path("paper_stage.toml")), positions=1,
                             stresses=True)
    for name in ("face_meshes", "k_hbeta", "largest_load_z_mm", "line_load_N_per_mm",
                 "root_stress_MPa", "hertz_pressure_MPa"):
        assert not hasattr(r, name), name
