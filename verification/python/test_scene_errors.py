"""Bad input from Python raises ValueError with the scene reader's message, the message the
program prints for the same file (name and line included): one case per class of scene error (a
value out of its range, a wrong type, an unknown key, a missing key, a gear the stage does not
have, a word that is not one of the allowed, a pitch class outside ISO 1328-1), each naming its
key; a refused edit leaves the scene unchanged and hands back the refused text."""

import pytest

import epicycle
from conftest import run_cli, scene_path

CASES = [
    # (edit, the key the message names, the rule's words)
    (lambda s: s.add_runout("planet1", amplitude_um=1e6), "errors.runout[0].amplitude_um",
     "must be in [0, 1057.5]"),
    (lambda s: s.set("load.sun_torque_Nm", "strong"), "load.sun_torque_Nm", "must be a number"),
    (lambda s: s.set("sun.colour", "red"), "sun.colour", "unknown"),
    (lambda s: s.set("sun.teeth", None), "sun.teeth", "missing"),
    (lambda s: s.add_pin("planet7", radial_um=5.0), "errors.pin[0].gear", "planet7"),
    (lambda s: s.add_thickness("sun", error_um=-5000.0), "errors.thickness[0].error_um",
     "must be in"),
    (lambda s: s.set("supports.sun", "wobbly"), "supports.sun", "wobbly"),
    (lambda s: s.set_pitch("planet", iso1328_grade=40), "planet.pitch.iso1328_grade", "40"),
    (lambda s: s.add_pit("planet1", 13, "-", roll_deg=(23.0, 28.0), depth_um=5000.0),
     "damage.pit[0].depth_um", "must be in"),
]


@pytest.mark.parametrize("edit,key,rule", CASES)
def test_a_bad_value_raises_the_program_message(tmp_path, edit, key, rule):
    path = tmp_path / "bad.toml"
    with open(scene_path("paper_stage.toml")) as f:
        s = epicycle.Scene.parse(f.read(), source=str(path))
    before = s.text
    with pytest.raises(ValueError) as e:
        edit(s)
    message = str(e.value)
    assert key in message and rule in message and str(path) in message
    assert s.text == before  # unchanged
    # The program reads the refused text from that file and prints the same message.
    path.write_text(e.value.scene_text)
    p = run_cli("geometry", path, check=False)
    assert p.returncode == 2
    assert message in p.stderr


def test_a_syntax_error_and_a_missing_file():
    with pytest.raises(ValueError, match=r"bad\.toml.*2"):
        epicycle.Scene.parse("[scene]\nname = \n", source="bad.toml")
    with pytest.raises(ValueError, match=r"/nonexistent/scene\.toml: cannot be opened"):
        epicycle.Scene.load("/nonexistent/scene.toml")


def test_bad_driver_arguments_name_the_argument():
    s = epicycle.Scene.load(scene_path("paper_stage.toml"))
    with pytest.raises(ValueError, match="nonsense"):
        epicycle.quasistatic(s, range="nonsense")
    with pytest.raises(ValueError, match="threads"):
        epicycle.quasistatic(s, threads=-1)
    with pytest.raises(ValueError, match="no-such-backend"):
        epicycle.quasistatic(s, backend="no-such-backend")
    with pytest.raises(ValueError, match=r"dynamics\.sun_speed_rpm"):
        epicycle.dynamic(s, sun_speed_rpm=-5.0)
    with pytest.raises(ValueError, match="gear-pair scene"):
        epicycle.quasistatic(epicycle.Scene.load(scene_path("iso_pair_20_40.toml")))


def test_keys_read_and_change_in_their_units():
    s = epicycle.Scene.load(scene_path("paper_stage.toml"))
    assert s["load.sun_torque_Nm"] == -600.0 and s["carrier.planets"] == 3
    assert "errors.runout[0].amplitude_um" not in s
    s.add_runout("planet2", amplitude_um=10.0, phase_deg=90.0)
    assert s["errors.runout[0].gear"] == "planet2"
    assert s["errors.runout[0].amplitude_um"] == 10.0
    t = s.with_values({"load.sun_torque_Nm": -700, "supports.sun": "floating"})
    assert t.sun_torque_Nm == -700.0 and t.sun_support == "floating"
    assert s.sun_torque_Nm == -600.0 and s.sun_support == "fixed"
    with pytest.raises(KeyError):
        s["load.nothing_Nm"]
