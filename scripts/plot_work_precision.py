#!/usr/bin/python3
"""Figures of ancf-study-work-precision (studies/work_precision.cpp).

Usage: scripts/plot_work_precision.py DIR [FIGURE_DIR = studies/figures]
  DIR/runs.csv -> FIGURE_DIR/work_precision.png   (wall time against error, one panel per scene,
                                                   one curve per integrator setting)
               -> FIGURE_DIR/time_convergence.png (error against the number of steps; slope −p
                                                   is order p; dotted guides of slope −2)
Uses Debian's matplotlib (/usr/bin/python3) with the Agg backend; no numpy needed.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def curves(path):
    """{scene: {curve label: [(parameter, error, wall, steps)]}} of the successful runs."""
    out = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            if r["status"] != "ok" or not math.isfinite(float(r["error_m"])):
                continue
            if r["method"] == "ida":
                label = f"IDA, BDF order ≤ {r['max_order']} (rtol sweep)"
            else:
                label = f"gen-α ρ∞ = {float(r['rho_inf']):.1f} (h sweep)"
            out.setdefault(r["scene"], {}).setdefault(label, []).append(
                (float(r["parameter"]), float(r["error_m"]), float(r["wall_s"]), float(r["steps"])))
    return out


def panels(data, path, x_of, y_of, xlabel, ylabel, guide=None):
    scenes = list(data)
    fig, ax = plt.subplots(1, len(scenes), figsize=(5 * len(scenes), 4.5), squeeze=False)
    for axis, scene in zip(ax[0], scenes):
        for label, pts in data[scene].items():
            pts = sorted(pts, key=lambda p: -p[0])
            style = "o-" if label.startswith("IDA") else "s--"
            axis.loglog([x_of(p) for p in pts], [y_of(p) for p in pts], style, ms=4, lw=1, label=label)
        if guide:
            guide(axis, data[scene])
        axis.set_title(scene)
        axis.set_xlabel(xlabel)
        axis.grid(True, which="both", lw=0.3)
    ax[0][0].set_ylabel(ylabel)
    ax[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print("wrote", path)


def slope_two_guide(axis, scene_curves):
    """A dotted line of slope −2 through the finest generalized-α point."""
    pts = [p for label, c in scene_curves.items() if not label.startswith("IDA") for p in c]
    if not pts:
        return
    finest = max(pts, key=lambda p: p[3])
    n = [finest[3] / 16, finest[3]]
    axis.loglog(n, [finest[1] * (finest[3] / x) ** 2 for x in n], "k:", lw=1, label="slope −2")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    data = curves(os.path.join(sys.argv[1], "runs.csv"))
    figures = sys.argv[2] if len(sys.argv) > 2 else "studies/figures"
    os.makedirs(figures, exist_ok=True)
    panels(data, os.path.join(figures, "work_precision.png"), lambda p: p[1], lambda p: p[2],
           "max node position error [m]", "wall time [s]")
    panels(data, os.path.join(figures, "time_convergence.png"), lambda p: p[3], lambda p: p[1], "steps",
           "max node position error [m]", slope_two_guide)


if __name__ == "__main__":
    main()
