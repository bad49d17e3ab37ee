"""Ctrl-C stops a long computation cleanly: a sweep of 100000 positions in a child interpreter,
SIGINT once it has started, KeyboardInterrupt raised in the child within seconds."""

import os
import signal
import subprocess
import sys
import time

from conftest import scene_path

CHILD = r"""
import sys, epicycle
scene = epicycle.Scene.load(sys.argv[1])
def progress(done, total):
    if done == 1:
        print("started", flush=True)
try:
    epicycle.quasistatic(scene, positions=100000, threads=1, progress=progress)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", flush=True)
"""


def interrupt(child_code):
    """Runs `child_code` in a child interpreter, sends SIGINT once it says "started"; the seconds
    until it ended, having printed "interrupted" and exited 0."""
    child = subprocess.Popen([sys.executable, "-c", child_code, scene_path("paper_stage.toml")],
                             stdout=subprocess.PIPE, text=True, env=os.environ)
    assert child.stdout.readline().strip() == "started"
    t0 = time.monotonic()
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=60)
    assert out.strip() == "interrupted"
    assert child.returncode == 0
    return time.monotonic() - t0


def test_sigint_stops_a_long_sweep():
    assert interrupt(CHILD) < 10  # 100000 positions take minutes


STREAM_CHILD = r"""
import sys, epicycle
scene = epicycle.Scene.load(sys.argv[1])
try:
    for r in epicycle.quasistatic_positions(scene, positions=100000, threads=1):
        if r.index == 0:
            print("started", flush=True)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", flush=True)
"""


def test_sigint_stops_a_streamed_sweep():
    """The same through quasistatic_positions: the signal arrives while the loop waits for a
    position (GIL released) or runs its body; either way KeyboardInterrupt, the sweep stopped."""
    assert interrupt(STREAM_CHILD) < 10  # 100000 positions take well over 10 s
