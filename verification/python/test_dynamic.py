"""The dynamic run, the natural modes and a speed sweep's plan through Python equal the program's
files: `epicycle dynamic` over one mesh cycle of the paper's run-out case at 1500 rpm, to the
printed digits of its CSVs (the vibration output's too); `epicycle modes --json` exactly (JSON carries every digit)."""

import pytest

import epicycle
from conftest import deg, num, read_csv, read_json, run_cli, scene_path


def test_dynamic_run_equals_the_program_files(tmp_path):
    out = tmp_path / "cli"
    run_cli("dynamic", scene_path("paper_stage_runout.toml"), "--range", "cycle",
            "--outputs-per-cycle", 12, "--quiet", "--out", out, "--spectrum",
            "--spectrum-skip-cycles", 0)
    r = epicycle.dynamic(epicycle.Scene.load(scene_path("paper_stage_runout.toml")),
                         range="cycle", outputs_per_cycle=12)
    assert r.completed and r.outputs == 12 and r.sun_speed_rpm == 1500.0
    steps = read_csv(out / "dynamic_steps.csv")
    n = r.planets
    assert len(steps) == len(r.time_s) == 12
    for k, row in enumerate(steps):
        assert row["time_s"] == num(r.time_s[k])
        assert row["carrier_deg"] == deg(r.carrier_deg[k])
        for i in range(n):
            assert row[f"LSR_{i + 1}"] == num(r.lsr[k, i])
            assert row[f"L_{i + 1}"] == num(r.load_sharing_factor[k, i])
        for column, values in [("K_gamma", r.k_gamma), ("transmission_error_urad", r.te_urad),
                               ("sun_x_um", r.sun_x_um), ("sun_y_um", r.sun_y_um),
                               ("sun_torque_balance_Nm", r.sun_torque_balance_Nm),
                               ("external_work_J", r.external_work_J),
                               ("dissipated_work_J", r.dissipated_work_J),
                               ("kinetic_energy_J", r.kinetic_energy_J),
                               ("elastic_energy_J", r.elastic_energy_J),
                               ("compliance_work_J", r.compliance_work_J),
                               ("friction_power_W", r.friction_power_W)]:
            assert row[column] == num(values[k]), column
        assert row["contacts"] == str(r.contacts[k])
        assert row["active_contacts"] == str(r.active_contacts[k])
    pairs = read_csv(out / "dynamic_pairs.csv")
    p = r.pairs
    assert len(pairs) == len(p.time_s) > 12
    for j, row in enumerate(pairs):
        assert row["time_s"] == num(p.time_s[j])
        assert (row["mesh"], row["kind"], row["flank"]) == (p.mesh[j], p.kind[j], p.flank[j])
        assert row["teeth"] == f"{p.tooth_a[j]}/{p.tooth_b[j]}"
        assert row["normal_force_N"] == num(p.normal_force_N[j])
        assert row["elastic_force_N"] == num(p.elastic_force_N[j])
        assert row["friction_force_N"] == num(p.friction_force_N[j])
        assert row["overlap_rate_mm_per_s"] == num(p.overlap_rate_mm_per_s[j])
    bearings = read_csv(out / "dynamic_bearings.csv")
    for k, row in enumerate(bearings):
        assert row["sun_Fx_N"] == num(r.sun_bearing_force_N[k, 0])
        assert row["sun_Fy_N"] == num(r.sun_bearing_force_N[k, 1])
    vibration = read_csv(out / "dynamic_vibration.csv")
    v = r.vibration
    assert [name for name, _ in v.channels] == [c for c in vibration[0] if c not in
                                                 ("time_s", "carrier_deg")]
    assert dict(v.channels)["te_rad"] == "torsional"
    assert dict(v.channels)["ring_force_x_N"] == "housing"
    assert len(vibration) == 12
    for k, row in enumerate(vibration):
        for name, _ in v.channels:
            # Written with 10 significant digits: equal to half a unit of the last, 5e-10.
            assert float(row[name]) == pytest.approx(getattr(v, name)[k], rel=5e-10, abs=0), name
    j = read_json(out / "dynamic_summary.json")
    s = r.summary
    assert j["K_gamma_max"] == s.k_gamma
    assert j["transmission_error_peak_to_peak_urad"] == s.te_peak_to_peak_urad
    assert j["sun_orbit_radius_max_um"] == s.orbit_radius_max_um
    assert j["mesh_stiffness_sun_planet_N_per_m"] == r.mesh_stiffness_sun_planet_N_per_m
    assert j["steps"] == r.stats.steps


