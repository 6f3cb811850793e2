#!/usr/bin/python3
"""Figures of ancf-study-energy-drift (studies/energy_drift.cpp).

Usage: scripts/plot_energy_drift.py DIR [FIGURE_DIR = studies/figures]
  DIR/<scene>_<run>.csv -> FIGURE_DIR/energy_drift.png: relative energy error against t (symmetric
  log scale, linear within ±1e-8), one panel per scene (pendulum, spinning, rigid), one curve per
  generalized-α setting at h = 1e-3 s and every IDA run present;
  FIGURE_DIR/energy_drift_steps.png: max |relative energy error| against h for each
  generalized-α variant and scene (DIR/summary.csv), with a slope-2 guide.
Uses Debian's matplotlib (/usr/bin/python3) with the Agg backend; no numpy needed.
"""
import csv
import glob
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENES = ["pendulum", "spinning", "rigid"]


def label(run):
    m = re.match(r"genalpha_(index[23])_rho([0-9.]+)_h(.*)", run)
    if m:
        return f"gen-α {m.group(1)}, ρ∞ = {m.group(2)}, h = {float(m.group(3)):g}"
    return run.replace("ida_rtol", "IDA rtol ")


def traces(directory, scene):
    out = []
    for path in sorted(glob.glob(os.path.join(directory, f"{scene}_*.csv"))):
        run = os.path.basename(path)[len(scene) + 1:-4]
        if run.startswith("genalpha") and not run.endswith("h1e-03"):
            continue
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        out.append((label(run), [float(r["t"]) for r in rows], [float(r["rel_energy_error"]) for r in rows]))
    return out


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    directory = sys.argv[1]
    figures = sys.argv[2] if len(sys.argv) > 2 else "studies/figures"
    os.makedirs(figures, exist_ok=True)

    fig, ax = plt.subplots(len(SCENES), 1, figsize=(9, 9), sharex=True)
    for axis, scene in zip(ax, SCENES):
        for name, t, e in traces(directory, scene):
            axis.plot(t, e, lw=0.8, label=name)
        # Symmetric log scale: IDA at rtol 1e-4 errs by up to 0.3, the others by 1e-8 … 1e-4.
        axis.set_yscale("symlog", linthresh=1e-8)
        axis.set_title(scene, fontsize=9)
        axis.set_ylabel("(E − E₀)/E_scale")
        axis.grid(True, lw=0.3)
        axis.legend(fontsize=6, loc="lower left")
    ax[-1].set_xlabel("t [s]")
    fig.tight_layout()
    path = os.path.join(figures, "energy_drift.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print("wrote", path)

    with open(os.path.join(directory, "summary.csv"), newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["run"].startswith("genalpha")]
    fig, ax = plt.subplots(1, len(SCENES), figsize=(13, 4), squeeze=False)
    for axis, scene in zip(ax[0], SCENES):
        variants = {}
        for r in rows:
            if r["scene"] != scene:
                continue
            m = re.match(r"genalpha_(index[23])_rho([0-9.]+)_h(.*)", r["run"])
            variants.setdefault(f"{m.group(1)}, ρ∞ = {m.group(2)}", []).append(
                (float(m.group(3)), float(r["max_abs_rel_energy_error"])))
        for name, pts in variants.items():
            pts.sort()
            axis.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", ms=4, lw=1, label=name)
        if variants:
            h0, e0 = sorted(next(iter(variants.values())))[0]
            hs = [h0, 4 * h0]
            axis.loglog(hs, [e0 * (h / h0) ** 2 for h in hs], "k:", lw=1, label="slope 2")
        axis.set_title(scene)
        axis.set_xlabel("h [s]")
        axis.grid(True, which="both", lw=0.3)
    ax[0][0].set_ylabel("max |relative energy error|")
    ax[0][0].legend(fontsize=7)
    fig.tight_layout()
    path = os.path.join(figures, "energy_drift_steps.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print("wrote", path)


if __name__ == "__main__":
    main()
