"""Maps of the capture envelope from the tables of `ancf sweep` (studies/README.md, "Capture
envelope"): studies/sweeps/capture_envelope.toml (offset x tilt about +y) and the wide passes
(studies/sweeps/capture_envelope_wide.toml, ..._refine.toml: with the lean direction, column
tilt_axis). Each case is a marker at its root offset dx (x) and its tilt component (y): left panel
of a friction value the tilt in the plane of the offset (knob towards +x positive, beta = 0/180),
right panel the tilt across it (towards +y positive, beta = 90/270); untilted cases are in both.
Filled circle = captured and centred (locked, axis within CENTRED_MM of the ring axis at h/2 at
the end), triangle = locked off-centre, cross = not locked (label: why), grey square = the run
failed (status). Grey area: impossible starts (studies/capture_geometry.py: shaft outside a ring
bore or a rope inside the pole). The dashed line is the boundary of capture: the 0.5 contour of
the captured indicator, interpolated linearly over a triangulation of the cases of the panel.

When the case folders are there (SWEEP_OUT/cases/case-NNNN/out/probes.csv next to the table),
each case's pole history is read for what the events do not say: the largest distance of the
pole axis from the ring axis at the two rings (a pole through a ring, which has no contact shape
in the scene), the ropes on the knob at the end, and the drive angle at the end. These go into
a derived table (--derived CSV).

Usage: /usr/bin/python3 studies/capture_envelope.py [--derived CSV] TABLE.csv [TABLE.csv ...] PNG"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from capture_geometry import H, start_problem  # noqa: E402

CENTRED_MM = 2.0


def num(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return math.nan


def lean_deg(row):
    """Azimuth the knob leans towards, from tilt_axis = (-sin b, cos b, 0) (absent: 0)."""
    text = row.get("tilt_axis")
    if not text:
        return 0.0
    ax, ay, _ = (float(v) for v in text.strip("[] ").split(","))
    return math.degrees(math.atan2(-ax, ay)) % 360.0


def rotation(rv):
    th = np.linalg.norm(rv)
    if th < 1e-15:
        return np.eye(3)
    k = rv / th
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(th) * kx + (1 - math.cos(th)) * kx @ kx


def history(probes):
    """What the pole history shows: largest axis distance from the ring axis at z = 0 and h [mm],
    ropes on the knob at the end, drive angle at the end [deg]."""
    with open(probes, newline="") as f:
        rows = list(csv.DictReader(f))
    worst = 0.0
    for r in rows:
        p = np.array([num(r["pole.x"]), num(r["pole.y"]), num(r["pole.z"])])
        a = rotation(np.array([num(r["pole.rx"]), num(r["pole.ry"]), num(r["pole.rz"])])) @ [0, 0, 1]
        for z in (0.0, H):
            q = p + (z - p[2]) / a[2] * a
            worst = max(worst, math.hypot(q[0], q[1]))
    last = rows[-1]
    knob = sum(1 for i in (1, 2, 3) if num(last.get(f"rope {i}-knob.active")) > 0)
    return 1e3 * worst, knob, math.degrees(num(last["ring drive.angle"]))


def classify(r):
    """(kind, label): kind 'centred' | 'offcentre' | 'nolock' | 'run failed'."""
    if r["status"] != "completed":
        return "run failed", r["status"]
    lock = num(r["events.lock"])
    if math.isnan(lock):
        if math.isnan(num(r["events.all_three"])):
            why = "a rope never on the pole"
        elif math.isnan(num(r["events.stall"])):
            why = "no stall"
        else:
            why = "not at rest"
        return "nolock", why
    if 1e3 * num(r["events.final_lateral_offset_m"]) < CENTRED_MM:
        return "centred", f"lock {lock:.2f} s"
    return "offcentre", f"lock {lock:.2f} s"


def main():
    args = sys.argv[1:]
    derived = None
    if args[:1] == ["--derived"]:
        derived, args = args[1], args[2:]
    png = args[-1] if args and args[-1].endswith(".png") else "studies/figures/capture_envelope.png"
    tables = [a for a in args if a.endswith(".csv")] or ["out/capture_envelope/results.csv"]
    rows = []
    for table in tables:
        with open(table, newline="") as f:
            for r in csv.DictReader(f):
                r["table"] = table
                r["lean"] = lean_deg(r)
                probes = os.path.join(os.path.dirname(table), "cases", "case-%04d" % int(r["case"]),
                                      "out", "probes.csv")
                if os.path.exists(probes) and r["status"] == "completed":
                    r["bore_max_mm"], r["knob_ropes_end"], r["drive_end_deg"] = history(probes)
                rows.append(r)
    if derived:
        cols = ["table", "case", "mu", "offset_mm", "tilt_deg", "lean", "status", "class", "why",
                "events.lock", "events.final_tilt_deg", "events.final_lateral_offset_m",
                "events.peak_contact_force", "bore_max_mm", "knob_ropes_end", "drive_end_deg"]
        with open(derived, "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(["lean_deg" if c == "lean" else c for c in cols])
            for r in rows:
                r["class"], r["why"] = classify(r)
                w.writerow([r.get(c, "") if not isinstance(r.get(c), float) else f"{r[c]:.6g}"
                            for c in cols])
        print("wrote", derived)

    mus = sorted({num(r["mu"]) for r in rows})
    wide = any(r.get("tilt_axis") for r in rows)
    offsets = [num(r["offset_mm"]) for r in rows]
    xlim = (min(min(offsets), -90.0) - 10, max(max(offsets), 90.0) + 10) if wide else \
        (min(offsets) - 15, max(offsets) + 15)
    tmax = max(num(r["tilt_deg"]) for r in rows) + 4
    panels = (("x", 0.0), ("y", 90.0)) if wide else (("x", 0.0),)
    if wide:
        fig, axes = plt.subplots(len(mus), 2, figsize=(14.0, 5.4 * len(mus)), squeeze=False)
    else:
        fig, axes = plt.subplots(1, len(mus), figsize=(5.5 * len(mus), 4.8), squeeze=False)
        axes = axes.T
    for i, mu in enumerate(mus):
        for j, (comp, along) in enumerate(panels):
            ax = axes[i][j]
            # Impossible starts, on a grid of the panel (tilt about the panel's direction).
            gx = np.linspace(*xlim, 61)
            gy = np.linspace(-tmax, tmax, 41) if wide else np.linspace(-5, tmax, 31)
            bad = np.array([[start_problem(x, abs(y), along if y >= 0 else along + 180, samples=100)
                             is not None for x in gx] for y in gy], dtype=float)
            ax.contourf(gx, gy, bad, levels=[0.5, 1.5], colors=["0.85"])
            ax.contour(gx, gy, bad, levels=[0.5], colors="0.5", linewidths=0.8)
            pts, ind = [], []
            for r in rows:
                if num(r["mu"]) != mu:
                    continue
                th, b = num(r["tilt_deg"]), math.radians(r["lean"])
                c = math.cos(b) if comp == "x" else math.sin(b)
                if th > 0 and abs(c) < 0.5:
                    continue  # this case leans the other way: it is in the other panel
                x, y = num(r["offset_mm"]), th * (round(c) if th > 0 else 0.0)
                kind, label = classify(r)
                style = {"centred": ("o", "tab:green"), "offcentre": ("^", "tab:orange"),
                         "nolock": ("x", "tab:red"), "run failed": ("s", "0.5")}[kind]
                ax.plot(x, y, style[0], color=style[1], ms=10, mew=2.5)
                if kind in ("centred", "offcentre", "nolock"):
                    pts.append((x, y))
                    ind.append(1.0 if kind == "centred" else 0.0)
                if kind != "centred":
                    extra = f"\n{num(r['events.final_tilt_deg']):.1f}°" if kind == "offcentre" else ""
                    ax.annotate(label + extra, (x, y), textcoords="offset points", xytext=(0, -22),
                                ha="center", fontsize=6.5)
            if len(pts) >= 3 and 0.0 < sum(ind) < len(ind):
                p = np.array(pts)
                try:
                    tri = mtri.Triangulation(p[:, 0], p[:, 1])
                    ax.tricontour(tri, ind, levels=[0.5], colors="k", linestyles="--")
                except (RuntimeError, ValueError):
                    pass  # collinear cases: no triangulation, no boundary drawn
            name = "in the plane of the offset (+: knob towards +x)" if comp == "x" else \
                "across the offset (+: knob towards +y)"
            ax.set_title(f"μ = {mu:g}: tilt {name}" if wide else f"μ = {mu:g}", fontsize=10)
            ax.set_xlabel("root offset dx [mm] (along x)")
            ax.set_ylabel("initial tilt [deg]")
            ax.set_xlim(*xlim)
            ax.set_ylim(gy[0], gy[-1])
            ax.grid(alpha=0.3)
    fig.suptitle("Capture envelope: green captured and centred, orange locked off-centre, red not locked,\n"
                 "grey square run failed; grey area: impossible start; dashed: boundary of capture",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print("wrote", png)


if __name__ == "__main__":
    main()
