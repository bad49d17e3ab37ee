"""The schedulers' recipes of docs/studies.md "Shards" run on a small study: GNU parallel running
`epicycle study FILE --shard K/N` then `epicycle study merge`, and Dask (a LocalCluster of
processes, and one of threads) running epicycle.study_part then epicycle.study_merge. The
reference is a single run of the program on the same study file: the merged rows, summary (its
computed_seconds aside: the merge computed nothing) and plots equal it byte for byte. A missing or
repeated shard is refused, naming the part files and the cases."""

import json
import os
import subprocess

import pytest

import epicycle
from conftest import EXE, SCENES, run_cli

CACHE = os.environ.get("EPICYCLE_CACHE_DIR", "")

# The shipped pin-tolerance study (pins of every planet, σ = 5 µm, fixed sun) cut to 16 cases of
# 4 positions (a few ms per case), its scene path made absolute for the temporary folder.
with open(os.path.join(SCENES, "studies", "pin_tolerance.toml")) as _f:
    STUDY_TEXT = (_f.read().replace("samples = 200", "samples = 16")
                  .replace("positions = 24", "positions = 4")
                  .replace('"../paper_stage.toml"', '"' + os.path.join(SCENES, "paper_stage.toml") + '"'))
assert "samples = 16" in STUDY_TEXT and "positions = 4" in STUDY_TEXT and SCENES in STUDY_TEXT

FILES = ["study_rows.csv", "study_kgamma_hist.svg", "study_kgamma_cdf.svg"]


def cache_args():
    return ["--cache", CACHE] if CACHE else []


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    """The study file and the folder of its single run (the reference)."""
    d = tmp_path_factory.mktemp("shards")
    path = str(d / "shards.toml")
    with open(path, "w") as f:
        f.write(STUDY_TEXT)
    single = str(d / "single")
    run_cli("study", path, "--out", single, "--threads", 1, "--quiet", *cache_args())
    return path, single


def assert_same_files(merged, single):
    for name in FILES:
        with open(os.path.join(merged, name), "rb") as a, open(os.path.join(single, name), "rb") as b:
            assert a.read() == b.read(), name
    with open(os.path.join(merged, "study_summary.json")) as a:
        ja = json.load(a)
    with open(os.path.join(single, "study_summary.json")) as b:
        jb = json.load(b)
    assert ja.pop("computed_seconds") == 0
    jb.pop("computed_seconds")
    assert ja == jb


def test_gnu_parallel_recipe_equals_the_single_run(study, tmp_path):
    path, single = study
    parts, merged = str(tmp_path / "parts"), str(tmp_path / "merged")
    # The recipe: one shard per job, as many jobs at once as cores (parallel's default).
    subprocess.run(["parallel", "--will-cite", EXE, "study", path,
                    "--shard", "{}/7", "--out", parts, "--threads", "1", "--quiet",
                    *cache_args(), ":::", *map(str, range(7))],
                   check=True, capture_output=True)
    assert len(os.listdir(parts)) == 7
    run_cli("study", "merge", parts, "--out", merged)
    assert_same_files(merged, single)


@pytest.mark.parametrize("processes", [True, False], ids=["processes", "threads"])
def test_dask_recipe_equals_the_single_run(study, tmp_path, processes):
    from dask.distributed import Client, LocalCluster

    path, single = study
    parts, merged = str(tmp_path / "parts"), str(tmp_path / "merged")
    shards = 3
    extra = {"cache_dir": CACHE} if CACHE else {}
    # The recipe: one task per shard, each a case range of the study into its own part file.
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=processes,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        futures = [client.submit(epicycle.study_part, path, shard=(k, shards), out_dir=parts,
                                 threads=1, pure=False, **extra) for k in range(shards)]
        done = client.gather(futures)
    assert [(r.first_case, r.last_case) for r in done] == [(0, 5), (5, 10), (10, 16)]
    assert all(r.failed == 0 and r.rows == r.last_case - r.first_case for r in done)
    m = epicycle.study_merge([r.part_file for r in done], out_dir=merged, study=path)
    assert m.cases == 16 and m.failed == 0 and len(m.parts) == shards
    assert_same_files(merged, single)


def test_a_missing_or_repeated_shard_is_refused_by_name(study, tmp_path):
    path, _ = study
    parts = str(tmp_path / "parts")
    made = [epicycle.study_part(path, shard=(k, 3), out_dir=parts, threads=1,
                                **({"cache_dir": CACHE} if CACHE else {})).part_file
            for k in range(3)]
    with pytest.raises(ValueError, match=r"cases 5:10 are in no part \(between .*study_cases_0_5"
                                         r"\.csv \(cases 0:5\) and .*study_cases_10_16\.csv"):
        epicycle.study_merge([made[0], made[2]], out_dir=str(tmp_path / "m"))
    with pytest.raises(ValueError, match=r"study_cases_5_10\.csv \(cases 5:10\) and .*"
                                         r"study_cases_5_10\.csv \(cases 5:10\) overlap in cases "
                                         r"5:10"):
        epicycle.study_merge(made + [made[1]], out_dir=str(tmp_path / "m"))
    # The program says the same and exits 2.
    p = run_cli("study", "merge", made[0], made[2], "--out", tmp_path / "m", check=False)
    assert p.returncode == 2 and "cases 5:10 are in no part" in p.stderr
    # Keyword-only arguments, and exactly one of cases and shard.
    with pytest.raises(TypeError):
        epicycle.study_part(path, (0, 3), parts)
    with pytest.raises(ValueError, match="give exactly one"):
        epicycle.study_part(path, out_dir=parts)
