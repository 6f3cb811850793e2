#!/usr/bin/python3
"""Figures of the capture example from the outputs of ancf-capture (studies/capture_study.cpp).

Usage: scripts/plot_capture.py [--window T0 T1] DIR [DIR2 ...]
  DIR/samples.csv   -> DIR/capture_tilt.png, DIR/capture_drive.png, DIR/capture_contact.png
  DIR/snapshots.csv -> DIR/capture_snapshots.png (the mechanism at t = 0, the events, the end)
With several DIRs (e.g. both integrators) the time series are overlaid in the first DIR's figures
as well, labelled by the directory names. --window T0 T1 limits the time series to T0 <= t <= T1
(e.g. the pole's swings between the ropes, to see a phase lead between meshes).
Uses Debian's matplotlib (/usr/bin/python3) with the Agg backend; no numpy needed.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_columns(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]} if rows else {}


def two_panels(path, title, panels, data, threshold=None, window=None):
    """One figure of two stacked panels sharing t; panels = [(ylabel, [(column, label suffix)])]."""
    fig, ax = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for axis, (ylabel, columns) in zip(ax, panels):
        for name, c in data:
            for column, suffix in columns:
                axis.plot(c["t"], c[column], label=f"{name}{suffix}", lw=1)
        axis.set_ylabel(ylabel)
    if threshold is not None:
        ax[0].axhline(threshold, color="grey", ls=":", lw=1)
    ax[0].legend(fontsize=7)
    if window:
        for axis in ax:  # y limits from the samples inside the window
            axis.set_xlim(*window)
            ys = [y for line in axis.get_lines() if len(line.get_xdata()) > 1
                  for x, y in zip(line.get_xdata(), line.get_ydata()) if window[0] <= x <= window[1]]
            if ys:
                pad = 0.05 * (max(ys) - min(ys) or 1.0)
                axis.set_ylim(min(ys) - pad, max(ys) + pad)
    ax[1].set_xlabel("t [s]")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def time_series(dirs, window=None):
    data = [(os.path.basename(os.path.normpath(d)), read_columns(os.path.join(d, "samples.csv"))) for d in dirs]
    out = dirs[0]
    two_panels(os.path.join(out, "capture_tilt.png"), "Capture: pole alignment",
               [("pole tilt [deg]", [("tilt_deg", "")]),
                ("axis offset at z = h/2 [mm]", [("lateral_offset_mm", "")])], data, threshold=0.3,
               window=window)
    two_panels(os.path.join(out, "capture_drive.png"), "Capture: ring drive",
               [("drive torque [N m]", [("drive_torque", "")]),
                ("ring angle [deg]", [("ring_angle_deg", "")])], data, threshold=0.95 * 6.0,
               window=window)
    ropes = (1, 2, 3)
    two_panels(os.path.join(out, "capture_contact.png"), "Capture: contact and rope forces",
               [("rope-pole normal force [N]", [(f"pole_force_{i}", f" rope {i}") for i in ropes]),
                ("rope end force at ring [N]", [(f"ring_tension_{i}", f" rope {i}") for i in ropes])], data,
               window=window)


def snapshots(d):
    path = os.path.join(d, "snapshots.csv")
    groups = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            groups.setdefault((r["label"], float(r["t"])), []).append((float(r["x"]), float(r["y"]), float(r["z"])))
    if not groups:
        return
    n = len(groups)
    cols = min(4, n)
    rows = math.ceil(n / cols)
    fig = plt.figure(figsize=(4 * cols, 4 * rows))
    for k, ((label, t), pts) in enumerate(groups.items()):
        ax = fig.add_subplot(rows, cols, k + 1, projection="3d")
        ropes = pts[:-2]
        per = len(ropes) // 3
        for i in range(3):
            r = ropes[i * per:(i + 1) * per]
            ax.plot([p[0] for p in r], [p[1] for p in r], [p[2] for p in r], lw=1.5)
        root, tip = pts[-2], pts[-1]
        ax.plot([root[0], tip[0]], [root[1], tip[1]], [root[2], tip[2]], color="k", lw=4)
        for z in (0.0, 0.15):  # the two rings
            ax.plot([0.1 * math.cos(a / 20 * math.pi) for a in range(41)],
                    [0.1 * math.sin(a / 20 * math.pi) for a in range(41)], [z] * 41, color="grey", lw=1)
        ax.set_xlim(-0.11, 0.11)
        ax.set_ylim(-0.11, 0.11)
        ax.set_zlim(-0.08, 0.2)
        ax.set_title(f"{label}\nt = {t:.2f} s", fontsize=9)
        ax.set_box_aspect((1, 1, 1.3))
    fig.tight_layout()
    fig.savefig(os.path.join(d, "capture_snapshots.png"), dpi=110)
    plt.close(fig)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    args = sys.argv[1:]
    window = None
    if args[:1] == ["--window"]:
        if len(args) < 4:
            sys.exit(__doc__)
        window = (float(args[1]), float(args[2]))
        args = args[3:]
    dirs = args
    time_series(dirs, window)
    for d in dirs:
        snapshots(d)
    print("figures written to", ", ".join(dirs))


if __name__ == "__main__":
    main()
