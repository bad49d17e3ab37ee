"""The other drivers through Python equal the program's outputs on the same scenes: the geometry
report (`geometry --json`), the potential contacts at a pose (`contacts`, its printed columns),
a mesh's stiffness (`stiffness`: CSV to the printed digits, JSON exactly) and a two-speed sweep
(`dynamic --speed-sweep`: CSV to the printed digits, the load-sharing parts included)."""

import pytest

import epicycle
from conftest import num, read_csv, read_json, run_cli, scene_path


def test_geometry_report_equals_the_program_json(tmp_path):
    path = tmp_path / "geometry.json"
    run_cli("geometry", scene_path("paper_stage_runout.toml"), "--json", path)
    j = read_json(path)
    g = epicycle.geometry(epicycle.Scene.load(scene_path("paper_stage_runout.toml")))
    for key in ("gears", "meshes", "assembly", "fits", "gear_order"):
        assert g.report[key] == j[key], key
    sun = g.gears["sun"]
    assert sun.teeth == 16 and sun.outline_mm.shape[1] == 2
    # the outline's radii lie between the root and tip circles of the report
    r = (sun.outline_mm ** 2).sum(axis=1) ** 0.5
    assert r.max() <= j["gears"]["sun"]["tip_radius_mm"] + 1e-9
    assert r.min() >= j["gears"]["sun"]["root_radius_mm"] - 1e-9


def test_contacts_equal_the_program_table():
    p = run_cli("contacts", scene_path("paper_stage_runout.toml"), "--carrier-deg", 10)
    rows = [line.split() for line in p.stdout.splitlines()
            if line.startswith("  sun-planet") or line.startswith("  planet")]
    c = epicycle.contacts(epicycle.Scene.load(scene_path("paper_stage_runout.toml")), 10.0)
    assert len(rows) == len(c.mesh) > 6
    for k, row in enumerate(rows):
        assert row[:5] == [c.mesh[k], c.kind[k], c.flank[k], str(c.tooth[k]), str(c.mate[k])]
        assert row[5:] == ["%.4f" % c.x_mm[k], "%.4f" % c.y_mm[k], "%.6f" % c.normal_x[k],
                           "%.6f" % c.normal_y[k], "%.3f" % c.overlap_um[k],
                           "%.3f" % c.arm_a_mm[k], "%.3f" % c.arm_b_mm[k],
                           "%.3f" % c.curvature_radius_a_mm[k], "%.3f" % c.curvature_radius_b_mm[k]]


def test_mesh_stiffness_equals_the_program_files(tmp_path):
    out = tmp_path / "cli"
    run_cli("stiffness", scene_path("iso_pair_20_40.toml"), "--positions", 12, "--out", out)
    m = epicycle.mesh_stiffness(epicycle.Scene.load(scene_path("iso_pair_20_40.toml")),
                                positions=12)
    j = read_json(out / f"stiffness_{m.mesh}.json")
    assert j["mean_mesh_stiffness_N_per_m"] == m.mean_stiffness_N_per_m
    assert j["peak_single_pair_stiffness_N_per_mm_um"] == m.peak_pair_stiffness_N_per_mm_um
    assert j["iso6336_c_gamma_alpha_N_per_mm_um"] == m.iso6336_c_gamma_alpha_N_per_mm_um
    assert j["contact_ratio"] == m.contact_ratio
    rows = read_csv(out / f"stiffness_{m.mesh}.csv")
    p = m.pairs
    assert len(rows) == len(p.force_N)
    for k, row in enumerate(rows):
        assert row["angle_deg"] == "%.6f" % p.angle_deg[k]
        assert row["pair_teeth"] == f"{p.tooth1[k]}/{p.tooth2[k]}"
        assert row["pair_force_N"] == num(p.force_N[k])
        assert row["pair_stiffness_N_per_m"] == num(p.stiffness_N_per_m[k])
        assert row["pair_share"] == num(p.share[k])
    by_angle = {("%.6f" % a): (k, t) for a, k, t in
                zip(m.angle_deg, m.stiffness_N_per_m, m.rotation_urad)}
    for row in rows:
        k, t = by_angle[row["angle_deg"]]
        assert row["mesh_stiffness_N_per_m"] == num(k)
        assert row["transmission_error_urad"] == num(t)


