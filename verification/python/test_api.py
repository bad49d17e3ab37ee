"""The package's public names each carry a docstring, and every driver's states its results'
units (what help(epicycle.quasistatic) shows; docs/python.md)."""

import re

import epicycle

DRIVERS = ["contacts", "dynamic", "geometry", "mesh_stiffness", "modes", "quasistatic",
           "solve_contact", "speed_sweep", "study"]


def test_every_public_name_has_a_docstring():
    for name in epicycle.__all__:
        assert getattr(epicycle, name).__doc__, name
    methods = [m for m in dir(epicycle.Scene) if not m.startswith("_")]
    assert {"load", "parse", "set", "with_values", "add_pin", "add_runout", "add_thickness",
            "add_pit", "set_pitch", "set_relief"} <= set(methods)
    for m in methods:
        assert getattr(epicycle.Scene, m).__doc__, m


def test_every_driver_documents_its_units():
    for name in DRIVERS:
        doc = getattr(epicycle, name).__doc__
        assert "Returns Result" in doc, name
        units = re.findall(r"\[(?:deg|µm|µrad|N|N/m|N·m|mm|Hz|rpm|s|-|m|J|W|N/\(mm·µm\))\]", doc)
        assert len(units) >= 3, (name, units)
