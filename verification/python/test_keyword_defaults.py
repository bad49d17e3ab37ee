"""Python's keyword defaults are the library's request defaults (docs/python.md, "Drivers"): the
bindings read them from a default-made request (QuasiStaticRequest, StiffnessRequest,
DynamicRequest, ...), the requests the program's options start from. So each default in a
driver's signature equals the setting the program's record reports for a run given no such option:
the reference is the program's run, not the binding, and the two can only part if a front end
stops reading the request's defaults; a default changed in the request changes both."""

import ast

import epicycle
from conftest import parse_signature, read_json, run_cli, scene_path, signature_doc


def defaults(function):
    """{keyword: default value} of a driver's pybind11 signature (the text help() shows)."""
    name = function.__name__
    params, _ = parse_signature(signature_doc(function, name), name)
    out = {}
    for p, _, d, _ in params:
        if d is not None and d != "None":
            out[p] = ast.literal_eval(d)
    return out


def test_quasistatic_keywords_default_to_the_programs_settings(tmp_path):
    run_cli("quasistatic", scene_path("paper_stage.toml"), "--positions", 2, "--quiet",
            "--out", tmp_path)
    j = read_json(tmp_path / "quasistatic_summary.json")
    for driver in (epicycle.quasistatic, epicycle.quasistatic_positions):
        d = defaults(driver)
        for key in ("backend", "local_terms", "warm_start", "threads"):
            assert d[key] == j[key], (driver.__name__, key)
        assert "friction" not in j and d["friction"] == "off"  # friction off: no key


def test_mesh_stiffness_keywords_default_to_the_programs_settings(tmp_path):
    run_cli("stiffness", scene_path("iso_pair_20_40.toml"), "--out", tmp_path)
    j = read_json(tmp_path / "stiffness_gear1-gear2.json")
    d = defaults(epicycle.mesh_stiffness)
    for key in ("positions", "local_terms"):
        assert d[key] == j[key], key


def test_dynamic_keywords_default_to_the_programs_settings(tmp_path):
    run_cli("dynamic", scene_path("paper_stage.toml"), "--range", "cycle", "--quiet",
            "--out", tmp_path)
    j = read_json(tmp_path / "dynamic_summary.json")
    for driver in (epicycle.dynamic, epicycle.speed_sweep, epicycle.periodic_branch):
        d = defaults(driver)
        for key in ("rtol", "backend"):
            assert d[key] == j[key], (driver.__name__, key)
    for driver in (epicycle.dynamic, epicycle.speed_sweep):
        assert defaults(driver)["integrator"] == j["integrator"], driver.__name__