def assert_same_sweep_record(record, summary):
    """Python's speed-sweep record against the program's summary JSON: the same keys (but the
    provenance) and values, bit for bit, but the times (wall and CPU, per speed `*_s`)."""
    times = {"plan_seconds", "wall_seconds", "cpu_seconds_in_speeds", "cpu_over_wall"}
    assert sorted(record) == sorted(k for k in summary if k != "provenance")
    for key in record:
        if key not in times and key != "speeds":
            assert record[key] == summary[key], key
    assert len(record["speeds"]) == len(summary["speeds"])
    for a, b in zip(record["speeds"], summary["speeds"]):
        assert {k: v for k, v in a.items() if not k.endswith("_s")} == \
            {k: v for k, v in b.items() if not k.endswith("_s")}


def test_speed_sweep_equals_the_program_csv(tmp_path):
    out = tmp_path / "cli"
    run_cli("dynamic", scene_path("paper_stage.toml"), "--speed-sweep", "1000:3000:2",
            "--window-cycles", 1, "--outputs-per-cycle", 8, "--threads", 2, "--quiet",
            "--out", out)
    rows = read_csv(out / "speed_sweep.csv")
    s = epicycle.speed_sweep(epicycle.Scene.load(scene_path("paper_stage.toml")),
                             epicycle.speed_grid(1000, 3000, 2), window_cycles=1,
                             outputs_per_cycle=8, threads=2)
    assert len(rows) == 2 and s.ok.all()
    rows.sort(key=lambda row: int(row["index"]))
    for k, row in enumerate(rows):
        assert row["sun_speed_rpm"] == num(s.sun_speed_rpm[k])
        assert row["mesh_frequency_Hz"] == num(s.mesh_frequency_Hz[k])
        assert row["K_gamma"] == num(s.k_gamma[k])
        assert row["dynamic_factor"] == num(s.dynamic_factor[k])
        assert row["dynamic_factor_mesh"] == s.dynamic_factor_mesh[k]
        assert row["peak_mesh_force_N"] == num(s.peak_mesh_force_N[k])
        assert row["te_amplitude_urad"] == num(s.te_amplitude_urad[k])
        assert row["sun_orbit_radius_um"] == num(s.sun_orbit_radius_um[k])
        assert row["lsr_min"] == num(s.lsr_min[k]) and row["lsr_max"] == num(s.lsr_max[k])
        assert row["lsr_deviation"] == num(s.lsr_deviation[k])
        for name in ("sun_rotation", "sun_translation", "bearing", "friction", "off_line",
                     "geometry", "residual"):
            assert row["dev_" + name] == num(getattr(s.lsr_deviation_parts, name)[k]), name
        assert row["largest_residual"] == num(s.largest_residual[k])
        # K_v is the ratio of the mesh's peak in motion to its reference's (the same doubles
        # divided: equal to the last bit).
        assert s.dynamic_factor[k] == s.peak_mesh_force_N[k] / s.reference_peak_mesh_force_N[k]
    # The record: the keys and values of the program's summary JSON, defaults included, bit for
    # bit but the times and the provenance (the same request, the same run).
    j = read_json(out / "speed_sweep_summary.json")
    assert_same_sweep_record(s.record, j)


@pytest.mark.parametrize("method", ["shooting", "hb"])
def test_periodic_branch_equals_the_program_csv(tmp_path, method):
    """The periodic orbits over the sun speed as arrays: the program's branch, point by point, by
    shooting and by harmonic balance (`--periodic-method hb`, `method="hb"`)."""
    out = tmp_path / "cli"
    run_cli("dynamic", scene_path("paper_stage.toml"), "--speed-sweep", "4000:4100:2",
            "--periodic", "--periodic-method", method, "--quiet", "--out", out)
    rows = read_csv(out / "periodic_branch.csv")
    b = epicycle.periodic_branch(epicycle.Scene.load(scene_path("paper_stage.toml")),
                                 "sun_speed_rpm", 4000, 4100, steps=2, method=method)
    assert b.record["method"] == method
    assert b.record["harmonics"] == (24 if method == "hb" else 0)
    assert b.ok and b.status == "completed" and b.unit == "rpm"
    assert len(rows) == len(b.sun_speed_rpm) >= 2
    assert b.sun_speed_rpm[0] == 4000 and b.sun_speed_rpm[-1] >= 4100
    assert b.state.shape == (len(rows), len(b.state_labels))
    for k, row in enumerate(rows):
        assert row["sun_speed_rpm"] == num(b.sun_speed_rpm[k])
        assert row["period_s"] == num(b.period_s[k])
        assert row["stability"] == b.stability[k]
        assert (row["stability"] != "unstable") == b.stable[k]
        assert row["spectral_radius"] == num(b.spectral_radius[k])
        assert row["K_gamma"] == num(b.k_gamma[k])
        assert row["te_amplitude_urad"] == num(b.te_amplitude_urad[k])


