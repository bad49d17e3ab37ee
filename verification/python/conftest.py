"""Shared by the Python bindings' tests (run by CTest: "python: ..."; docs/python.md).

The references are the `epicycle` program's own result files, run here on the same scene with the
same settings: the bindings and the program share the libraries, not the code that prints.
CTest sets EPICYCLE_EXE (the program), EPICYCLE_SOURCE_DIR and EPICYCLE_CACHE_DIR (the suite's
influence-table cache), and PYTHONPATH to the build's package.
"""

import csv
import json
import os
import subprocess
import sys

import pytest

SOURCE_DIR = os.environ.get(
    "EPICYCLE_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
)
SCENES = os.path.join(SOURCE_DIR, "scenes")
EXE = os.environ.get("EPICYCLE_EXE", os.path.join(SOURCE_DIR, "build", "app", "epicycle"))


# The signature parser of the stub generator (tools/python_stubs.py).
sys.path.insert(0, os.path.join(SOURCE_DIR, "tools"))
from python_stubs import parse_signature  # noqa: E402


def public_callables():
    """(qualified name, callable, name in its signature line) of every public function of the
    module epicycle._epicycle, every public method of its classes and their constructors."""
    import inspect

    import epicycle
    out = []
    for name in epicycle.__all__:
        obj = getattr(epicycle, name)
        if inspect.isclass(obj):
            if obj.__module__ != "epicycle._epicycle":
                continue  # Result, ComputationError: the package's Python classes
            if (obj.__dict__.get("__init__").__doc__ or "").startswith("__init__("):
                out.append((name, obj, "__init__"))
            for m, member in obj.__dict__.items():
                if m.startswith("_") or isinstance(member, property):
                    continue
                out.append((f"{name}.{m}", getattr(obj, m), m))
        elif callable(obj):
            out.append((name, obj, name))
    return out


def signature_doc(obj, sig_name):
    """The docstring holding a callable's signature line (a class's: its __init__'s)."""
    return (obj.__init__ if sig_name == "__init__" else obj).__doc__


def scene_path(name):
    return os.path.join(SCENES, name)


def run_cli(*args, check=True):
    """Runs the program; returns the CompletedProcess (text)."""
    p = subprocess.run([EXE, *map(str, args)], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"epicycle {' '.join(map(str, args))}: exit {p.returncode}\n{p.stderr}")
    return p


def read_csv(path):
    """Rows of a result CSV as dicts of strings (the provenance comment line skipped)."""
    with open(path, newline="") as f:
        lines = [line for line in f if not line.startswith("#")]
    return list(csv.DictReader(lines))


def read_json(path):
    with open(path) as f:
        return json.load(f)


def num(v):
    """A number as the result files print it ({:.9g}; empty where not finite)."""
    return "" if v != v or v in (float("inf"), float("-inf")) else "%.9g" % v


def deg(v):
    """A carrier angle as the files print it ({:.6f})."""
    return "%.6f" % v


@pytest.fixture(scope="session")
def epicycle_module():
    import epicycle

    return epicycle


# What two runs of the same request may differ in: wall times.
TIMES = {"setup_seconds", "wall_seconds", "evaluation_seconds", "sweep_seconds", "table_seconds"}


def without_times(record):
    return {k: v for k, v in record.items() if k not in TIMES}


def quasistatic_records(scene, tmp_path, positions=2):
    """Python's quasi-static record of scene file `scene` and the program's summary JSON (its
    provenance dropped), the same request: `positions` positions, quiet."""
    import epicycle

    run_cli("quasistatic", scene, "--positions", str(positions), "--quiet", "--out", tmp_path)
    program = read_json(tmp_path / "quasistatic_summary.json")
    del program["provenance"]
    python = epicycle.quasistatic(epicycle.Scene.load(scene), positions=positions).record
    return python, program
