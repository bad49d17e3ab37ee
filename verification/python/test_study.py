"""A tolerance study through Python gives the rows the program writes (`epicycle study
--max-cases 4`: the first four cases of scenes/studies/pin_tolerance.toml), byte for byte."""

import os

import epicycle
from conftest import SCENES, SOURCE_DIR, read_json, run_cli

STUDY = os.path.join(SCENES, "studies", "pin_tolerance.toml")


def test_study_rows_equal_the_program_rows(tmp_path):
    out = tmp_path / "cli"
    run_cli("study", STUDY, "--max-cases", 4, "--threads", 2, "--out", out)
    with open(out / "study_rows.csv") as f:
        lines = [line for line in f if not line.startswith("#")]
    r = epicycle.study(STUDY, max_cases=4, threads=2)
    assert lines[0] == r.header + "\n"
    # the program appends rows as cases complete (threads): compared in case order
    rows = sorted(lines[1:], key=lambda line: int(line.split(",")[0]))
    assert rows == list(r.rows_csv) and len(r.rows_csv) == 4
    assert list(r.case_id) == [0, 1, 2, 3] and r.ok.all()
    assert r.values.shape == (4, len(r.columns))
    # the row's numbers are the arrays' (the rows print them exactly)
    k_gamma_column = r.header.split(",").index("K_gamma")
    for k, line in enumerate(r.rows_csv):
        assert float(line.split(",")[k_gamma_column]) == r.k_gamma[k]
    j = read_json(out / "study_summary.json")
    assert j["K_gamma"]["mean"] == r.summary.k_gamma.mean
    assert j["K_gamma"]["max"] == r.summary.k_gamma.max
    assert j["cases_in_file"] == r.summary.cases == 4


def test_study_from_text_resolves_the_scene_beside_its_path():
    with open(STUDY) as f:
        text = f.read()
    r = epicycle.study(STUDY, text=text.replace("samples = 200", "samples = 2"), threads=1)
    assert r.cases == 2 and len(r.rows_csv) == 2


def test_study_exceedance_counts_the_cases_above_each_limit():
    # docs/studies.md "Results": P(K_gamma > x) = k/n with k counted here from the returned
    # K_gamma of every case, and the Clopper-Pearson bounds at their closed forms where k = 0 or
    # k = n (1 - 0.025^(1/n), 0.025^(1/n)), else bracketing k/n.
    with open(STUDY) as f:
        text = f.read()
    limits = [1.0, 1.3, 3.0]
    text = text.replace("samples = 200", "samples = 6").replace(
        "sun = \"fixed\"", "sun = \"fixed\"\nk_gamma_limit = [1.0, 1.3, 3.0]")
    r = epicycle.study(STUDY, text=text, threads=2)
    assert r.ok.all() and len(r.summary.k_gamma_exceedance) == 3
    n = len(r.k_gamma)
    for x, e in zip(limits, r.summary.k_gamma_exceedance):
        k = int((r.k_gamma > x).sum())
        assert e.k_gamma_limit == x and e.cases == n and e.above == k
        assert e.probability == k / n
        if k == 0:
            assert e.lower == 0 and abs(e.upper - (1 - 0.025 ** (1 / n))) < 1e-12
        elif k == n:
            assert e.upper == 1 and abs(e.lower - 0.025 ** (1 / n)) < 1e-12
        else:
            assert e.lower < k / n < e.upper
    assert r.summary.k_gamma_exceedance[0].above == n  # K_gamma >= 1 always
    assert r.summary.k_gamma_exceedance[2].above == 0  # K_gamma <= n = 3


def test_study_case_status_names_how_each_case_ended(tmp_path):
    # verification/data/bad_inputs/study_bad_sampled_value.toml: the second grid point is a tooth
    # thickness error of 3 mm, past the scene's rule (below m/2), so that case is not run: its
    # status is bad-sampled-value, in Python's rows as in the program's rows file and summary JSON.
    study = os.path.join(SOURCE_DIR, "verification", "data", "bad_inputs",
                         "study_bad_sampled_value.toml")
    r = epicycle.study(study, threads=1, raise_on_failure=False)
    assert list(r.status) == ["completed", "bad-sampled-value"]
    assert list(r.ok) == [True, False]
    status_column = r.header.split(",").index("status")
    assert r.rows_csv[1].split(",")[status_column] == "bad-sampled-value"
    assert "planet.thickness_error_um = 3000" in r.message[1]
    assert r.record["cases_failed"] == 1
    assert r.record["cases_failed_by_status"] == {
        "contact-failure": 0, "geometry": 0, "bad-sampled-value": 1}
    assert run_cli("study", study, "--quiet", "--threads", 1, "--out", tmp_path,
                   check=False).returncode == 1
    program = read_json(tmp_path / "study_summary.json")
    assert program["cases_failed_by_status"] == r.record["cases_failed_by_status"]
