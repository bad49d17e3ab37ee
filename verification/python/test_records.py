"""Given the same request, the program and Python return the same record (docs/records.md): the
program's summary JSON and Python's result.record hold the same keys and, value by value, the
same numbers bit for bit (the JSON writes each double with the digits that read back exactly),
every setting left at its default on both sides. The program's provenance and the runs' wall
times are the only keys taken out: they describe the process, not the run's results."""

import math
import os

import epicycle
from conftest import SOURCE_DIR, read_json, run_cli, scene_path

# Keys that differ between two runs of the same request: the program's provenance and wall times.
RUN_DEPENDENT = {"provenance", "sweep_seconds", "table_seconds"}


def same_record(program, python):
    program = {k: v for k, v in program.items() if k not in RUN_DEPENDENT}
    python = {k: v for k, v in python.items() if k not in RUN_DEPENDENT}
    assert sorted(program) == sorted(python)
    for key in program:
        # == on floats is bit for bit (NaN is null on both sides: JSON has no NaN).
        assert program[key] == python[key], key


def test_stiffness_record_equals_the_program_json(tmp_path):
    scene = scene_path("iso_pair_20_40.toml")
    run_cli("stiffness", scene, "--out", tmp_path)
    program = read_json(tmp_path / "stiffness_gear1-gear2.json")
    python = epicycle.mesh_stiffness(epicycle.Scene.load(scene)).record
    same_record(program, python)
    assert program["positions"] == 60  # the default, on both sides


def test_helical_stiffness_record_equals_the_program_json(tmp_path):
    # A helical pair in slices (docs/mesh_stiffness.md, "Helical pairs"): the record's helical keys
    # on both sides; eps_beta = b sin(beta)/(pi m_n) = 20 sin 15 deg/(4 pi) = 0.41192.
    scene = scene_path("iso_pair_20_40_helical.toml")
    run_cli("stiffness", scene, "--positions", 6, "--out", tmp_path)
    program = read_json(tmp_path / "stiffness_gear1-gear2.json")
    python = epicycle.mesh_stiffness(epicycle.Scene.load(scene), positions=6).record
    same_record(program, python)
    assert abs(program["overlap_ratio"] - 20 * math.sin(math.radians(15)) / (4 * math.pi)) < 1e-12
    assert program["slices"] == 20 and program["peak_slice_pair_stiffness_N_per_mm_um"] > 0


def test_modes_record_equals_the_program_json(tmp_path):
    scene = scene_path("paper_stage.toml")
    run_cli("modes", scene, "--json", tmp_path / "modes.json")
    program = read_json(tmp_path / "modes.json")
    python = epicycle.modes(epicycle.Scene.load(scene)).record
    same_record(program, python)
    assert len(program["modes"]) > 0 and len(program["coincidences"]) > 0


def test_quasistatic_record_equals_the_program_json(tmp_path):
    scene = scene_path("paper_stage_runout.toml")
    run_cli("quasistatic", scene, "--quiet", "--out", tmp_path)
    program = read_json(tmp_path / "quasistatic_summary.json")
    python = epicycle.quasistatic(epicycle.Scene.load(scene)).record
    same_record(program, python)
    assert program["positions"] == 60 and program["converged_positions"] == 60


def test_face_width_record_equals_the_program_json(tmp_path):
    # Slices of the face width (docs/face_width.md): planet 1's radial pin tilt loads its sun mesh
    # at -z and its ring mesh at +z, the end slices' centres -+11.875 mm of the 25 mm face in 20.
    scene = scene_path("paper_stage_pin_tilt.toml")
    run_cli("quasistatic", scene, "--positions", "6", "--quiet", "--out", tmp_path)
    program = read_json(tmp_path / "quasistatic_summary.json")
    python = epicycle.quasistatic(epicycle.Scene.load(scene), positions=6).record
    same_record(program, python)
    meshes = {m["mesh"]: m for m in python["face_width"]}
    assert meshes["sun-planet1"]["largest_load_z_mm"] == -11.875
    assert meshes["planet1-ring"]["largest_load_z_mm"] == 11.875
    assert meshes["sun-planet1"]["K_Hbeta_max"] > 1.05


