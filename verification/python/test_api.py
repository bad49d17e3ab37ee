"""The package's public names each carry a numpydoc docstring (docs/python.md, "Docstrings"):
every callable that takes parameters has a Parameters section naming each of them, every one
that returns something a Returns section, and every driver states its results' units (what
help(epicycle.quasistatic) shows). The callables are listed from the module."""

import inspect
import re

import epicycle
from conftest import parse_signature, public_callables, signature_doc

DRIVERS = ["contacts", "dynamic", "geometry", "mesh_stiffness", "modes", "quasistatic",
           "quasistatic_positions", "solve_contact", "speed_sweep", "study"]


def section(doc, title):
    """The text of a numpydoc section (its entries), or None."""
    m = re.search(rf"^{title}\n-{{{len(title)}}}\n(.*?)(?:\n\n[A-Z][a-z]+\n-+\n|\Z)", doc,
                  re.S | re.M)
    return m.group(1) if m else None


def documented_names(parameters):
    """The names a Parameters section documents: `name : type` and `a, b : type` lines, and
    `*args`, `**keys`."""
    names = set()
    for line in parameters.splitlines():
        if line and not line.startswith(" "):
            head = line.split(" : ")[0]
            names |= {n.strip() for n in head.split(",")}
    return names


def test_every_public_name_has_a_docstring():
    for name in epicycle.__all__:
        assert getattr(epicycle, name).__doc__, name
    methods = [m for m in dir(epicycle.Scene) if not m.startswith("_")]
    assert {"load", "parse", "set", "with_values", "add_pin", "add_runout", "add_thickness",
            "add_pit", "set_pitch", "set_relief"} <= set(methods)
    for m in methods:
        assert getattr(epicycle.Scene, m).__doc__, m


def test_every_callable_documents_its_parameters_and_returns():
    checked = 0
    for qualified, obj, sig_name in public_callables():
        params, ret = parse_signature(signature_doc(obj, sig_name), sig_name)
        names = [p for p, _, _, _ in params if p != "self"]
        # A constructor's parameters are documented in its class's docstring (numpydoc).
        doc = obj.__doc__ if sig_name == "__init__" else signature_doc(obj, sig_name)
        if names:
            parameters = section(doc, "Parameters")
            assert parameters is not None, f"{qualified}: no Parameters section"
            documented = documented_names(parameters)
            for n in names:
                assert n in documented or n.lstrip("*") in {d.lstrip("*") for d in documented}, \
                    f"{qualified}: parameter {n} not in its Parameters section"
        if ret not in ("None",) and sig_name != "__init__":
            assert section(doc, "Returns") is not None, f"{qualified}: no Returns section"
        checked += 1
    # ...and the package's Python classes
    for cls in (epicycle.Result, epicycle.ComputationError):
        assert section(cls.__doc__.replace("\n    ", "\n"), "Parameters"), cls
    assert checked >= 30, checked  # 16 functions, a constructor, Scene's and the others' methods


def test_every_driver_documents_its_units_and_raises():
    for name in DRIVERS:
        doc = getattr(epicycle, name).__doc__
        returns = section(doc, "Returns")
        assert returns is not None and returns.split("\n")[0] in ("Result", "QuasiStaticPositions")
        units = re.findall(r"\[(?:deg|µm|µrad|N|N/m|N·m|mm|Hz|rpm|s|-|m|J|W|N/\(mm·µm\))\]", doc)
        assert len(units) >= 3, (name, units)
        raises = section(doc, "Raises")
        assert raises is not None and "ValueError" in raises, name
