"""Bad calls of every driver and of the contact core's solve_contact, as the program's bad options (verification/CMakeLists.txt, "bad
option: ..."): for every numeric argument, values outside its rule (negative, zero where it is not
allowed, nan, ±inf, huge, tiny, random ones past either bound) raise ValueError naming the
argument, its value and the rule (the library's: transmission/ and dynamics/run_arguments.hpp,
the same words as the program's option), and a value of the wrong type raises TypeError naming the
argument; never a signal, never a result (nan or not), and before any work: the influence tables
are asked for in memory (cache_dir=""), which would take several seconds to build, so a check made
after them shows as a slow call.

The calls run in a child interpreter, each announced before it is made: a call that kills the
child (a signal) is a failure naming that call, and the remaining calls run in a new child. The
random values come from a seed printed with every failure (EPICYCLE_BAD_CALL_SEED repeats a run).
"""

import json
import math
import os
import random
import subprocess
import sys
import time

from conftest import SOURCE_DIR, scene_path

# Longest a refused call may take [s]: the in-memory influence tables of the paper's stage take
# about 10 s on the 2-core development machine, the scene's geometry a few milliseconds.
BEFORE_WORK_S = 3.0


class Real:
    """A float argument legal in [lo, hi] ((lo, hi] with lo_open); `default`: a value outside
    that the driver documents as 'use the default' (0), hence legal."""

    def __init__(self, lo, hi, lo_open=False, default=None):
        self.lo, self.hi, self.lo_open, self.default = lo, hi, lo_open, default

    def bad(self, rng):
        v = [math.nan, math.inf, -math.inf, 1e300, -1e300,
             self.hi * (1 + rng.uniform(1e-9, 10)) if self.hi > 0 else self.hi + 1,
             self.hi + 10 ** rng.uniform(0, 300)]
        if self.lo >= 0:
            v += [-1.0, -(10 ** rng.uniform(-300, 300))]
        if self.lo > 0 or self.lo_open:
            v += [0.0, self.lo * rng.uniform(0, 0.999) if self.lo > 0 else 0.0]
        if self.lo > 0:
            v += [1e-300, self.lo / 10]
        v.append(self.lo - 10 ** rng.uniform(0, 300))
        return [x for x in v if x != self.default and not self.legal(x)]

    def legal(self, x):
        if not math.isfinite(x):
            return False
        return (x > self.lo if self.lo_open else x >= self.lo) and x <= self.hi

    @staticmethod
    def wrong_types():
        return ["1", [1.0], {}]


INT_MAX = 2 ** 31 - 1


class Int(Real):
    """A count legal in [lo, hi]; `default` as Real's; `negative_default`: every value < 0 is
    documented as 'all' (study's max_cases)."""

    def __init__(self, lo, hi, default=None, negative_default=False, long=False):
        super().__init__(lo, hi, False, default)
        self.negative_default, self.long = negative_default, long

    def bad(self, rng):
        hi = int(self.hi)
        v = [hi + 1, hi + rng.randint(2, 10 ** 6), rng.randint(hi + 1, INT_MAX)]
        if not self.negative_default:
            v += [int(self.lo) - 1, int(self.lo) - rng.randint(1, 10 ** 9), -INT_MAX]
        return [x for x in v if x != self.default and not self.legal(x)]

    def legal(self, x):
        return self.lo <= x <= self.hi or (self.negative_default and x < 0)

    def wrong_types(self):
        # nan, inf and 2.5 are floats, not a count; 2 ** 40 and 2 ** 70 do not fit the C++
        # integer the argument is (the counts are int, max_cases long).
        return [math.nan, math.inf, 2.5, "3", 2 ** 70] + ([] if self.long else [2 ** 40])


class Each:
    """A list argument whose items follow `item`; its length in [1, most]."""

    def __init__(self, item, most):
        self.item, self.most = item, most

    def bad(self, rng):
        return [[x] for x in self.item.bad(rng)] + [[]]

    @staticmethod
    def wrong_types():
        return ["1", 1.0]


ANGLE = Real(-3600, 3600)
SPEED = Real(1, 1e5)
THREADS = Int(0, 4096)
INTEGRATION = {"rtol": Real(1e-12, 0.1), "rate_scale": Real(0, 1e12),
               "contact_tol": Real(1e-14, 1e-2), "max_order": Int(1, 5)}

