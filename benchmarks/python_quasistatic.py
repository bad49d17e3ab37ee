"""The cost of the Python bindings: 1000 quasi-static positions of the paper's run-out case (one
planet revolution, sun fixed, warm-started, one thread) through epicycle.quasistatic, against the
same sweep through the library from C++ (bench_quasistatic's BM_StageSweep1000). Reports the
figures, asserts nothing (docs/python.md, "Cost").

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/python_quasistatic.py [build] [repeats]
"""
import json
import os
import subprocess
import sys
import time

import epicycle

here = os.path.dirname(os.path.abspath(__file__))
build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "build")
repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 3
scene = epicycle.Scene.load(os.path.join(here, "..", "scenes", "paper_stage_runout.toml"))
sweep = dict(range="planet", positions=1000, threads=1)
first = epicycle.quasistatic(scene, **sweep)  # builds or loads the tables once, not timed
times = []
for _ in range(repeats):
    t0 = time.perf_counter()
    r = epicycle.quasistatic(scene, **sweep)
    times.append(time.perf_counter() - t0)
assert (r.lsr == first.lsr).all()
cpp = subprocess.run([os.path.join(build, "benchmarks", "bench_quasistatic"),
                      "--benchmark_filter=BM_StageSweep1000/", "--benchmark_format=json",
                      f"--benchmark_repetitions={repeats}"],
                     capture_output=True, text=True, check=True)
runs = [b for b in json.loads(cpp.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
cpp_s = min(b["real_time"] for b in runs) / 1e3
py_s = min(times)
print(f"1000 positions, K_gamma {r.summary.k_gamma:.6f} (C++ {runs[0]['k_gamma']:.6f})")
print(f"  C++    {cpp_s:.3f} s (best of {len(runs)})")
print(f"  Python {py_s:.3f} s (best of {repeats}): {100 * (py_s / cpp_s - 1):+.1f} % against C++")
