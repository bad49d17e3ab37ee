"""A helical stage's records in Python against the program's (docs/face_width.md, "Helical
meshes"; docs/model.md §10): the quasi-static, dynamic and modes records of the helical paper
stage have exactly the keys and values of the program's JSON (the `helical` object of axial
forces and tilting moments among them), and the dynamic run's per-step axial loads are the steps
file's columns cell by cell; a scene of hands that cannot mesh is refused with the program's
first message."""

import os

import pytest

import epicycle
from conftest import SOURCE_DIR, num, read_csv, read_json, run_cli, scene_path

SCENE = "paper_stage_helical.toml"
# What two runs of the same request may differ in: wall times.
TIMES = {"setup_seconds", "wall_seconds", "evaluation_seconds", "sweep_seconds", "table_seconds"}


def without_times(record):
    return {k: v for k, v in record.items() if k not in TIMES}


def test_quasistatic_helical_record_equals_the_program_json(tmp_path):
    run_cli("quasistatic", scene_path(SCENE), "--positions", "2", "--quiet", "--out", tmp_path)
    program = read_json(tmp_path / "quasistatic_summary.json")
    python = epicycle.quasistatic(epicycle.Scene.load(scene_path(SCENE)), positions=2).record
    del program["provenance"]
    assert sorted(python) == sorted(program)
    assert without_times(python) == without_times(program)
    h = python["helical"]
    assert h["axial_and_tilting_motion"].startswith("held")
    assert len(h["planets"]) == 3
    # Each planet's meshes push on opposite flanks: axial forces of opposite signs.
    for p in h["planets"]:
        assert p["sun_mesh_axial_force_N"] * p["ring_mesh_axial_force_N"] < 0


def test_dynamic_helical_record_and_steps_equal_the_program_files(tmp_path):
    out = tmp_path / "cli"
    run_cli("dynamic", scene_path(SCENE), "--time", "0.0005", "--quiet", "--out", out)
    j = read_json(out / "dynamic_summary.json")
    r = epicycle.dynamic(epicycle.Scene.load(scene_path(SCENE)), time_s=0.0005)
    del j["provenance"]
    assert sorted(r.record) == sorted(j)
    assert without_times(r.record) == without_times(j)
    assert "helical" in j and len(j["helical"]["planets"]) == 3
    # Per step: the steps file's axial-load columns as arrays, cell by cell.
    rows = read_csv(out / "dynamic_steps.csv")
    assert len(rows) == len(r.time_s) > 0
    for key in ("sun_axial_force_N", "ring_axial_force_N", "carrier_axial_force_N"):
        assert [row[key] for row in rows] == [num(v) for v in getattr(r, key)], key
    for key in ("sun_mesh_axial_force_N", "tilting_moment_radial_Nm",
                "tilting_moment_tangential_Nm"):
        values = getattr(r, key)
        assert values.shape == (len(rows), 3)
        for i in range(3):
            assert [row[f"{key}_{i + 1}"] for row in rows] == [num(v) for v in values[:, i]], key
    # The summary's means are the steps' means.
    mean = sum(r.sun_axial_force_N) / len(rows)
    assert abs(j["helical"]["sun_axial_force_N"] - mean) <= 1e-12 * abs(mean)


def test_modes_helical_record_equals_the_program_json(tmp_path):
    run_cli("modes", scene_path(SCENE), "--json", tmp_path / "modes.json")
    program = read_json(tmp_path / "modes.json")
    python = epicycle.modes(epicycle.Scene.load(scene_path(SCENE))).record
    program.pop("provenance", None)
    assert sorted(python) == sorted(program)
    assert python == program
    assert "slices" in python["mesh_stiffness_source"]


# The helical paper stage in 5 slices (verification/data/helical/): the drivers in motion at a
# quarter of the 20 slices' cost.
DATA = os.path.join(SOURCE_DIR, "verification", "data")
HELICAL5 = os.path.join(DATA, "helical", "paper_stage_helical_5_slices.toml")


