"""The quasi-static sweep through Python equals the `epicycle quasistatic` files to their printed
digits: the paper's run-out case over one planet revolution (30 positions), sun fixed and floating
(the Python scene's supports.sun key, the program's --sun)."""

import threading

import pytest

import epicycle
from conftest import deg, num, read_csv, read_json, run_cli, scene_path

POSITIONS = 30


def python_sweep(sun, **kw):
    scene = epicycle.Scene.load(scene_path("paper_stage_runout.toml"))
    scene.set("supports.sun", sun)
    return epicycle.quasistatic(scene, range="planet", positions=POSITIONS, threads=1, **kw)


@pytest.mark.parametrize("sun", ["fixed", "floating"])
def test_quasistatic_equals_the_program_files(tmp_path, sun):
    out = tmp_path / "cli"
    run_cli("quasistatic", scene_path("paper_stage_runout.toml"), "--range", "planet",
            "--positions", POSITIONS, "--threads", 1, "--sun", sun, "--quiet", "--out", out)
    rows = read_csv(out / "quasistatic_positions.csv")
    r = python_sweep(sun)
    n = r.planets
    assert n == 3 and r.sun_support == sun
    assert len(rows) == POSITIONS == len(r.carrier_deg)
    for k, row in enumerate(rows):
        assert row["carrier_deg"] == deg(r.carrier_deg[k])
        assert row["converged"] == str(int(r.converged[k]))
        for i in range(n):
            assert row[f"LSR_{i + 1}"] == num(r.lsr[k, i])
            assert row[f"L_{i + 1}"] == num(r.load_sharing_factor[k, i])
        assert row["K_gamma"] == num(r.k_gamma[k])
        assert row["transmission_error_urad"] == num(r.te_urad[k])
        assert row["sun_x_um"] == num(r.sun_x_um[k])
        assert row["sun_y_um"] == num(r.sun_y_um[k])
        assert row["geometric_iterations"] == str(r.geometric_iterations[k])
        assert row["contact_iterations"] == str(r.contact_iterations[k])
        assert row["warm_started"] == str(int(r.warm_started[k]))
        assert row["residual"] == num(r.residual[k])
        assert row["status"] == r.status[k]
        assert row["active_contacts"] == str(r.active_contacts[k])
        assert row["contacts"] == str(r.contacts[k])
    pairs = read_csv(out / "quasistatic_pairs.csv")
    p = r.pairs
    assert len(pairs) == len(p.force_N) > POSITIONS
    for j, row in enumerate(pairs):
        assert row["carrier_deg"] == deg(p.carrier_deg[j])
        assert row["mesh"] == p.mesh[j]
        assert row["kind"] == p.kind[j]
        assert row["flank"] == p.flank[j]
        assert row["teeth"] == f"{p.tooth_a[j]}/{p.tooth_b[j]}"
        assert row["force_N"] == num(p.force_N[j])
    # The summary: JSON numbers carry every digit, so they are compared exactly.
    j = read_json(out / "quasistatic_summary.json")
    s = r.summary
    assert j["K_gamma_max"] == s.k_gamma
    assert j["transmission_error_min_urad"] == s.te_min_urad
    assert j["transmission_error_max_urad"] == s.te_max_urad
    assert j["sun_displacement_max_um"] == s.sun_displacement_max_um
    for i, planet in enumerate(j["planets"]):
        assert planet["lsr_mean"] == s.lsr_mean[i]
        assert planet["lsr_min"] == s.lsr_min[i]
        assert planet["lsr_max"] == s.lsr_max[i]
    assert j["converged_positions"] == s.converged == POSITIONS


def test_two_threads_at_once_equal_one_after_the_other():
    # Each sweep on one worker (its warm starts in sequence), so a sweep's result does not depend
    # on what else runs: the two at once must give the bytes of the two in turn.
    alone = {sun: python_sweep(sun) for sun in ("fixed", "floating")}
    together = {}

    def run(sun):
        together[sun] = python_sweep(sun)

    threads = [threading.Thread(target=run, args=(sun,)) for sun in ("fixed", "floating")]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for sun in ("fixed", "floating"):
        a, b = alone[sun], together[sun]
        assert (a.lsr == b.lsr).all() and (a.te_urad == b.te_urad).all()
        assert (a.sun_x_um == b.sun_x_um).all() and (a.sun_y_um == b.sun_y_um).all()
        assert (a.pairs.force_N == b.pairs.force_N).all()
    # and the two cases differ (a floating sun shares the load differently)
    assert not (alone["fixed"].lsr == alone["floating"].lsr).all()


def test_an_added_runout_equals_the_scene_file_with_it():
    # scene.add_runout writes the [[errors.runout]] table of scenes/paper_stage_runout.toml.
    scene = epicycle.Scene.load(scene_path("paper_stage.toml"))
    scene.add_runout("planet1", amplitude_um=20.0, phase_deg=0.0)
    a = epicycle.quasistatic(scene, range="planet", positions=12, threads=1)
    b = epicycle.quasistatic(epicycle.Scene.load(scene_path("paper_stage_runout.toml")),
                             range="planet", positions=12, threads=1)
    assert (a.lsr == b.lsr).all() and (a.te_urad == b.te_urad).all()


