"""Every driver and constructor takes its options by keyword only (docs/python.md, "Drivers"):
the essentials (the scene, the speeds, a problem, a gear) are positional, every other argument is
after the `*` of its signature, and a call that passes an option positionally raises TypeError.

The callables are listed from the module (every public function, every public method of its
classes and their constructors), not by hand; a new one whose positional arguments have no
sample value here fails the test until it gets one.
"""

import ast
import inspect

import numpy as np
import pytest

import epicycle
from conftest import SOURCE_DIR, parse_signature, public_callables, scene_path, signature_doc

# Arguments with a default that stay positional: each is what a caller passes second as a matter
# of course (the pose of contacts, the mesh of mesh_stiffness, the speed of dynamic, the back end
# of solve_contact, the multipliers of an answer, dict.get's default).
POSITIONAL_DEFAULTS = {
    ("contacts", "carrier_deg"),
    ("mesh_stiffness", "mesh"),
    ("dynamic", "sun_speed_rpm"),
    ("solve_contact", "backend"),
    ("contact_residuals", "multiplier"),
    ("Scene.get", "default"),
}


def parameters(doc, name):
    """(positional, keyword-only) parameters of a callable's pybind11 signature line: lists of
    (name, default text or None); self, *args and **kwargs left out."""
    params, _ = parse_signature(doc, name)
    positional = [(p, d) for p, _, d, kind in params if kind == "positional" and p != "self"]
    keyword = [(p, d) for p, _, d, kind in params if kind == "keyword"]
    return positional, keyword


@pytest.fixture(scope="module")
def samples():
    stage = epicycle.Scene.load(scene_path("paper_stage_runout.toml"))
    pair = epicycle.Scene.load(scene_path("iso_pair_20_40.toml"))
    problem = epicycle.ContactProblem(np.eye(2) * 1e-9, np.array([1e-6, -1e-6]))
    rng = np.random.default_rng(1)
    return {
        # A stage driver given a pair scene refuses it (ValueError) once its arguments are bound:
        # so a call that binds its arguments ends fast, whatever it would compute.
        "scene": pair,
        "sun_speeds_rpm": [1000.0],
        "path": f"{SOURCE_DIR}/scenes/studies/pin_tolerance.toml",
        "y": list(rng.normal(size=3 * 8)),
        "d": 1,
        "problem": problem,
        "force_N": np.zeros(2),
        "multiplier": None,
        "reference_force_N": np.zeros(2),
        "reference_multiplier": None,
        "compliance_m_per_N": np.eye(2) * 1e-9,
        "overlap_m": np.array([1e-6, -1e-6]),
        "from_rpm": 100.0, "to_rpm": 200.0, "count": 2,
        "parameter": "sun_speed_rpm", "start": 1000.0, "end": 2000.0,
        "gear": "planet1", "tooth": 0, "flank": "+", "side": "+",
        "amplitude_um": 1.0, "error_um": 1.0,
        "key": "load.sun_torque_Nm", "value": -700.0, "values": {},
        "text": stage.text,
        "contact": 0,
        "carrier_deg": 0.0, "mesh": "", "sun_speed_rpm": None, "backend": "newton",
        "default": None,
        "depth_um": 1.0,  # add_pit's, keyword-only without a default
        # study_part without a case range and study_merge of a part that does not exist refuse
        # at once (ValueError).
        "parts": [f"{SOURCE_DIR}/no-such-study-part.csv"],
        # compare_backends on a folder without problem files refuses at once (ValueError).
        "inputs": [f"{SOURCE_DIR}/no-such-problem-folder"],
        "out_dir": "/nonexistent/study-out",
        "__stage__": stage,
    }


# Options given by keyword that make a call end before its work (ValueError): the drivers that
# would otherwise compute for long on a scene they accept.
FAST_FAIL = {"mesh_stiffness": {"positions": -1}, "study": {"threads": -1}}


def receiver(qualified, obj, samples):
    """What to call: a bound method of a fresh copy of the stage scene for Scene's methods."""
    if qualified.startswith("Scene.") and not isinstance(
            inspect.getattr_static(epicycle.Scene, qualified.split(".")[1]), staticmethod):
        return getattr(samples["__stage__"].copy(), qualified.split(".")[1])
    return obj


def test_options_come_after_the_star():
    found = public_callables()
    assert {"quasistatic", "quasistatic_positions", "dynamic", "speed_sweep", "study",
            "ContactProblem", "solve_contact", "Scene.add_pin"} <= {q for q, _, _ in found}
    for qualified, obj, sig_name in found:
        positional, keyword = parameters(signature_doc(obj, sig_name), sig_name)
        for pname, default in positional:
            if default is not None:
                assert (qualified, pname) in POSITIONAL_DEFAULTS, (
                    f"{qualified}: option {pname} = {default} is positional (put it after "
                    "py::kw_only())")


def test_an_option_passed_positionally_raises_type_error(samples):
    checked = 0
    for qualified, obj, sig_name in public_callables():
        positional, keyword = parameters(signature_doc(obj, sig_name), sig_name)
        if not keyword:
            continue
        missing = [p for p, _ in positional if p not in samples]
        assert not missing, f"{qualified}: no sample value for {missing} in this test"
        f = receiver(qualified, obj, samples)
        args = [samples[p] for p, _ in positional]
        required = {p: samples[p] for p, default in keyword if default is None}
        # The arguments bind when the options go by keyword (no TypeError): the samples are right.
        try:
            f(*args, **required, **FAST_FAIL.get(qualified, {}))
        except (ValueError, epicycle.ComputationError):
            pass
        # One more positional argument, the first option's default: refused before any work.
        first, default = keyword[0]
        try:
            extra = ast.literal_eval(default) if default is not None else 0
        except ValueError:
            extra = None
        with pytest.raises(TypeError):
            f(*args, extra)
        checked += 1
    assert checked >= 15, checked