def test_modes_equal_the_program_json(tmp_path):
    path = tmp_path / "modes.json"
    run_cli("modes", scene_path("paper_stage.toml"), "--json", path)
    j = read_json(path)
    m = epicycle.modes(epicycle.Scene.load(scene_path("paper_stage.toml")))
    assert len(j["modes"]) == len(m.frequency_Hz) >= 3
    assert j["mesh_stiffness_sun_planet_N_per_m"] == m.mesh_stiffness_sun_planet_N_per_m
    assert j["mesh_stiffness_planet_ring_N_per_m"] == m.mesh_stiffness_planet_ring_N_per_m
    assert j["secant_mesh_stiffness_sun_planet_N_per_m"] == m.secant_mesh_stiffness_sun_planet_N_per_m
    assert j["mesh_frequency_Hz_per_sun_rpm"] == m.mesh_hz_per_sun_rpm
    for k, mode in enumerate(j["modes"]):
        assert mode["frequency_Hz"] == m.frequency_Hz[k]
        assert mode["multiplicity"] == m.multiplicity[k]
        assert mode["type"] == m.type[k]
        assert mode["central_translation_energy"] == m.central_translation_energy[k]
        assert mode["central_rotation_energy"] == m.central_rotation_energy[k]
        assert mode["planet_energy"] == m.planet_energy[k]
        rpm = mode["sun_rpm_at_mesh_harmonics_1_2_3"]
        assert rpm == [v for v in m.sun_rpm_at_mesh_harmonics_1_2_3[k] if v == v]
        # a mode group's shapes: one column per mode of the group, one row per DOF
        assert m.shapes[k].shape == (len(m.dofs), m.multiplicity[k])


def test_dynamic_stresses_and_rating_equal_the_program(tmp_path):
    """Stresses and the rating in motion (docs/stresses.md, "Ratings in motion") through
    Python's dynamic equal `epicycle dynamic --rating`'s: the summary JSON's root_stress and
    rating key by key and value by value (JSON carries every digit), and each step's root
    stresses the steps file's sigma_t_<gear>_MPa, sigma_c_<gear>_MPa columns to their printed
    digits; a rating without the material's limits raises ValueError naming the key."""
    scene = epicycle.Scene.load(scene_path("paper_stage_runout_rated.toml"))
    assert "material.bending_limit_MPa" in scene and "material.contact_limit_MPa" in scene
    out = tmp_path / "cli"
    run_cli("dynamic", scene_path("paper_stage_runout_rated.toml"), "--range", "cycle",
            "--outputs-per-cycle", 8, "--rating", "--quiet", "--out", out)
    j = read_json(out / "dynamic_summary.json")
    r = epicycle.dynamic(scene, range="cycle", outputs_per_cycle=8, rating=True)
    assert r.completed and r.outputs == 8
    assert r.summary.root_stress == j["root_stress"]
    assert r.rating == j["rating"]
    assert len(r.rating["gears"]) == 5
    steps = read_csv(out / "dynamic_steps.csv")
    columns = [c for c in steps[0] if c.startswith("sigma_")]
    assert sorted(columns) == sorted(vars(r.root_stress)) and len(columns) == 10
    for k, row in enumerate(steps):
        for c in columns:
            assert row[c] == num(getattr(r.root_stress, c)[k]), (k, c)
    # stresses alone: the same stresses, no rating
    s = epicycle.dynamic(scene, range="cycle", outputs_per_cycle=8, stresses=True)
    assert s.summary.root_stress == j["root_stress"] and not hasattr(s, "rating")
    with pytest.raises(ValueError, match=r"rating=True needs the scene's \[material\] "
                                         r"bending_limit_MPa"):
        epicycle.dynamic(epicycle.Scene.load(scene_path("paper_stage_runout.toml")),
                         range="cycle", outputs_per_cycle=8, rating=True)