def test_progress_is_called_in_order_and_its_exception_stops_the_sweep():
    scene = epicycle.Scene.load(scene_path("paper_stage.toml"))
    seen = []
    epicycle.quasistatic(scene, positions=6, threads=2, progress=lambda d, t: seen.append((d, t)))
    assert seen == [(k, 6) for k in range(1, 7)]

    def stop(done, total):
        if done == 2:
            raise KeyError("stop here")

    with pytest.raises(KeyError, match="stop here"):
        epicycle.quasistatic(scene, positions=30, threads=1, progress=stop)


def test_failed_positions_raise_computation_error_with_the_results():
    # nlopt-lbfgs handles only problems without equalities: every position of a stage fails.
    scene = epicycle.Scene.load(scene_path("paper_stage.toml"))
    with pytest.raises(epicycle.ComputationError, match="3 of 3 positions failed") as e:
        epicycle.quasistatic(scene, positions=3, threads=1, backend="nlopt-lbfgs")
    r = e.value.result
    assert not r.converged.any() and len(r.message) == 3
    assert "nlopt-lbfgs handles only problems without equalities" in r.message[0]
    r = epicycle.quasistatic(scene, positions=3, threads=1, backend="nlopt-lbfgs",
                             raise_on_failure=False)
    assert r.summary.converged == 0


@pytest.mark.parametrize("sun", ["fixed", "floating"])
def test_quasistatic_friction_at_rest_equals_the_program_files(tmp_path, sun):
    """Friction at rest (docs/quasistatic.md): the loss, powers and efficiency per position and the
    summary's efficiency through Python equal the program's columns to their printed digits."""
    out = tmp_path / "cli"
    run_cli("quasistatic", scene_path("paper_stage_runout.toml"), "--range", "planet",
            "--positions", POSITIONS, "--threads", 1, "--sun", sun, "--friction", "constant",
            "--quiet", "--out", out)
    rows = read_csv(out / "quasistatic_positions.csv")
    r = python_sweep(sun, friction="constant")
    assert r.friction == "constant"
    assert len(rows) == POSITIONS == len(r.efficiency)
    for k, row in enumerate(rows):
        assert row["LSR_1"] == num(r.lsr[k, 0])
        assert row["friction_power_W"] == num(r.friction_power_W[k])
        assert row["input_power_W"] == num(r.input_power_W[k])
        assert row["output_power_W"] == num(r.output_power_W[k])
        assert row["efficiency"] == num(r.efficiency[k])
        assert row["force_change"] == num(r.force_change[k])
    pairs = read_csv(out / "quasistatic_pairs.csv")
    assert len(pairs) == len(r.pairs.friction_N)
    for j, row in enumerate(pairs):
        assert row["friction_N"] == num(r.pairs.friction_N[j])
        assert row["sliding_m_per_s"] == num(r.pairs.sliding_m_per_s[j])
    j = read_json(out / "quasistatic_summary.json")
    assert j["friction"] == "constant"
    assert j["efficiency_mean"] == r.summary.efficiency_mean
    assert j["friction_power_mean_W"] == r.summary.friction_power_mean_W
    with pytest.raises(ValueError, match="friction = \"wet\": must be one of off, scene"):
        python_sweep(sun, friction="wet")


def test_quasistatic_rating_equals_the_program(tmp_path):
    """Stresses and ratings (docs/stresses.md): the summary's root stresses and contact pressures
    and the rating through Python equal the program's summary JSON; a rating without the
    material's limits raises ValueError naming the key."""
    text = open(scene_path("paper_stage_runout.toml")).read().replace(
        "poisson_ratio = 0.3\n", "poisson_ratio = 0.3\nbending_limit_MPa = 430\n"
        "contact_limit_MPa = 1500\n", 1)
    path = tmp_path / "rated.toml"
    path.write_text(text)
    out = tmp_path / "cli"
    run_cli("quasistatic", path, "--positions", 6, "--threads", 1, "--rating", "--quiet",
            "--out", out)
    j = read_json(out / "quasistatic_summary.json")
    r = epicycle.quasistatic(epicycle.Scene.load(str(path)), positions=6, threads=1, rating=True)
    assert r.summary.root_stress == j["root_stress"]
    assert r.summary.contact_pressure == j["contact_pressure"]
    assert r.rating == j["rating"]
    assert len(r.rating["gears"]) == 5
    with pytest.raises(ValueError, match=r"rating=True needs the scene's \[material\] "
                                         r"bending_limit_MPa"):
        epicycle.quasistatic(epicycle.Scene.load(scene_path("paper_stage_runout.toml")),
                             positions=2, rating=True)