def test_speed_sweep_helical_loads_equal_the_program_files(tmp_path):
    """A speed of a helical stage's sweep (docs/speed_sweeps.md, "Helical stages"): the window's
    axial forces and tilting moments in Python are the CSV's cells and the summary JSON's values."""
    out = tmp_path / "cli"
    run_cli("dynamic", HELICAL5, "--speed-sweep", "3000:3000:1", "--window-cycles", 0.5,
            "--outputs-per-cycle", 8, "--quiet", "--out", out)
    rows = read_csv(out / "speed_sweep.csv")
    j = read_json(out / "speed_sweep_summary.json")
    s = epicycle.speed_sweep(epicycle.Scene.load(HELICAL5), [3000.0], window_cycles=0.5,
                             outputs_per_cycle=8)
    assert len(rows) == 1 and s.ok.all()
    h = s.helical
    row = rows[0]
    for name in ("sun_axial_force_N", "ring_axial_force_N", "carrier_axial_force_N"):
        base, unit = name.rsplit("_", 1)
        for stat in ("mean", "max_abs"):
            key = f"{base}_{stat}_{unit}"
            assert row[key] == num(getattr(h, key)[0]), key
            assert j["speeds"][0]["helical"][key] == getattr(h, key)[0], key
    for name in ("sun_mesh_axial_force_N", "ring_mesh_axial_force_N", "tilting_moment_radial_Nm",
                 "tilting_moment_tangential_Nm"):
        base, unit = name.rsplit("_", 1)
        for stat in ("mean", "max_abs"):
            key = f"{base}_{stat}_{unit}"
            values = getattr(h, key)
            assert values.shape == (1, 3)
            for i in range(3):
                assert row[f"{key}_{i + 1}"] == num(values[0, i]), key
                assert j["speeds"][0]["helical"]["planets"][i][key] == values[0, i], key
    # The sun carries n F_a = |T_s| tan(beta_b) / r_b,sun along its axis: the mean's magnitude
    # lies below the largest.
    assert 0 < abs(h.sun_axial_force_mean_N[0]) <= h.sun_axial_force_max_abs_N[0]


def test_helical_study_rows_carry_the_quasistatic_axial_loads(tmp_path):
    """A helical study of 3 cases (the sun torque on a grid, docs/studies.md): each row's axial
    forces and tilting moments are the quasi-static driver's means at the case's torque over the
    same positions (2 over a mesh cycle), and the program's rows file has the same columns."""
    study = os.path.join(DATA, "studies", "helical_torque_3_cases.toml")
    out = tmp_path / "cli"
    run_cli("study", study, "--threads", 1, "--quiet", "--out", out)
    r = epicycle.study(study, threads=1)
    assert r.ok.all() and len(r.case_id) == 3
    columns = list(r.helical_columns)
    assert columns[:2] == ["F_a_sun-planet1_N", "F_a_sun-planet2_N"]
    assert "M_tilt_tangential_planet3_Nm" in columns
    header = r.header.split(",")
    assert all(c in header for c in columns)
    rows = read_csv(out / "study_rows.csv")
    assert len(rows) == 3
    for k, case in enumerate(r.case_id):
        torque = r.values[k, 0]
        scene = epicycle.Scene.load(HELICAL5)
        scene.set("load.sun_torque_Nm", float(torque))
        scene.set("supports.sun", "fixed")
        q = epicycle.quasistatic(scene, range="cycle", positions=2).record["helical"]
        expected = {}
        for i, p in enumerate(q["planets"]):
            expected[f"F_a_sun-planet{i + 1}_N"] = p["sun_mesh_axial_force_N"]
            expected[f"F_a_planet{i + 1}-ring_N"] = p["ring_mesh_axial_force_N"]
            expected[f"M_tilt_radial_planet{i + 1}_Nm"] = p["tilting_moment_radial_Nm"]
            expected[f"M_tilt_tangential_planet{i + 1}_Nm"] = p["tilting_moment_tangential_Nm"]
        assert sorted(expected) == sorted(columns)
        # The same positions of the same stage model: equal to the contact solver's tolerance
        # (the study warm-starts its cases from its grid's first position, the driver from the
        # previous position; both converge to 1e-10 of the contact forces, 1e-8 of the largest
        # value in N or N·m leaves a hundredfold margin for the sums over contacts).
        scale = max(abs(v) for v in expected.values())
        row = next(x for x in rows if int(x["case"]) == case)
        for c, value in expected.items():
            got = r.helical[k, columns.index(c)]
            assert abs(got - value) <= 1e-8 * scale, c
            assert float(row[c]) == got, c  # the rows file's shortest exact form
    assert set(r.record["helical"]) == set(columns)


def test_a_scene_of_hands_that_cannot_mesh_is_refused_with_the_program_message():
    # hands_external_same.toml: the planets' hand that of the sun, and no [face_width] slices. Both
    # doors check the stage's rules before the driver's need of slices: the same first message.
    path = os.path.join(SOURCE_DIR, "verification", "data", "bad_inputs", "hands_external_same.toml")
    p = run_cli("quasistatic", path, "--positions", "1", check=False)
    assert p.returncode == 2
    with pytest.raises(ValueError) as e:
        epicycle.quasistatic(epicycle.Scene.load(path), positions=1)
    message = str(e.value)
    assert 'planet.hand = "right"' in message
    assert "an external mesh needs opposite hands" in message
    assert "slices" not in message
    assert message in p.stderr
