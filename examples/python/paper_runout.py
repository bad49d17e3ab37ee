"""The paper's Figs. 4 and 5: load-sharing ratios over one planet revolution with a 20 µm run-out
on planet 1, sun fixed (Fig. 4) and floating (Fig. 5). Writes paper_runout.png (or argv[1])."""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

import epicycle

here = os.path.dirname(os.path.abspath(__file__))
scene = epicycle.Scene.load(os.path.join(here, "..", "..", "scenes", "paper_stage_runout.toml"))
turn = scene["ring.teeth"] / scene["planet.teeth"]  # planet turn per carrier turn (relative)
fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
for ax, sun, fig_no in zip(axes, ("fixed", "floating"), (4, 5)):
    r = epicycle.quasistatic(scene.with_values({"supports.sun": sun}), range="planet", positions=360)
    for i in range(r.planets):
        ax.plot(r.carrier_deg * turn, r.lsr[:, i], label=f"planet {i + 1}")
    ax.axhline(1 / r.planets, color="grey", lw=0.5)
    ax.set(title=f"Fig. {fig_no}: sun {sun}, K_γ = {r.summary.k_gamma:.3f}",
           xlabel="planet 1 rotation relative to the carrier [deg]", xlim=(0, 360))
axes[0].set_ylabel("load-sharing ratio LSR_i [-]")
axes[0].legend()
fig.tight_layout()
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "paper_runout.png", dpi=120)
