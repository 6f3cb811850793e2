"""Maps of the capture envelope from the table of `ancf sweep studies/sweeps/capture_envelope.toml`
(studies/README.md, "Capture envelope"). One panel per friction coefficient, initial lateral offset
of the pole root (x) against initial tilt (y); each case is a marker: filled circle = captured and
centred (locked, axis within CENTRED_MM of the ring axis at h/2 at the end), triangle = locked but
not centred, cross = not locked, grey = not run (yet) or failed. Labels: lock time [s], peak
contact force [N], final tilt [deg]. The capture boundary is the 0.5 contour of the captured
indicator over the cases that ran (drawn where at least a 2 x 2 block of cases exists).

Usage: /usr/bin/python3 studies/capture_envelope.py [out/capture_envelope/results.csv] [PNG]"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

CENTRED_MM = 2.0
table = sys.argv[1] if len(sys.argv) > 1 else "out/capture_envelope/results.csv"
png = sys.argv[2] if len(sys.argv) > 2 else "studies/figures/capture_envelope.png"


def num(s):
    try:
        return float(s)
    except ValueError:
        return math.nan


with open(table, newline="") as f:
    rows = list(csv.DictReader(f))

mus = sorted({num(r["mu"]) for r in rows} | {0.05, 0.2})
tilts = sorted({num(r["tilt_deg"]) for r in rows} | {0.0, 8.0, 16.0})
offsets = sorted({num(r["offset_mm"]) for r in rows} | {-30.0, 0.0, 30.0})
fig, axes = plt.subplots(1, len(mus), figsize=(5.5 * len(mus), 4.8), squeeze=False)
for ax, mu in zip(axes[0], mus):
    grid = np.full((len(tilts), len(offsets)), np.nan)
    for r in rows:
        if num(r["mu"]) != mu:
            continue
        i, j = tilts.index(num(r["tilt_deg"])), offsets.index(num(r["offset_mm"]))
        x, y = num(r["offset_mm"]), num(r["tilt_deg"])
        if r["status"] != "completed":
            ax.plot(x, y, "s", color="0.6", ms=12)
            ax.annotate(r["status"], (x, y), textcoords="offset points", xytext=(0, -20), ha="center", fontsize=7)
            continue
        lock, off = num(r["events.lock"]), 1e3 * num(r["events.final_lateral_offset_m"])
        locked = not math.isnan(lock)
        centred = locked and off < CENTRED_MM
        grid[i, j] = 1.0 if centred else 0.0
        marker, colour = ("o", "tab:green") if centred else (("^", "tab:orange") if locked else ("x", "tab:red"))
        ax.plot(x, y, marker, color=colour, ms=12, mew=3)
        label = (f"lock {lock:.2f} s\n" if locked else "no lock\n") + \
            f"F {num(r['events.peak_contact_force']):.0f} N\ntilt {num(r['events.final_tilt_deg']):.1f}°"
        ax.annotate(label, (x, y), textcoords="offset points", xytext=(0, -34), ha="center", fontsize=7)
    for t in tilts:
        for o in offsets:
            if not any(num(r["mu"]) == mu and num(r["tilt_deg"]) == t and num(r["offset_mm"]) == o for r in rows):
                ax.plot(o, t, "o", mfc="none", color="0.7", ms=12)
    ok = ~np.isnan(grid)
    if ok.sum() >= 4 and np.nanmin(grid) < 0.5 < np.nanmax(grid):
        ax.contour(offsets, tilts, np.where(ok, grid, 0.0), levels=[0.5], colors="k", linestyles="--")
    ax.set_title(f"μ = {mu:g}  (open grey: not run yet)")
    ax.set_xlabel("initial lateral offset of the pole root dx [mm] (+: towards the lean)")
    ax.set_ylabel("initial tilt about +y [deg]")
    ax.set_xlim(min(offsets) - 15, max(offsets) + 15)
    ax.set_ylim(min(tilts) - 5, max(tilts) + 3)
    ax.grid(alpha=0.3)
fig.suptitle("Capture envelope (green: captured and centred, orange: locked off-centre, red: not locked)")
fig.tight_layout()
fig.savefig(png, dpi=120)
print("wrote", png)
