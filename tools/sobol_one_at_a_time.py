#!/usr/bin/env python3
"""The Sobol indices of a study against a one-at-a-time sweep (docs/studies.md "Sensitivity:
Sobol indices").

Runs `epicycle study` on a Sobol study file (design = "sobol"), then, for each of its
[[variable]] tables, a Monte-Carlo study of that variable alone (the others at the base scene's
nominal values; the same [study] keys, `samples` cases), and prints a Markdown table per
output: each variable's first-order and total index with their bootstrap intervals, the
one-at-a-time standard deviation of the output, and the three rankings.

    python3 tools/sobol_one_at_a_time.py scenes/studies/sobol_pins_runout.toml \
        [--out DIR] [--samples 2000] [--threads 2] [--exe build/app/epicycle]
"""

import argparse
import json
import os
import subprocess
import sys
import tomllib


def run_study(exe, path, out, threads, cache):
    args = [exe, "study", path, "--out", out, "--threads", str(threads), "--quiet"]
    if cache:
        args += ["--cache", cache]
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"epicycle study {path}: exit {p.returncode}\n{p.stderr}")
    with open(os.path.join(out, "study_summary.json")) as f:
        return json.load(f)


def toml_value(v):
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    return repr(v)


def toml_table(keys):
    return "".join(f"{k} = {toml_value(v)}\n" for k, v in keys.items())


def ranks(values):
    order = sorted(range(len(values)), key=lambda i: -values[i])
    r = [0] * len(values)
    for k, i in enumerate(order):
        r[i] = k + 1
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("study")
    ap.add_argument("--out", default="sobol-oat")
    ap.add_argument("--samples", type=int, default=2000)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--exe", default=os.path.join("build", "app", "epicycle"))
    ap.add_argument("--cache", default="")
    ap.add_argument("--outputs", default="K_gamma,TE_pp_urad")
    a = ap.parse_args()
    with open(a.study, "rb") as f:
        spec = tomllib.load(f)
    study_dir = os.path.dirname(os.path.abspath(a.study))
    os.makedirs(a.out, exist_ok=True)
    sobol = run_study(a.exe, a.study, os.path.join(a.out, "sobol"), a.threads, a.cache)["sobol"]
    # One study per [[variable]] (a "planets" table would be three variables: not split here).
    oat = []
    for k, var in enumerate(spec["variable"]):
        keys = dict(spec["study"])
        keys.pop("design", None)
        keys["samples"] = a.samples
        keys["name"] = f"one at a time: variable {k}"
        keys["scene"] = os.path.join(study_dir, keys["scene"])
        text = "[study]\n" + toml_table(keys) + "\n[[variable]]\n" + toml_table(var)
        path = os.path.join(a.out, f"oat{k}.toml")
        with open(path, "w") as f:
            f.write(text)
        oat.append(run_study(a.exe, path, os.path.join(a.out, f"oat{k}"), a.threads, a.cache))
    if len(oat) != len(sobol["variables"]):
        sys.exit("a [[variable]] table stands for several variables: one-at-a-time not split")
    print(f"N = {sobol['base_samples_N']}, {sobol['bootstrap_resamples']} bootstrap resamples, "
          f"{100 * sobol['confidence_level']:g} % intervals; one at a time: {a.samples} cases "
          "each\n")
    stat_key = {"K_gamma": "K_gamma", "TE_pp_urad": "TE_peak_to_peak_urad",
                "K_gamma_mean": "K_gamma_sweep_mean"}
    for name in a.outputs.split(","):
        o = sobol["outputs"][name]
        sd = [j[stat_key[name]]["std"] for j in oat]
        first = [x["value"] for x in o["first_order"]]
        total = [x["value"] for x in o["total"]]
        print(f"**{name}**\n")
        print("| variable | S_i [95 % CI] | S_Ti [95 % CI] | one-at-a-time std | rank S_i / S_Ti "
              "/ one at a time |")
        print("|---|---|---|---|---|")
        rf, rt, ro = ranks(first), ranks(total), ranks(sd)
        for i, v in enumerate(sobol["variables"]):
            f_, t_ = o["first_order"][i], o["total"][i]
            print(f"| {v} | {f_['value']:.3f} [{f_['ci'][0]:.3f}, {f_['ci'][1]:.3f}] | "
                  f"{t_['value']:.3f} [{t_['ci'][0]:.3f}, {t_['ci'][1]:.3f}] | {sd[i]:.4g} | "
                  f"{rf[i]} / {rt[i]} / {ro[i]} |")
        s = o["sum_first_order"]
        print(f"| sum | {s['value']:.3f} [{s['ci'][0]:.3f}, {s['ci'][1]:.3f}] | "
              f"{sum(total):.3f} | | |\n")


if __name__ == "__main__":
    main()