STAGE = scene_path("paper_stage.toml")
STUDY = scene_path(os.path.join("studies", "pin_tolerance.toml"))

# driver: (its fixed arguments, {argument: rule}). `scene` is the paper's stage where a driver
# takes one.
DRIVERS = {
    "geometry": ({}, {"points_per_segment": Int(1, 1000)}),
    "contacts": ({}, {"carrier_deg": ANGLE, "gap_window_um": Real(1, 1057.5)}),
    "mesh_stiffness": ({"mesh": "sun-planet1", "cache_dir": ""},
                       {"positions": Int(2, 1e5), "threads": THREADS}),
    "quasistatic": ({"cache_dir": ""},
                    {"positions": Int(1, 1e6, default=0), "start_deg": ANGLE,
                     "angles_deg": Each(ANGLE, 10 ** 6), "threads": THREADS}),
    "quasistatic_positions": ({"cache_dir": ""},
                              {"positions": Int(1, 1e6, default=0), "start_deg": ANGLE,
                               "angles_deg": Each(ANGLE, 10 ** 6), "threads": THREADS}),
    "dynamic": ({"cache_dir": ""},
                dict({"sun_speed_rpm": SPEED, "time_s": Real(1e-6, 3600, default=0.0),
                      "outputs_per_cycle": Int(1, 1e5), "start_deg": ANGLE}, **INTEGRATION)),
    "speed_sweep": ({"sun_speeds_rpm": [1000.0], "cache_dir": ""},
                    dict({"sun_speeds_rpm": Each(SPEED, 10 ** 5),
                          "window_cycles": Real(0, 1e5, lo_open=True, default=0.0),
                          "outputs_per_cycle": Int(1, 1e5), "start_deg": ANGLE,
                          "harmonics": Int(1, 100, default=0), "threads": THREADS},
                         **INTEGRATION)),
    "speed_grid": ({"from_rpm": 1000.0, "to_rpm": 2000.0, "count": 3},
                   {"from_rpm": SPEED, "to_rpm": SPEED, "count": Int(1, 1e5)}),
    "study": ({"path": STUDY, "cache_dir": ""},
              {"threads": THREADS, "max_cases": Int(0, 1e9, negative_default=True, long=True)}),
    # The contact core: the first argument a problem of the collection, not the scene.
    "solve_contact": ({}, {"tolerance": Real(0, 1, lo_open=True), "max_iterations": Int(1, 1e6),
                           "time_limit_s": Real(0, 86400, lo_open=True)}),
}
NO_SCENE = {"speed_grid", "study"}
PROBLEM = os.path.join(SOURCE_DIR, "verification", "data", "contact", "cf_two_symmetric.json")

# The child: reads the calls (JSON lines), announces and makes each, reports what happened.
CHILD = r"""
import json, math, sys, time
import epicycle
scene = epicycle.Scene.load(sys.argv[1])
problem = epicycle.read_contact_problem(sys.argv[2]).problem
def decode(v):
    if isinstance(v, dict) and "float" in v:
        return float(v["float"])
    if isinstance(v, list):
        return [decode(x) for x in v]
    return v
for line in sys.stdin:
    call = json.loads(line)
    print(json.dumps({"start": call["id"]}), flush=True)
    f = getattr(epicycle, call["driver"])
    kwargs = {k: decode(v) for k, v in call["kwargs"].items()}
    t0 = time.monotonic()
    try:
        first = problem if call["driver"] == "solve_contact" else scene
        r = f(**kwargs) if call["no_scene"] else f(first, **kwargs)
        out = {"kind": "returned", "message": repr(r)[:300]}
    except Exception as e:
        out = {"kind": type(e).__name__, "message": str(e)}
    out["id"] = call["id"]
    out["seconds"] = time.monotonic() - t0
    print(json.dumps(out), flush=True)
"""


def encode(v):
    """JSON for a value, nan and inf included (as {"float": "nan"})."""
    if isinstance(v, float) and not math.isfinite(v):
        return {"float": repr(v)}
    if isinstance(v, list):
        return [encode(x) for x in v]
    return v