def test_periodic_branch_bad_input_names_the_argument():
    import pytest

    scene = epicycle.Scene.load(scene_path("paper_stage.toml"))
    with pytest.raises(ValueError, match="parameter = 'speed': not a key of the scene"):
        epicycle.periodic_branch(scene, "speed", 1000, 2000, cache_dir="")
    with pytest.raises(ValueError, match="parameter = 'scene.name': not a number in the scene"):
        epicycle.periodic_branch(scene, "scene.name", 1, 2, cache_dir="")
    with pytest.raises(ValueError,
                       match="parameter = 'sun.teeth': a number of the scene that a branch "
                             "cannot continue"):
        epicycle.periodic_branch(scene, "sun.teeth", 16, 17, cache_dir="")
    with pytest.raises(ValueError, match="'errors.runout.planet1.amplitude_um': a run-out turns "
                                         "with its gear: the stage's period with it = 24"):
        epicycle.periodic_branch(scene, "errors.runout.planet1.amplitude_um", 0, 20, cache_dir="")
    with pytest.raises(ValueError, match="end = 1000: equals start = 1000: the range must have"):
        epicycle.periodic_branch(scene, "sun_speed_rpm", 1000, 1000, cache_dir="")
    with pytest.raises(ValueError, match="steps = 0: must be >= 1"):
        epicycle.periodic_branch(scene, "sun_speed_rpm", 1000, 2000, steps=0, cache_dir="")
    runout = epicycle.Scene.load(scene_path("paper_stage_runout.toml"))
    with pytest.raises(ValueError, match="period = 24 mesh cycles .planet1 run-out"):
        epicycle.periodic_branch(runout, "sun_speed_rpm", 1000, 2000, cache_dir="")
    with pytest.raises(ValueError, match="method = 'fourier': not a periodic method .shooting, hb"):
        epicycle.periodic_branch(scene, "sun_speed_rpm", 1000, 2000, method="fourier",
                                 cache_dir="")
    with pytest.raises(ValueError, match="harmonics = 8: must be >= 1, with the harmonic-balance"):
        epicycle.periodic_branch(scene, "sun_speed_rpm", 1000, 2000, harmonics=8, cache_dir="")


def test_carried_speed_sweep_equals_the_program(tmp_path):
    """A run-up that carries each speed's end state into the next (`--carry-state up`,
    docs/speed_sweeps.md "Carried state"): Python's record is the program's summary JSON, times and
    provenance aside; an unknown carry is a ValueError naming the argument."""
    out = tmp_path / "cli"
    run_cli("dynamic", scene_path("paper_stage.toml"), "--speed-sweep", "1000:3000:2",
            "--window-cycles", 1, "--outputs-per-cycle", 8, "--carry-state", "up", "--quiet",
            "--out", out)
    j = read_json(out / "speed_sweep_summary.json")
    s = epicycle.speed_sweep(epicycle.Scene.load(scene_path("paper_stage.toml")),
                             epicycle.speed_grid(1000, 3000, 2), window_cycles=1,
                             outputs_per_cycle=8, carry_state="up")
    assert j["carry_state"] == s.record["carry_state"] == "up"
    assert j["threads"] == s.record["threads"] == 1  # one speed after the other
    assert_same_sweep_record(s.record, j)
    with pytest.raises(ValueError, match="carry_state = 'sideways'"):
        epicycle.speed_sweep(epicycle.Scene.load(scene_path("paper_stage.toml")), [1000.0],
                             carry_state="sideways")


def test_speed_sweep_with_every_default_equals_the_program(tmp_path):
    """One speed with every option at its default on both sides: the window one planet
    revolution relative to the carrier (the paper stage's planet has 24 teeth: 24 mesh cycles) at
    64 samples per mesh cycle, one worker per core, no carried state, the integrator's and the
    contact solve's tolerances. Python's record is the program's summary JSON, times and
    provenance aside."""
    import os

    out = tmp_path / "cli"
    run_cli("dynamic", scene_path("paper_stage.toml"), "--speed-sweep", "1500:1500:1", "--quiet",
            "--out", out)
    j = read_json(out / "speed_sweep_summary.json")
    s = epicycle.speed_sweep(epicycle.Scene.load(scene_path("paper_stage.toml")), [1500.0])
    assert_same_sweep_record(s.record, j)
    assert j["window_mesh_cycles"] == 24 and j["window_samples"] == 24 * 64
    assert j["threads"] == s.record["threads"] == os.cpu_count()
    assert j["carry_state"] == "none" and j["rtol"] == 1e-6
