"""The quasi-static sweep one position at a time (epicycle.quasistatic_positions; docs/python.md,
"Streaming a sweep"): its records equal epicycle.quasistatic's arrays bit for bit, the process's
peak memory does not grow with the number of positions, and leaving the loop early (break, an
exception in the loop's body) stops the sweep."""

import json
import os
import subprocess
import sys
import time

import numpy as np
import pytest

import epicycle
from conftest import scene_path

SCENE = scene_path("paper_stage_runout.toml")
FIELDS = ["carrier_deg", "converged", "k_gamma", "te_urad", "sun_x_um", "sun_y_um",
          "geometric_iterations", "contact_iterations", "warm_started", "residual",
          "active_contacts", "contacts"]


@pytest.mark.parametrize("threads", [1, 2])
def test_records_equal_the_sweep_bit_for_bit(threads):
    scene = epicycle.Scene.load(SCENE)
    options = dict(range="planet", positions=150, threads=threads)
    whole = epicycle.quasistatic(scene, **options)
    stream = epicycle.quasistatic_positions(scene, **options)
    assert len(stream) == 150 and stream.planets == whole.planets
    records = list(stream)
    assert [r.index for r in records] == list(range(150))
    assert all(r.converged for r in records)
    for name in FIELDS:
        streamed = np.array([getattr(r, name) for r in records])
        # bit for bit: the same doubles (tobytes), not merely close ones
        assert streamed.astype(getattr(whole, name).dtype).tobytes() == \
            getattr(whole, name).tobytes(), name
    for name in ["lsr", "load_sharing_factor"]:
        assert np.array([getattr(r, name) for r in records]).tobytes() == \
            getattr(whole, name).tobytes(), name
    assert [r.status for r in records] == whole.status
    assert [r.message for r in records] == whole.message


def test_friction_records_equal_the_sweep():
    scene = epicycle.Scene.load(SCENE)
    whole = epicycle.quasistatic(scene, positions=12, threads=1, friction="constant")
    records = list(epicycle.quasistatic_positions(scene, positions=12, threads=1,
                                                  friction="constant"))
    for name in ["friction_power_W", "input_power_W", "output_power_W", "efficiency",
                 "force_change"]:
        assert np.array([getattr(r, name) for r in records]).tobytes() == \
            getattr(whole, name).tobytes(), name


CHILD = r"""
import json, resource, sys
import epicycle
count, keep = int(sys.argv[1]), sys.argv[2] == "keep"
scene = epicycle.Scene.load(sys.argv[3])
kept, seen, k_max = [], 0, 0.0
for r in epicycle.quasistatic_positions(scene, range="revolution", positions=count, threads=1):
    seen += 1
    k_max = max(k_max, r.k_gamma)
    if keep:
        kept.append(r)
print(json.dumps({"seen": seen, "maxrss_kB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss}))
"""


def peak_kB(count, keep):
    p = subprocess.run([sys.executable, "-c", CHILD, str(count), "keep" if keep else "stream",
                        SCENE], capture_output=True, text=True, env=os.environ, check=True)
    out = json.loads(p.stdout)
    assert out["seen"] == count
    return out["maxrss_kB"]


def test_peak_memory_does_not_grow_with_the_positions():
    # Both counts above the library's in-flight results (transmission::kSweepInFlight = 4096:
    # its ring holds up to that many, fewer for a shorter sweep), so that the ring is full in both
    # and the difference is what the binding holds per position.
    small, large = 5000, 50000
    t0 = time.monotonic()
    streamed_small, streamed_large = peak_kB(small, False), peak_kB(large, False)
    seconds = time.monotonic() - t0
    # The scale of growth a sweep that kept something per position would show: the records kept
    # in a list (what a binding that gathered them, as epicycle.quasistatic does, would hold).
    kept_large = peak_kB(large, True)
    per_record_kB = (kept_large - streamed_large) / large
    assert per_record_kB > 0.2, per_record_kB  # a record: a dict, two arrays, numbers
    growth = streamed_large - streamed_small
    # Allowed: what a tenth of a record per position would add, (large - small) x per_record /
    # 10 (the allocator's and the interpreter's own noise is a few hundred kB; a tenth of the
    # records, 4500 of them, about 1.5 MB above it).
    allowed = (large - small) * per_record_kB / 10
    print(f"peak RSS {streamed_small} kB for {small} positions, {streamed_large} kB for {large}, "
          f"{kept_large} kB keeping them ({per_record_kB:.2f} kB a record); growth {growth} kB "
          f"(allowed {allowed:.0f} kB); {seconds:.1f} s for the two streamed sweeps")
    assert growth < allowed


def test_leaving_the_loop_stops_the_sweep():
    scene = epicycle.Scene.load(SCENE)
    stream = epicycle.quasistatic_positions(scene, range="revolution", positions=200000)
    t0 = time.monotonic()
    for r in stream:
        if r.index == 10:
            break
    stream.close()  # returns once the workers stopped: well before 200 000 positions
    assert time.monotonic() - t0 < 10.0
    with pytest.raises(StopIteration):
        next(stream)

    class Stop(Exception):
        pass

    with pytest.raises(Stop):
        with epicycle.quasistatic_positions(scene, range="revolution", positions=200000) as s:
            for r in s:
                raise Stop()


def test_bad_input_raises_before_any_work():
    scene = epicycle.Scene.load(SCENE)
    with pytest.raises(ValueError, match="positions"):
        epicycle.quasistatic_positions(scene, positions=-1)
    with pytest.raises(ValueError, match="start_deg"):
        epicycle.quasistatic_positions(scene, start_deg=float("nan"))
    with pytest.raises(TypeError):
        epicycle.quasistatic_positions(scene, "planet")