def test_pins_record_equals_the_program_json(tmp_path):
    # Planets tilting on straddle pins (docs/face_width.md, "The planet's tilt on its pin"): the
    # helical paper stage's tilting moment, about 163 N m, over k_tilt = 16 E I / L = 2.926e6 N m/rad
    # turns each planet radially by about 55.6 urad (the hand calculation; the load's shift along
    # the face moves it by less than 10 %).
    scene = scene_path("paper_stage_helical_pin.toml")
    run_cli("quasistatic", scene, "--positions", "2", "--quiet", "--out", tmp_path)
    program = read_json(tmp_path / "quasistatic_summary.json")
    python = epicycle.quasistatic(epicycle.Scene.load(scene), positions=2).record
    same_record(program, python)
    for p in python["pins"]["planets"]:
        assert abs(p["tilt_radial_mean_urad"] - 55.6) < 5.6


def test_rigid_pins_record_equals_the_program_json(tmp_path):
    # The same scene without the tilt's feedback: the program's --rigid-pins is Python's
    # pin_feedback=False. With the pins left out every planet is held at its given tilt (none here),
    # so the record has no pins section, where the run with feedback has one.
    scene = scene_path("paper_stage_helical_pin.toml")
    run_cli("quasistatic", scene, "--positions", "2", "--rigid-pins", "--quiet", "--out", tmp_path)
    program = read_json(tmp_path / "quasistatic_summary.json")
    python = epicycle.quasistatic(epicycle.Scene.load(scene), positions=2, pin_feedback=False).record
    same_record(program, python)
    with_feedback = epicycle.quasistatic(epicycle.Scene.load(scene), positions=2).record
    assert "pins" in with_feedback and "pins" not in python


def test_study_record_equals_the_program_json(tmp_path):
    # Four cases of 24 positions (verification/data/studies/kgamma_limit_small.toml): every
    # default of both sides, the exceedances and the Spearman columns in the record.
    import os
    from conftest import SOURCE_DIR
    study = os.path.join(SOURCE_DIR, "verification", "data", "studies", "kgamma_limit_small.toml")
    run_cli("study", study, "--quiet", "--out", tmp_path)
    program = read_json(tmp_path / "study_summary.json")
    python = epicycle.study(study).record
    program.pop("computed_seconds")  # wall time: run-dependent
    python.pop("computed_seconds")
    same_record(program, python)
    assert program["cases_in_file"] == 4 and len(program["K_gamma_exceedance"]) == 2


def test_periodic_branch_record_equals_the_program_json(tmp_path):
    # The sun speed from 4000 to 4100 rpm in steps of at most 1/2 of the range (docs/periodic.md
    # §3): every other setting at its default on both sides (rtol 1e-6, rate scale 1e4, the
    # contact tolerance, the back end, 400 points at most).
    scene = scene_path("paper_stage.toml")
    run_cli("dynamic", scene, "--speed-sweep", "4000:4100:2", "--periodic", "--quiet", "--out",
            tmp_path)
    program = read_json(tmp_path / "periodic_branch_summary.json")
    python = epicycle.periodic_branch(epicycle.Scene.load(scene), "sun_speed_rpm", 4000, 4100,
                                      steps=2).record
    for times in (program, python):  # the run's own CPU and wall times: run-dependent
        times.pop("cpu_seconds")
        times.pop("wall_seconds")
    same_record(program, python)
    assert program["range"] == [4000, 4100] and program["max_step"] == 0.5
    assert program["rate_tolerance_scale_rad_per_s"] == 1e4 and program["rtol"] == 1e-6
    assert program["status"] == "completed" and len(program["points"]) >= 2


def test_comparison_record_equals_the_program_json(tmp_path):
    # Every available back end on two problems of the collection, every setting at its default on
    # both sides (tolerance 1e-10, 5 solves per run); the runs' median times are wall times, the
    # only values two runs may differ in.
    collection = os.path.join(SOURCE_DIR, "verification", "data", "contact")
    inputs = [os.path.join(collection, n) for n in ("cf_one_contact_open.json",
                                                    "cf_one_contact_load.json")]
    # nlopt-lbfgs takes no equalities: its run on cf_one_contact_load (one) is a failed run, which
    # the program's exit status (1) and both records' failures list.
    p = run_cli("contact", "compare", *inputs, "--json", tmp_path / "compare.json", check=False)
    program = read_json(tmp_path / "compare.json")
    python = epicycle.compare_backends(inputs).record
    for record in (program, python):
        for item in record["backends"] + record["runs"]:
            del item["median_seconds"]
    same_record(program, python)
    assert program["repeats"] == 5 and program["tolerance"] == 1e-10  # the defaults, both sides
    assert p.returncode == (1 if python["failures"] else 0)
    assert python["failures"] == epicycle.compare_backends(inputs, repeats=1).failures
    assert len(program["runs"]) == 2 * len(epicycle.contact_backends())
