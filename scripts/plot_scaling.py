#!/usr/bin/python3
"""Figures of the scaling study (ancf-study-scaling, studies/README.md).

Usage: scripts/plot_scaling.py [RUN_DIR = out/scaling] [--out DIR = studies/figures]

Writes scaling_time.png (time per step against elements, log-log, with a slope-1 guide, and the
CPU time per element per step) and scaling_memory.png (peak memory increment against elements
with its least-squares line). Needs only the standard library and matplotlib (Agg backend).
"""
import argparse
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")  # no display: write files only
import matplotlib.pyplot as plt  # noqa: E402

SERIES = [  # (integrator, sweep, label, colour, marker)
    ("genalpha", "elements", "generalized-α, 1 string of N elements", "tab:blue", "o"),
    ("genalpha", "cables", "generalized-α, N/100 strings of 100", "tab:blue", "s"),
    ("ida", "elements", "IDA, 1 string of N elements", "tab:red", "o"),
    ("ida", "cables", "IDA, N/100 strings of 100", "tab:red", "s"),
]


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def series(rows, integrator, sweep, key):
    pts = [(int(r["elements"]), float(r[key])) for r in rows
           if r["integrator"] == integrator and r["sweep"] == sweep]
    return [p[0] for p in pts], [p[1] for p in pts]


def slope(xs, ys):
    """Least-squares slope of log y against log x."""
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((a - mx) ** 2 for a in lx)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sxx


def plot_time(rows, out):
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.8))
    all_x = []
    for integrator, sweep, label, colour, marker in SERIES:
        x, t = series(rows, integrator, sweep, "cpu_seconds_per_step")
        if len(x) < 2:
            continue
        all_x += x
        dashed = "--" if sweep == "cables" else "-"
        ax.loglog(x, t, dashed, color=colour, marker=marker,
                  label=f"{label} (p = {slope(x, t):.2f})")
        _, per = series(rows, integrator, sweep, "cpu_us_per_element_step")
        bx.semilogx(x, per, dashed, color=colour, marker=marker, label=label)
    # Slope-1 guide through the generalized-α 100-element point.
    x100 = [float(r["cpu_seconds_per_step"]) for r in rows
            if r["integrator"] == "genalpha" and r["elements"] == "100"]
    if x100 and all_x:
        lo, hi = min(all_x), max(all_x)
        ax.loglog([lo, hi], [x100[0] * lo / 100, x100[0] * hi / 100], ":", color="grey",
                  label="slope 1 (linear)")
    ax.set_xlabel("cable elements in the model")
    ax.set_ylabel("CPU time per step [s]")
    ax.set_title("time per step (p: least-squares exponent)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    bx.set_xlabel("cable elements in the model")
    bx.set_ylabel("CPU time per element per step [µs]")
    bx.set_ylim(bottom=0)
    bx.set_title("cost per element (flat = linear growth)")
    bx.grid(True, which="both", alpha=0.3)
    bx.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out, "scaling_time.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_memory(rows, out):
    fig, ax = plt.subplots(figsize=(6.5, 4.8))
    for integrator, sweep, label, colour, marker in SERIES:
        x, m = series(rows, integrator, sweep, "peak_rss_increment_mib")
        if len(x) < 2:
            continue
        n = len(x)
        mx, my = sum(x) / n, sum(m) / n
        b = sum((a - mx) * (c - my) for a, c in zip(x, m)) / sum((a - mx) ** 2 for a in x)
        dashed = "--" if sweep == "cables" else "-"
        ax.loglog(x, m, dashed, color=colour, marker=marker,
                  label=f"{label}: {my - b * mx:.1f} MiB + {1024 * b:.1f} KiB/element")
    ax.set_xlabel("cable elements in the model")
    ax.set_ylabel("peak RSS increment over an empty child [MiB]")
    ax.set_title("peak memory per case (forked child, ru_maxrss)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    path = os.path.join(out, "scaling_memory.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir", nargs="?", default="out/scaling")
    parser.add_argument("--out", default="studies/figures")
    args = parser.parse_args()
    rows = read_rows(os.path.join(args.run_dir, "scaling.csv"))
    os.makedirs(args.out, exist_ok=True)
    for path in (plot_time(rows, args.out), plot_memory(rows, args.out)):
        print(path)


if __name__ == "__main__":
    main()
