"""Every CSV the program writes is CSV as RFC 4180 has it: each command that writes one runs here on
a small case, and every *.csv it wrote is read by Python's csv module in strict mode; every row
must have its header's number of fields. A text cell holding a comma (the spectrum lines' kind
"planet tooth, both flanks", a failed solve's message) is quoted, so that it stays one field
(README, "provenance": the first '#' line of each file is a comment, not a row).

Commands without a CSV (geometry, contacts, modes, contact solve) write JSON or SVG only."""

import csv
import os

import pytest

from conftest import SOURCE_DIR, run_cli, scene_path

CONTACT = os.path.join(SOURCE_DIR, "verification", "data", "contact")


def rated_scene(tmp_path):
    """The paper stage with material strengths (for --rating) and planet 1 pushed ahead by a
    100 um pin error, so that planets 2 and 3 carry no load at carrier 0 deg."""
    text = open(scene_path("paper_stage.toml")).read()
    text = text.replace("poisson_ratio = 0.3\n",
                        "poisson_ratio = 0.3\nbending_limit_MPa = 430\ncontact_limit_MPa = 1500\n", 1)
    text += '\n[[errors.pin]]\ngear = "planet1"\ntangential_um = 100.0\n'
    path = tmp_path / "rated.toml"
    path.write_text(text)
    return path


# (name, arguments before --out/--csv, the files expected, exit statuses allowed). Small runs: a
# few positions, a hundredth of a second of motion, two speeds, two study cases.
RUNS = [
    ("stiffness pair", ["stiffness", scene_path("iso_pair_20_40.toml"), "--positions", 4,
                        "--stresses"], None, (0,)),
    ("stiffness stage mesh", ["stiffness", scene_path("paper_stage.toml"), "--mesh", "sun-planet1",
                              "--positions", 3], None, (0,)),
    ("quasistatic", ["quasistatic", scene_path("paper_stage_runout.toml"), "--range", "cycle",
                     "--positions", 3, "--stresses", "--friction", "scene", "--quiet"],
     ["quasistatic_positions.csv", "quasistatic_pairs.csv"], (0,)),
    ("quasistatic --rating", ["quasistatic", "RATED", "--angles-deg", 0, "--rating", "--quiet"],
     ["quasistatic_positions.csv", "quasistatic_pairs.csv"], (0,)),
    ("dynamic --spectrum", ["dynamic", scene_path("paper_stage.toml"), "--time", 0.01, "--spectrum",
                            "--spectrum-skip-cycles", 0, "--quiet"],
     ["dynamic_steps.csv", "dynamic_pairs.csv", "dynamic_bearings.csv", "dynamic_vibration.csv",
      "dynamic_spectrum.csv", "dynamic_spectrum_lines.csv"], (0,)),
    ("speed sweep", ["dynamic", scene_path("paper_stage.toml"), "--speed-sweep", "4000:5000:2",
                     "--window-cycles", 1, "--threads", 1, "--quiet"], ["speed_sweep.csv"], (0,)),
    ("study", ["study", scene_path("studies/pin_tolerance.toml"), "--max-cases", 2, "--threads", 1,
               "--quiet"], None, (0,)),
    # Back ends that fail on the stiff problem write their messages (exit 1: some failed).
    ("contact compare", ["contact", "compare", os.path.join(CONTACT, "cf_one_contact_open.json"),
                         os.path.join(CONTACT, "stiff_cond1e10_s1.json"), "--tol", 1e-30,
                         "--repeat", 1], None, (0, 1)),
]


def strict_rows(path):
    """The rows of a result file (its '#' comment lines left out), read strictly."""
    with open(path, newline="") as f:
        text = f.read()
    assert text.endswith("\n"), f"{path}: the last line has no end"
    lines = [line for line in text.splitlines(keepends=True) if not line.startswith("#")]
    return list(csv.reader(lines, strict=True))


@pytest.mark.parametrize("name,args,expected,statuses", RUNS, ids=[r[0] for r in RUNS])
def test_every_csv_has_its_header_fields_in_every_row(tmp_path, name, args, expected, statuses):
    out = tmp_path / "out"
    args = [rated_scene(tmp_path) if a == "RATED" else a for a in args]
    if args[0] == "contact":
        args += ["--csv", out / "compare.csv"]
    else:
        args += ["--out", out]
    p = run_cli(*args, check=False)
    assert p.returncode in statuses, f"{name}: exit {p.returncode}\n{p.stderr}"
    files = sorted(f for f in os.listdir(out) if f.endswith(".csv"))
    assert files, f"{name}: no CSV written"
    for f in expected or []:
        assert f in files, f"{name}: {f} not written"
    for f in files:
        rows = strict_rows(out / f)
        assert len(rows) >= 2, f"{f}: no row under the header"
        header = rows[0]
        for k, row in enumerate(rows[1:], start=2):
            assert len(row) == len(header), (
                f"{f}: row {k} has {len(row)} fields, its header {len(header)}: {row}")


def test_a_text_cell_with_a_comma_stays_one_field(tmp_path):
    """A back end's message, commas and all, read back whole from the comparison's CSV."""
    out = tmp_path / "compare.csv"
    p = run_cli("contact", "compare", os.path.join(CONTACT, "stiff_cond1e10_s1.json"), "--tol", "1e-30",
                "--repeat", 1, "--csv", out, check=False)
    assert p.returncode == 1, p.stderr
    rows = strict_rows(out)
    message = rows[0].index("message")
    with_commas = [row[message] for row in rows[1:] if "," in row[message]]
    assert with_commas, "no message with a comma to read back"
    for text in with_commas:
        assert text.startswith(("iteration-limit: ", "numerical-failure: ", "converged")), text
        assert "residual" in text
