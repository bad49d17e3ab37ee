#!/usr/bin/env python3
"""The face-width ratings of docs/face_width.md ("Ratings across the face") as Markdown tables.

    python3 tools/face_width_table.py NAME=SUMMARY.json ...

Each SUMMARY.json is the quasistatic_summary.json of `epicycle quasistatic SCENE --rating` on a
stage with slices (tools/paper_figures.sh writes them into docs/figures/face_*_summary.json).
A mesh whose K_Hbeta stays within 0.5 % of 1 has no loaded end ("uniform").
"""
import json
import sys


def table(name, path):
    summary = json.load(open(path))
    rated = {m["mesh"]: m for m in summary["rating"]["face_width"]}
    rows = [f"**{name}**", "",
            "| mesh | K_Hβ max (mean) | loaded end | f_ma, f_sh [µm] | K_Hβ ISO C | K_γ "
            "| K_γ·K_Hβ model | K_γ(table)·K_Hβ(C) | K_γ(model)·K_Hβ(C) "
            "| σ_F max [MPa] (gear, S_F) | p_H max [MPa] (S_H) |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    for f in summary["face_width"]:
        r = rated[f["mesh"]]
        end = ("uniform" if f["K_Hbeta_max"] < 1.005
               else "+z" if f["largest_load_z_mm"] > 0 else "−z")
        rows.append(
            f"| {f['mesh']} | {f['K_Hbeta_max']:.3f} ({f['K_Hbeta_mean']:.3f}) | {end} "
            f"| {r['f_ma_um']:.2f}, {r['f_sh_um']:.2f} | {r['K_Hbeta_ISO_method_C']:.3f} "
            f"| {r['K_gamma_model']:.3f} | {r['K_gamma_K_Hbeta_model']:.3f} "
            f"| {r['K_gamma_K_Hbeta_ISO']:.3f} "
            f"| {r['K_gamma_model'] * r['K_Hbeta_ISO_method_C']:.3f} "
            f"| {r['root_stress_model_MPa']:.0f} ({r['root_stress_gear']}, "
            f"{r['S_F_model_stress']:.2f}) "
            f"| {r['hertz_pressure_model_MPa']:.0f} ({r['S_H_model_pressure']:.2f}) |")
    return "\n".join(rows)


def main(args):
    if not args:
        print(__doc__, file=sys.stderr)
        return 2
    out = []
    for arg in args:
        name, _, path = arg.partition("=")
        out.append(table(name, path))
    print("\n\n".join(out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
