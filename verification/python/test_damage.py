"""Damage from Python: Scene.add_pit writes the [[damage.pit]] table the scene file has (the
reference is scenes/paper_stage_spall.toml, written by hand), so a quasi-static sweep of the
paper stage with the pit added equals the sweep of that file, position by position; the pit
changes the TE where the tooth meshes."""

import numpy as np

import epicycle
from conftest import scene_path


def test_add_pit_equals_the_scene_file():
    base = epicycle.Scene.load(scene_path("paper_stage.toml"))
    pitted = base.copy()
    pitted.add_pit("planet1", 13, "-", roll_deg=(23.0, 28.0), width_fraction=0.5, depth_um=30.0)
    assert pitted["damage.pit[0].tooth"] == 13
    assert pitted["damage.pit[0].depth_um"] == 30.0
    spall = epicycle.Scene.load(scene_path("paper_stage_spall.toml"))
    a = epicycle.quasistatic(pitted, range="planet", positions=48, threads=1)
    b = epicycle.quasistatic(spall, range="planet", positions=48, threads=1)
    h = epicycle.quasistatic(base, range="planet", positions=48, threads=1)
    assert np.array_equal(a.lsr, b.lsr)
    assert np.array_equal(a.te_urad, b.te_urad)
    # The pit acts: somewhere over the planet's turn the TE differs from the healthy stage's.
    assert np.max(np.abs(a.te_urad - h.te_urad)) > 0.1


def test_add_pit_needs_one_region():
    s = epicycle.Scene.load(scene_path("paper_stage.toml"))
    try:
        s.add_pit("planet1", 13, "-", depth_um=30.0)
    except ValueError as e:
        assert "roll_deg" in str(e) and "radius_mm" in str(e)
    else:
        raise AssertionError("a pit without a region was added")
