"""A helical stage's records in Python against the program's (docs/face_width.md, "Helical
meshes"; docs/model.md §10): the quasi-static, dynamic and modes records of the helical paper
stage have exactly the keys and values of the program's JSON (the `helical` object of axial
forces and tilting moments among them), and the dynamic run's per-step axial loads are the steps
file's columns cell by cell; a scene of hands that cannot mesh is refused with the program's
first message."""

import os

import pytest

import epicycle
from conftest import (SOURCE_DIR, num, quasistatic_records, read_csv, read_json, run_cli,
                      scene_path, without_times)

SCENE = "paper_stage_helical.toml"


def test_quasistatic_helical_record_equals_the_program_json(tmp_path):
    python, program = quasistatic_records(scene_path(SCENE), tmp_path)
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


# The helical branch of the CLI test "periodic branch of the helical paper stage reports axial
# forces per point" (verification/CMakeLists.txt): 3000 to 3001 rpm, steps of at most half the
# range, every other setting at its default (docs/periodic.md §3, "Helical stages").
BRANCH_ARGS = ("dynamic", HELICAL5, "--speed-sweep", "3000:3001:2", "--periodic", "--quiet")
# A branch CSV's axial-load columns (the speed sweep's: docs/speed_sweeps.md, "Helical stages"):
# the members' and, per planet, its meshes' axial forces and its tilting moments.
MEMBER_KEYS = ("sun_axial_force_N", "ring_axial_force_N", "carrier_axial_force_N")
PLANET_COLUMN_KEYS = ("sun_mesh_axial_force_N", "ring_mesh_axial_force_N",
                      "tilting_moment_radial_Nm", "tilting_moment_tangential_Nm")


def stat_key(name, stat):
    """sun_axial_force_N, mean -> sun_axial_force_mean_N (the record's and the CSV's name)."""
    base, unit = name.rsplit("_", 1)
    return f"{base}_{stat}_{unit}"


def helical_branch_files(tmp_path):
    """The folder of the program's helical branch: the CLI test's (CTest runs it first, its
    fixture, and names its folder in EPICYCLE_HELICAL_BRANCH_DIR), else a run of its own."""
    out = os.environ.get("EPICYCLE_HELICAL_BRANCH_DIR")
    if out:
        return out
    run_cli(*BRANCH_ARGS, "--out", tmp_path / "cli")
    return tmp_path / "cli"


def test_periodic_branch_helical_loads_equal_the_program_files(tmp_path):
    """A helical stage's branch of periodic orbits (docs/periodic.md §3, "Helical stages"): each
    point's axial forces and tilting moments over its period are, in the program's CSV, the
    summary JSON's values (the CSV's 9 digits), and, as Python's arrays, the JSON's values bit for
    bit under the same keys."""
    out = helical_branch_files(tmp_path)
    rows = read_csv(os.path.join(out, "periodic_branch.csv"))
    j = read_json(os.path.join(out, "periodic_branch_summary.json"))
    points = j["points"]
    assert j["status"] == "completed" and len(rows) == len(points) >= 2
    # The CSV: the speed sweep's columns after sun_orbit_radius_um, each the JSON's value.
    header = list(rows[0])
    columns = [stat_key(k, s) for k in MEMBER_KEYS for s in ("mean", "max_abs")]
    columns += [f"{stat_key(k, s)}_{i}" for i in (1, 2, 3) for k in PLANET_COLUMN_KEYS
                for s in ("mean", "max_abs")]
    at = header.index("sun_orbit_radius_um") + 1
    assert header[at:at + len(columns)] == columns
    assert header[at + len(columns)] == "arclength"
    for k, row in enumerate(rows):
        h = points[k]["helical"]
        for key in MEMBER_KEYS:
            for stat in ("mean", "max_abs"):
                assert row[stat_key(key, stat)] == num(h[stat_key(key, stat)]), (k, key)
        for i in range(3):
            for key in PLANET_COLUMN_KEYS:
                for stat in ("mean", "max_abs"):
                    name = stat_key(key, stat)
                    assert row[f"{name}_{i + 1}"] == num(h["planets"][i][name]), (k, i, name)
        # Action and reaction: the sun carries the sun meshes' axial forces on the planets
        # reversed, the ring the ring meshes', the carrier the planets' sums. Each cell is
        # rounded to 9 digits (relative error <= 5e-9), the means' own round-off is ~64 eps:
        # the sums agree to 5e-9 of the sum of the magnitudes, 1e-8 with a factor 2 for both.
        cell = lambda name: float(row[name])  # noqa: E731
        sun = [cell(f"sun_mesh_axial_force_mean_N_{i}") for i in (1, 2, 3)]
        ring = [cell(f"ring_mesh_axial_force_mean_N_{i}") for i in (1, 2, 3)]
        for member, parts in (("sun_axial_force_mean_N", [-x for x in sun]),
                              ("ring_axial_force_mean_N", [-x for x in ring]),
                              ("carrier_axial_force_mean_N", sun + ring)):
            scale = abs(cell(member)) + sum(abs(x) for x in parts)
            assert abs(cell(member) - sum(parts)) <= 1e-8 * scale, (k, member)
        assert abs(cell("sun_axial_force_mean_N")) > 1000  # n F_a of the stage's torque: loaded
    # Python: the same request; the arrays are the JSON's values under the JSON's keys.
    b = epicycle.periodic_branch(epicycle.Scene.load(HELICAL5), "sun_speed_rpm", 3000, 3001,
                                 steps=2)
    assert b.ok and len(b.sun_speed_rpm) == len(points)
    h = b.helical
    json_keys = {key for key in points[0]["helical"] if key not in ("planets",
                                                                     "axial_and_tilting_motion")}
    json_keys |= {key for key in points[0]["helical"]["planets"][0] if key != "planet"}
    assert set(vars(h)) == json_keys and len(json_keys) == 2 * (3 + 7)
    for k, p in enumerate(points):
        for key, value in p["helical"].items():
            if key not in ("planets", "axial_and_tilting_motion"):
                assert getattr(h, key).shape == (len(points),)
                assert getattr(h, key)[k] == value, (k, key)
        for i, planet in enumerate(p["helical"]["planets"]):
            assert planet["planet"] == i + 1
            for key, value in planet.items():
                if key != "planet":
                    assert getattr(h, key).shape == (len(points), 3)
                    assert getattr(h, key)[k, i] == value, (k, i, key)


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