def bad_calls(rng):
    """Every (driver, argument, value, expected exception) of this run."""
    calls = []
    for driver, (fixed, rules) in DRIVERS.items():
        for arg, rule in rules.items():
            for value in rule.bad(rng):
                calls.append((driver, fixed, arg, value, "ValueError"))
            for value in rule.wrong_types():
                calls.append((driver, fixed, arg, value, "TypeError"))
            if isinstance(rule, Each):  # one past the most items, each legal
                calls.append((driver, fixed, arg, [1000.0] * (rule.most + 1), "ValueError"))
    return calls


def run_children(calls):
    """Runs the calls in child interpreters; {id: outcome}, a crashed call as kind "signal"."""
    env = dict(os.environ)
    outcomes, todo = {}, list(range(len(calls)))
    while todo:
        lines = []
        for i in todo:
            driver, fixed, arg, value, _ = calls[i]
            kwargs = dict(fixed)
            kwargs[arg] = value
            lines.append(json.dumps({"id": i, "driver": driver, "no_scene": driver in NO_SCENE,
                                     "kwargs": {k: encode(v) for k, v in kwargs.items()}}))
        p = subprocess.run([sys.executable, "-c", CHILD, STAGE, PROBLEM], input="\n".join(lines) + "\n",
                           capture_output=True, text=True, env=env, cwd=SOURCE_DIR)
        started = None
        for line in p.stdout.splitlines():
            msg = json.loads(line)
            if "start" in msg:
                started = msg["start"]
            else:
                outcomes[msg["id"]] = msg
                started = None
        if p.returncode == 0:
            break
        if started is None:  # died outside a call (the import, the scene)
            raise AssertionError(f"the child interpreter failed: {p.returncode}\n{p.stderr}")
        outcomes[started] = {"kind": "signal", "message": f"exit status {p.returncode}: "
                             f"{p.stderr[-2000:]}", "seconds": math.nan}
        todo = [i for i in todo if i not in outcomes]
    return outcomes


def shown(value):
    """How the library's message shows a value (C++'s shortest round trip, Python's repr)."""
    if isinstance(value, float) and math.isnan(value):
        return "nan"
    if isinstance(value, float) and math.isinf(value):
        return "inf" if value > 0 else "-inf"
    return None  # finite values: their digits differ between C++ and Python; the name suffices


def test_every_bad_argument_of_every_driver_is_refused_by_name_before_any_work():
    seed = int(os.environ.get("EPICYCLE_BAD_CALL_SEED", time.time_ns() % 2 ** 32))
    calls = bad_calls(random.Random(seed))
    outcomes = run_children(calls)
    failures = []
    for i, (driver, _, arg, value, expected) in enumerate(calls):
        o = outcomes.get(i, {"kind": "missing", "message": ""})
        what = f"{driver}({arg}={value!r:.80})"
        if o["kind"] != expected:
            failures.append(f"{what}: {o['kind']} {o.get('message', '')!r}, expected {expected}")
            continue
        message = o["message"]
        if arg not in message:
            failures.append(f"{what}: {expected} does not name {arg}: {message!r}")
        if expected == "ValueError":
            if "must" not in message:
                failures.append(f"{what}: no rule in {message!r}")
            s = shown(value)
            if s is not None and f"= {s}" not in message:
                failures.append(f"{what}: the value {s} not in {message!r}")
        if not o["seconds"] <= BEFORE_WORK_S:
            failures.append(f"{what}: refused after {o['seconds']:.2f} s (after work began?)")
    assert not failures, (f"seed {seed} (EPICYCLE_BAD_CALL_SEED={seed} repeats it), "
                          f"{len(failures)} of {len(calls)} bad calls:\n" + "\n".join(failures))
    assert len(calls) > 200  # every driver, every argument, several values each


def test_the_rules_are_the_programs():
    """The bindings' messages are the program's for the same option (same rule text)."""
    import epicycle
    import pytest

    from conftest import run_cli

    scene = epicycle.Scene.load(STAGE)
    with pytest.raises(ValueError) as e:
        epicycle.quasistatic(scene, start_deg=math.nan, cache_dir="")
    python = str(e.value)
    p = run_cli("quasistatic", STAGE, "--start-deg", "nan", check=False)
    assert p.returncode == 2
    assert python.startswith("start_deg = nan: ")
    assert python.split(": ", 1)[1] in p.stderr  # "must be finite and in [-3600, 3600] [deg] ..."
