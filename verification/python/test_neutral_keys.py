"""Keys at their neutral values give today's plane spur model (docs/geometry.md, "Helical gears";
docs/face_width.md, "Slices"): each driver of the program, run once on a scene and once on the
same text with a zero helix angle, or a single face-width slice, written in, writes the same files,
byte for byte once the timing and provenance fields are masked as tools/docs_outputs.py masks
them for the docs' outputs. Both scenes are written to the same path in turn, so that the only
difference the program sees is the key. Small runs: a few positions, a hundredth of a second of
motion, two speeds, two study cases."""

import os
import sys

import pytest

from conftest import SOURCE_DIR, run_cli, scene_path

sys.path.insert(0, os.path.join(SOURCE_DIR, "tools"))
import docs_outputs  # noqa: E402  (the masking of the docs' output check, one definition)


def pair_helix_zero(text):
    """A pair scene's gears each given helix_angle_deg = 0 (a spur gear's hand says nothing)."""
    for gear in ("[gear1]\n", "[gear2]\n"):
        assert gear in text, f"{gear.strip()} missing from the pair scene"
        text = text.replace(gear, gear + "helix_angle_deg = 0.0\n", 1)
    return text


def stage_helix_zero(text):
    return text + '\n[helix]\nhelix_angle_deg = 0.0\nsun_hand = "right"\n'


def one_slice(text):
    assert "[face_width]" not in text
    return text + "\n[face_width]\nslices = 1\n"


# (name, scene, the arguments after the scene); pair scenes first.
PAIR_RUNS = [
    ("stiffness pair", "iso_pair_20_40.toml", ["stiffness", "--positions", 4, "--stresses"]),
]
STAGE_RUNS = [
    ("quasistatic", "paper_stage_runout.toml",
     ["quasistatic", "--range", "cycle", "--positions", 3, "--stresses", "--quiet"]),
    ("stiffness mesh", "paper_stage.toml", ["stiffness", "--mesh", "sun-planet1", "--positions", 3]),
    ("dynamic", "paper_stage.toml", ["dynamic", "--time", 0.01, "--quiet"]),
    ("modes", "paper_stage.toml", ["modes"]),
    ("speed sweep", "paper_stage.toml",
     ["dynamic", "--speed-sweep", "4000:5000:2", "--window-cycles", 1, "--threads", 1, "--quiet"]),
    ("periodic branch", "paper_stage.toml",
     ["dynamic", "--speed-sweep", "4000:4100:2", "--periodic", "--quiet"]),
    # The study reads its scene beside it: studies/pin_tolerance.toml pointed at the folder's copy.
    ("study", "paper_stage.toml", ["study", "--max-cases", 2, "--threads", 1, "--quiet"]),
]
CASES = (
    [("helix 0, " + n, s, pair_helix_zero, a) for n, s, a in PAIR_RUNS]
    + [("helix 0, " + n, s, stage_helix_zero, a) for n, s, a in STAGE_RUNS]
    + [("1 slice, " + n, s, one_slice, a) for n, s, a in PAIR_RUNS + STAGE_RUNS]
    # A sliced scene at helix 0: the spur slices (20, a pin tilted).
    + [("helix 0, 20 slices, quasistatic", "paper_stage_pin_tilt.toml", stage_helix_zero,
        ["quasistatic", "--positions", 3, "--quiet"])]
)


def study_beside(folder, scene):
    """scenes/studies/pin_tolerance.toml with its scene the copy in `folder`."""
    text = open(scene_path("studies/pin_tolerance.toml")).read()
    assert 'scene = "../paper_stage.toml"' in text
    path = folder / "study.toml"
    path.write_text(text.replace('scene = "../paper_stage.toml"', f'scene = "{scene}"', 1))
    return path


@pytest.mark.parametrize("name,scene,edit,args", CASES, ids=[c[0] for c in CASES])
def test_a_neutral_key_writes_the_same_files(tmp_path, name, scene, edit, args):
    text = open(scene_path(scene)).read()
    assert "helix_angle_deg" not in text, f"{scene} is not a spur scene"
    outs = []
    folder = tmp_path / "scene"  # one path for both runs: the files name their scene
    folder.mkdir()
    for label, body in (("plain", text), ("neutral", edit(text))):
        path = folder / scene
        path.write_text(body)
        if args[0] == "study":
            path = study_beside(folder, scene)
        out = tmp_path / label
        if args[0] == "modes":  # modes writes its JSON where --json says
            out.mkdir()
            run_cli(args[0], path, *args[1:], "--json", out / "modes.json")
        else:
            run_cli(args[0], path, *args[1:], "--out", out)
        outs.append(out)
    plain, neutral = outs
    files = sorted(os.listdir(plain))
    assert files, f"{name}: no file written"
    assert sorted(os.listdir(neutral)) == files, f"{name}: the two runs wrote different files"
    for f in files:
        a, b = docs_outputs.masked(str(plain / f)), docs_outputs.masked(str(neutral / f))
        assert a == b, f"{name}: {f} differs with the key written in"
