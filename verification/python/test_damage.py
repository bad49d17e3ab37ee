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


CRACK = """
[[damage.crack]]
gear = "sun"
tooth = 0
side = "-"
depth_mm = 1.0
angle_deg = 45
"""


def test_add_crack_equals_the_scene_text():
    """Scene.add_crack writes the [[damage.crack]] table the scene text has (written by hand
    here), so the sweeps are equal position by position; the crack changes the TE where the
    cracked sun tooth meshes (one sun turn relative to the carrier)."""
    base = epicycle.Scene.load(scene_path("paper_stage.toml"))
    cracked = base.copy()
    cracked.add_crack("sun", 0, "-", depth_mm=1.0, angle_deg=45.0)
    assert cracked["damage.crack[0].side"] == "-"
    assert cracked["damage.crack[0].depth_mm"] == 1.0
    with open(scene_path("paper_stage.toml")) as f:
        text = epicycle.Scene.parse(f.read() + CRACK, source="cracked.toml")
    a = epicycle.quasistatic(cracked, range="sun", positions=32, threads=1)
    b = epicycle.quasistatic(text, range="sun", positions=32, threads=1)
    h = epicycle.quasistatic(base, range="sun", positions=32, threads=1)
    assert np.array_equal(a.lsr, b.lsr)
    assert np.array_equal(a.te_urad, b.te_urad)
    assert np.max(np.abs(a.te_urad - h.te_urad)) > 0.1


def test_add_crack_polyline_and_errors():
    s = epicycle.Scene.load(scene_path("paper_stage.toml"))
    s.add_crack("planet2", 3, "+", start="iso_30deg", path_mm_deg=[(0.5, 45.0), (0.25, 80.0)])
    assert s["damage.crack[0].path[1].angle_deg"] == 80.0
    try:
        s.add_crack("planet2", 5, "+", depth_mm=1.0, angle_deg=45.0)
    except ValueError as e:
        assert "damage.crack[1].gear" in str(e) and "one root crack per gear" in str(e)
    else:
        raise AssertionError("a second crack on one gear was added")
