"""The type stub of the compiled module (epicycle/_epicycle.pyi, generated at build time by
tools/python_stubs.py and installed with py.typed; docs/python.md, "Docstrings and type stubs") is
the module's: it is beside the module, as the generator gives it from the module now; mypy's
stubtest finds every name of the module in it and nothing else; and mypy, reading the stub as an
editor does, accepts a call with options by keyword and refuses one with an option passed
positionally."""

import os
import subprocess
import sys

import epicycle
from conftest import SOURCE_DIR

PACKAGE = os.path.dirname(epicycle.__file__)
STUB = os.path.join(PACKAGE, "_epicycle.pyi")


def test_the_stub_is_the_modules():
    from python_stubs import generate  # tools/, on the path through conftest
    assert os.path.exists(os.path.join(PACKAGE, "py.typed"))
    with open(STUB) as f:
        stub = f.read()
    assert generate() == stub, "the stub is older than the module: build epicycle_python"
    assert "def quasistatic(scene: Scene, *, range: str = 'cycle'" in stub
    assert "compliance_m_per_N: NDArray[numpy.float64]" in stub
    assert "def speed_grid(from_rpm: float, to_rpm: float, count: int) -> " \
           "NDArray[numpy.float64]:" in stub


def mypy(*args):
    return subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True,
                          env=os.environ, cwd=os.path.dirname(STUB))


def test_stubtest_finds_the_module_and_the_stub_equal():
    allowlist = os.path.join(SOURCE_DIR, "verification", "python", "stubtest_allowlist.txt")
    p = mypy("mypy.stubtest", "--concise", "--allowlist", allowlist, "epicycle._epicycle")
    assert p.returncode == 0, p.stdout + p.stderr


def test_mypy_refuses_an_option_passed_positionally(tmp_path):
    good = tmp_path / "good.py"
    good.write_text("import epicycle\n"
                    "s = epicycle.Scene.load('x.toml')\n"
                    "r = epicycle.quasistatic(s, range='planet', positions=12)\n"
                    "d = epicycle.dynamic(s, 1500.0, outputs_per_cycle=8, rating=True)\n"
                    "for p in epicycle.quasistatic_positions(s, positions=3):\n"
                    "    print(p.k_gamma)\n")
    bad = tmp_path / "bad.py"
    bad.write_text("import epicycle\n"
                   "s = epicycle.Scene.load('x.toml')\n"
                   "r = epicycle.quasistatic(s, 'planet')\n")
    common = ("mypy", "--no-incremental", "--cache-dir", str(tmp_path / "cache"))
    p = mypy(*common, str(good))
    assert p.returncode == 0, p.stdout + p.stderr
    p = mypy(*common, str(bad))
    assert p.returncode == 1 and "Too many positional arguments" in p.stdout, p.stdout + p.stderr
