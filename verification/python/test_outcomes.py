"""Typed outcomes (docs/dynamic.md, "Outcomes"; docs/studies.md, "Results"): for each status a run
above the contact level can end with, the same request through the program and through Python
ends with that status in the record, the program exits 1 (legal input, a failed computation; 2 is
bad input) and Python raises the ComputationError subclass of the status, the record in
`.result`.

The requests (each fails at once, so the tests are cheap):
- contact-failure: verification/data/bad_inputs/study_failing_case.toml, a 3 mm run-out the scene
  takes but whose position's contact solve fails;
- integrator-failure: one integrator step allowed per output interval cannot reach the first output
  (CV_TOO_MUCH_WORK: a step of 1/211 mesh cycle is far beyond CVODE's first step on this stiff
  system);
- time-limit: 1 ns of wall time is spent before the integrator's first right-hand side;
- geometry: verification/data/outcomes/separated_planet2.toml, planet 2 thinned by three times the
  backlash, separated from both members at the start;
- bad-sampled-value: verification/data/bad_inputs/study_bad_sampled_value.toml, a 3 mm thickness
  error past the scene's rule (below m/2), so the case is not run.
"""

import os

import pytest

import epicycle
from conftest import SOURCE_DIR, read_json, run_cli, scene_path

DATA = os.path.join(SOURCE_DIR, "verification", "data")
PAPER = scene_path("paper_stage.toml")
SEPARATED = os.path.join(DATA, "outcomes", "separated_planet2.toml")
FAILING_CASE = os.path.join(DATA, "bad_inputs", "study_failing_case.toml")
BAD_SAMPLE = os.path.join(DATA, "bad_inputs", "study_bad_sampled_value.toml")

# status, the program's arguments, Python's call, the exception class.
DYNAMIC = [
    ("integrator-failure", [PAPER, "--max-steps", 1], PAPER, {"max_steps": 1},
     epicycle.IntegratorFailure),
    ("time-limit", [PAPER, "--time-limit", "1e-9"], PAPER, {"time_limit_s": 1e-9},
     epicycle.TimeLimitReached),
    ("geometry", [SEPARATED], SEPARATED, {}, epicycle.GeometryFailure),
]
STUDY = [
    ("contact-failure", FAILING_CASE, epicycle.ContactFailure),
    ("bad-sampled-value", BAD_SAMPLE, epicycle.BadSampledValue),
]


@pytest.mark.parametrize("status,args,scene,kwargs,error", DYNAMIC,
                         ids=[c[0] for c in DYNAMIC])
def test_a_dynamic_run_that_stops_has_its_status_exit_1_and_its_class(tmp_path, status, args,
                                                                       scene, kwargs, error):
    p = run_cli("dynamic", *args, "--range", "cycle", "--quiet", "--out", tmp_path, check=False)
    assert p.returncode == 1, p.stderr
    program = read_json(tmp_path / "dynamic_summary.json")
    assert program["status"] == status and program["completed"] is False
    with pytest.raises(error) as e:
        epicycle.dynamic(epicycle.Scene.load(scene), range="cycle", **kwargs)
    assert isinstance(e.value, epicycle.ComputationError)
    assert type(e.value) is error  # the status's own class, not a sibling's
    assert e.value.result.status == e.value.result.record["status"] == status
    assert e.value.result.record["outputs_written"] == program["outputs_written"] == 0


@pytest.mark.parametrize("status,study,error", STUDY, ids=[c[0] for c in STUDY])
def test_a_study_case_that_fails_has_its_status_exit_1_and_its_class(tmp_path, status, study,
                                                                     error):
    p = run_cli("study", study, "--quiet", "--threads", 1, "--out", tmp_path, check=False)
    assert p.returncode == 1, p.stderr
    program = read_json(tmp_path / "study_summary.json")
    assert program["cases_failed"] == 1 and program["cases_failed_by_status"][status] == 1
    with pytest.raises(error) as e:
        epicycle.study(study, threads=1)
    assert type(e.value) is error
    r = e.value.result
    assert list(r.status) == ["completed", status]  # the other case computed
    assert r.record["cases_failed_by_status"] == program["cases_failed_by_status"]


def test_bad_input_is_exit_2_and_value_error():
    # Not an outcome: a value that breaks a rule is refused before anything is computed.
    p = run_cli("dynamic", PAPER, "--time-limit", "0", check=False)
    assert p.returncode == 2 and "--time-limit = 0" in p.stderr
    with pytest.raises(ValueError, match="time_limit_s = 0"):
        epicycle.dynamic(epicycle.Scene.load(PAPER), range="cycle", time_limit_s=0.0)
