"""Python's dynamic returns the dynamic run's record, the program writes it (docs/dynamic.md,
"Outcomes"): given the same request (the library's defaults on both sides: outputs per mesh cycle,
friction, integrator), `r.record` has exactly the keys of `epicycle dynamic`'s summary JSON and
every value bit for bit (the JSON carries 17 significant digits, which read back to the same
double), the wall times and the program's provenance aside. A run that stops is a status, and
Python raises the ComputationError subclass of that status with the record in `.result`."""

import os

import pytest

import epicycle
from conftest import SOURCE_DIR, num, read_csv, read_json, run_cli, scene_path

# What two runs of the same request may differ in: wall times.
TIMES = {"setup_seconds", "wall_seconds", "evaluation_seconds"}


def without_times(record):
    return {k: v for k, v in record.items() if k not in TIMES}


def test_record_equals_the_program_summary_key_by_key_defaults_included(tmp_path):
    out = tmp_path / "cli"
    run_cli("dynamic", scene_path("paper_stage_runout_rated.toml"), "--range", "cycle",
            "--rating", "--quiet", "--out", out)
    j = read_json(out / "dynamic_summary.json")
    r = epicycle.dynamic(epicycle.Scene.load(scene_path("paper_stage_runout_rated.toml")),
                         range="cycle", rating=True)
    assert "provenance" in j
    del j["provenance"]
    assert sorted(r.record) == sorted(j)
    assert "rating" in j and "root_stress" in j  # the optional fields too
    for key in sorted(set(j) - TIMES):
        assert r.record[key] == j[key], key
    assert without_times(r.record) == without_times(j)
    # The program's default outputs per mesh cycle, not a binding's own.
    assert r.record["outputs"] == j["outputs"] == 211 and r.outputs == 211
    assert r.record["status"] == r.status == "completed"


def test_record_of_a_sliced_stage_equals_the_program_summary(tmp_path):
    # Slices of the face width (docs/face_width.md): the record's face_width list, K_Hbeta per
    # mesh over the run, has the program's keys and values; planet 1's radial pin tilt loads its
    # sun mesh at -z (the end slice's centre, -11.875 mm of 25 mm in 20) as in the quasi-static run.
    scene = scene_path("paper_stage_pin_tilt.toml")
    out = tmp_path / "cli"
    run_cli("dynamic", scene, "--range", "cycle", "--quiet", "--out", out)
    j = read_json(out / "dynamic_summary.json")
    r = epicycle.dynamic(epicycle.Scene.load(scene), range="cycle")
    del j["provenance"]
    assert sorted(r.record) == sorted(j)
    assert without_times(r.record) == without_times(j)
    meshes = {m["mesh"]: m for m in r.record["face_width"]}
    assert sorted(meshes) == sorted(["sun-planet1", "sun-planet2", "sun-planet3",
                                     "planet1-ring", "planet2-ring", "planet3-ring"])
    assert meshes["sun-planet1"]["largest_load_z_mm"] == -11.875
    assert meshes["sun-planet1"]["K_Hbeta_max"] >= meshes["sun-planet1"]["K_Hbeta_mean"] > 1.05
    # Per step, the steps file's K_Hbeta_<mesh> and largest_z_mm_<mesh> columns as arrays.
    rows = read_csv(out / "dynamic_steps.csv")
    assert r.k_hbeta.shape == (len(rows), 6) == r.largest_load_z_mm.shape
    for m, mesh in enumerate(r.face_meshes):
        assert [row["K_Hbeta_" + mesh] for row in rows] == [num(k) for k in r.k_hbeta[:, m]]
        assert [row["largest_z_mm_" + mesh] for row in rows] == \
            [num(z) for z in r.largest_load_z_mm[:, m]]
        assert max(r.k_hbeta[:, m]) == meshes[mesh]["K_Hbeta_max"]


def outcome(exc_type, *args, **kwargs):
    with pytest.raises(exc_type) as e:
        epicycle.dynamic(*args, range="cycle", **kwargs)
    assert isinstance(e.value, epicycle.ComputationError)
    return e.value


def test_each_status_raises_its_class_with_the_record():
    scene = epicycle.Scene.load(scene_path("paper_stage.toml"))
    # One step per output interval cannot reach the first output (CV_TOO_MUCH_WORK).
    e = outcome(epicycle.IntegratorFailure, scene, max_steps=1)
    assert "CV_TOO_MUCH_WORK" in str(e)
    assert e.result.status == e.result.record["status"] == "integrator-failure"
    assert e.result.record["completed"] is False and e.result.record["outputs_written"] == 0
    # 1 ns of wall time is spent before the integrator's first right-hand side.
    e = outcome(epicycle.TimeLimitReached, scene, time_limit_s=1e-9)
    assert "time limit" in str(e) and e.result.record["status"] == "time-limit"
    # Planet 2 thinned by three times the backlash: separated from both members at the start.
    separated = epicycle.Scene.load(
        os.path.join(SOURCE_DIR, "verification", "data", "outcomes", "separated_planet2.toml"))
    e = outcome(epicycle.GeometryFailure, separated)
    assert "planet2 is separated" in str(e) and e.result.record["status"] == "geometry"
    assert len(e.result.time_s) == 0
    # nlopt-lbfgs refuses a stage's problem (it has equalities): the start's contact solve fails.
    if "nlopt-lbfgs" in epicycle.contact_backends():
        e = outcome(epicycle.ContactFailure, scene, backend="nlopt-lbfgs")
        assert "nlopt-lbfgs" in str(e) and e.result.record["status"] == "contact-failure"
    # Without raise_on_failure the record is returned.
    r = epicycle.dynamic(scene, range="cycle", max_steps=1, raise_on_failure=False)
    assert r.status == "integrator-failure" and not r.completed


def test_bad_limits_are_value_errors_naming_the_argument():
    scene = epicycle.Scene.load(scene_path("paper_stage.toml"))
    rule = r"time_limit_s = 0: must be finite and in \(0, 1000000\] \[s\]"
    with pytest.raises(ValueError, match=rule):
        epicycle.dynamic(scene, range="cycle", time_limit_s=0.0)
    with pytest.raises(ValueError, match=r"max_steps = 0: must be a whole number"):
        epicycle.dynamic(scene, range="cycle", max_steps=0)
