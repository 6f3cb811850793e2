#!/usr/bin/python3
"""Figures of the stability stress study (ancf-study-stability, studies/README.md).

Usage: scripts/plot_stability.py [RUN_DIR = out/stability_stress] [--out DIR = studies/figures]
       [--prefix NAME = stability]

Writes
  NAME_map.png       success / failure map: one panel per swept parameter, a row per integrator
                     setting, a cell per case coloured by outcome and labelled with log10 of the
                     relative energy error (successes) or how the case ended;
  NAME_long_run.png  the 10^6-step runs: relative energy error and |Phi| against t, and the wall
                     time of each tenth of the run relative to the first tenth.
Needs numpy and matplotlib (Debian: python3-numpy, python3-matplotlib).
"""
import argparse
import csv
import math
import os
from collections import OrderedDict, defaultdict

import matplotlib

matplotlib.use("Agg")  # no display: write files only
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COLOURS = OrderedDict([
    ("success", "#4daf4a"),
    ("refused", "#bdbdbd"),
    ("clean stop", "#377eb8"),
    ("time limit", "#ffd92f"),
    ("blow-up", "#e41a1c"),
])

PANEL_TITLES = {
    ("stiffness", "f"): "Gerstmayr-Shabana pendulum: f (EA L²/EI = 4π·1e6/f²)",
    ("wire", "element_length_mm"): "steel wire L = 0.1 m: element length [mm]",
    ("snap", "tip_mass_kg"): "slack-to-taut snap: tip mass [kg]",
    ("rho", "rho_inf"): "generalized-α ρ∞ (G-S pendulum f = 5)",
    ("rho", "max_order"): "IDA BDF order limit (G-S pendulum f = 5)",
    ("large_h", "h"): "generalized-α step h [s] (benchmark pendulum)",
    ("large_h", "rtol"): "IDA rtol (benchmark pendulum)",
}


def outcome_class(outcome):
    return "blow-up" if outcome.startswith("blow-up") else outcome


def cell_label(row):
    cls = outcome_class(row["outcome"])
    if cls == "success":
        e = float(row["energy_error_max"])
        return f"{math.log10(e):.1f}" if e > 0 else "-inf"
    if cls == "time limit":
        return f"t={float(row['t_reached']):.2g}"
    return {"refused": "ref.", "clean stop": "stop", "blow-up": "BLOW"}[cls]


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def plot_map(rows, path):
    panels = OrderedDict()
    for r in rows:
        key = (r["group"], r["parameter_name"])
        if key in PANEL_TITLES:
            panels.setdefault(key, []).append(r)
    n = len(panels)
    cols = 2
    lines = (n + 1 + cols - 1) // cols  # one more cell for the legend
    fig, axes = plt.subplots(lines, cols, figsize=(13, 2.6 * lines))
    axes = np.atleast_1d(axes).ravel()
    for ax, (key, panel) in zip(axes, panels.items()):
        params = sorted({float(r["parameter"]) for r in panel})
        integrators = list(OrderedDict.fromkeys(r["integrator"] for r in panel))
        for r in panel:
            x = params.index(float(r["parameter"]))
            y = integrators.index(r["integrator"])
            colour = COLOURS[outcome_class(r["outcome"])]
            ax.add_patch(plt.Rectangle((x - 0.48, y - 0.45), 0.96, 0.9, color=colour))
            ax.text(x, y, cell_label(r), ha="center", va="center", fontsize=8)
        ax.set_xlim(-0.5, len(params) - 0.5)
        ax.set_ylim(-0.5, len(integrators) - 0.5)
        ax.set_xticks(range(len(params)))
        ax.set_xticklabels([f"{p:g}" for p in params], fontsize=8)
        ax.set_yticks(range(len(integrators)))
        ax.set_yticklabels(integrators, fontsize=8)
        ax.invert_yaxis()
        ax.set_title(PANEL_TITLES[key], fontsize=9)
    for ax in axes[n:]:
        ax.axis("off")
    legend_ax = axes[n]
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in COLOURS.values()]
    legend_ax.legend(handles, list(COLOURS.keys()), loc="center", ncol=2, fontsize=9,
                     title="cell text: log10 max |ΔE|/E_scale (success), t reached (time limit)",
                     title_fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_long_run(series_rows, wall_rows, path):
    series = defaultdict(lambda: ([], [], []))
    for r in series_rows:
        t, e, p = series[r["integrator"]]
        t.append(float(r["t"]))
        e.append(float(r["energy_error"]))
        p.append(float(r["position_drift"]))
    walls = defaultdict(list)
    for r in wall_rows:
        walls[r["integrator"]].append((int(r["tenth"]), float(r["wall_s"])))
    fig, axes = plt.subplots(1, 3, figsize=(14, 3.8))
    for name, (t, e, p) in series.items():
        axes[0].plot(t, e, label=name, lw=0.8)
        axes[1].semilogy(t, np.maximum(p, 1e-20), label=name, lw=0.8)
    axes[0].set_xlabel("t [s]")
    axes[0].set_ylabel("(E − E₀) / E_scale")
    axes[0].set_title("energy error")
    axes[1].set_xlabel("t [s]")
    axes[1].set_ylabel("max |Φ| [m] (floored at 1e-20)")
    axes[1].set_title("position constraint drift (0 for a linear pin)")
    width = 0.8 / max(1, len(walls))
    for i, name in enumerate(list(series.keys()) or sorted(walls)):  # same colours as the lines
        w = sorted(walls.get(name, []))
        if not w:
            continue
        tenths = np.array([k for k, _ in w])
        ratio = np.array([s for _, s in w]) / w[0][1]
        axes[2].bar(tenths + (i - 0.5 * (len(walls) - 1)) * width, ratio, width, label=name)
    axes[2].axhline(1.0, color="k", lw=0.6)
    axes[2].set_xlabel("tenth of the run (10⁵ steps each)")
    axes[2].set_ylabel("wall time / wall time of the first tenth")
    axes[2].set_title("slowdown check")
    for ax in axes:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir", nargs="?", default="out/stability_stress")
    parser.add_argument("--out", default="studies/figures")
    parser.add_argument("--prefix", default="stability")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = read_rows(os.path.join(args.run_dir, "cases.csv"))
    plot_map(rows, os.path.join(args.out, f"{args.prefix}_map.png"))
    series = os.path.join(args.run_dir, "long_run_series.csv")
    wall = os.path.join(args.run_dir, "long_run_wall.csv")
    if os.path.exists(series) and os.path.exists(wall):
        plot_long_run(read_rows(series), read_rows(wall),
                      os.path.join(args.out, f"{args.prefix}_long_run.png"))
    print(f"wrote {args.out}/{args.prefix}_map.png, {args.prefix}_long_run.png")


if __name__ == "__main__":
    main()
