"""A helical stage's records in Python against the program's (docs/face_width.md, "Helical
meshes"; docs/model.md §10): the quasi-static, dynamic and modes records of the helical paper
stage have exactly the keys and values of the program's JSON (the `helical` object of axial
forces and tilting moments among them), and the dynamic run's per-step axial loads are the steps
file's columns cell by cell."""

import epicycle
from conftest import num, read_csv, read_json, run_cli, scene_path

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
