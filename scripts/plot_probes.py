#!/usr/bin/python3
"""Turn the probes.csv of `ancf run` into PNG figures, one per probe (columns LABEL.*).

Usage: scripts/plot_probes.py RUN_DIR_OR_CSV [--out DIR] [--probes LABEL ...]

Each figure plots every column of one probe against t; contact probes split the forces from
the gap. Needs only the standard library and matplotlib (Debian: python3-matplotlib).
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")  # no display: write files only
import matplotlib.pyplot as plt  # noqa: E402

UNITS = {
    "x": "m", "y": "m", "z": "m", "rx": "rad", "ry": "rad", "rz": "rad",
    "kinetic": "J", "strain": "J", "spring": "J", "load": "J", "total": "J",
    "position": "-", "velocity": "-", "active": "-", "samples": "-", "min_gap": "m", "centreline_gap": "m",
    "normal": "N", "friction": "N", "peak": "N", "angle": "rad", "rate": "rad/s", "torque": "N m",
}


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        sys.exit(f"{path}: empty file")
    header, data = rows[0], rows[1:]
    columns = {name: [float(r[i]) for r in data if len(r) == len(header)] for i, name in enumerate(header)}
    return header, columns


def group_probes(header):
    probes = {}
    for name in header[1:]:
        label, _, suffix = name.rpartition(".")
        probes.setdefault(label, []).append(suffix)
    return probes


def plot_probe(t, columns, label, suffixes, out_dir):
    groups = {}
    for s in suffixes:
        groups.setdefault(UNITS.get(s, ""), []).append(s)
    fig, axes = plt.subplots(len(groups), 1, sharex=True, figsize=(7, 2.6 * len(groups)), squeeze=False)
    for ax, (unit, names) in zip(axes[:, 0], groups.items()):
        for s in names:
            ax.plot(t, columns[f"{label}.{s}"], label=s)
        ax.set_ylabel(f"[{unit}]" if unit else "")
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize="small")
    axes[0, 0].set_title(label)
    axes[-1, 0].set_xlabel("t [s]")
    fig.tight_layout()
    path = os.path.join(out_dir, f"{label.replace('/', '_')}.png")
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("source", help="run directory (with probes.csv) or a CSV file")
    p.add_argument("--out", help="output directory (default: the run directory)")
    p.add_argument("--probes", nargs="*", help="only these probe labels")
    a = p.parse_args()
    csv_path = os.path.join(a.source, "probes.csv") if os.path.isdir(a.source) else a.source
    out_dir = a.out or os.path.dirname(os.path.abspath(csv_path))
    os.makedirs(out_dir, exist_ok=True)
    header, columns = read_csv(csv_path)
    if header[0] != "t":
        sys.exit(f"{csv_path}: first column must be t")
    for label, suffixes in group_probes(header).items():
        if a.probes and label not in a.probes:
            continue
        print(plot_probe(columns["t"], columns, label, suffixes, out_dir))


if __name__ == "__main__":
    main()
