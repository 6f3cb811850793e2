#!/usr/bin/python3
"""Plots of ancf-study-mesh-convergence: relative error against element count (log-log), one
line per quantity, labelled with the least-squares order fitted by the study (orders.csv).

Usage: scripts/plot_mesh_convergence.py [study output dir = out/mesh_convergence]
                                        [figure dir = studies/figures]
Writes mesh_convergence_statics.png and mesh_convergence_frequencies.png.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def series(rows):
    out = {}
    for r in rows:
        key = (r["problem"], r["quantity"], r["strain"])
        out.setdefault(key, []).append((int(r["elements"]), float(r["rel_error"])))
    return out


def reference_slope(ax, order, n0, e0, label):
    """A dashed triangle-free guide e = e0 (n/n0)^-order from the first point."""
    xs = [n0, n0 * 8]
    ax.plot(xs, [e0 * (x / n0) ** (-order) for x in xs], "k:", lw=0.8)
    ax.annotate(label, (xs[1], e0 * 8.0 ** (-order)), fontsize=7)


def panel(ax, data, fits, keys, title):
    for key in keys:
        if key not in data:
            continue
        pts = [(n, e) for n, e in data[key] if e > 0]
        fit = fits.get(key)
        order = f"{float(fit['fitted_order']):.2f}" if fit and fit["fitted_order"] != "nan" else "n/a"
        style = "-" if key[2] == "green" or key[0] == "catenary" else "--"
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], style, marker="o", ms=3,
                  label=f"{key[0]} {key[1]} ({key[2]}): slope {order}")
    ax.set_xlabel("elements N")
    ax.set_ylabel("relative error")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=6)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/mesh_convergence"
    figs = sys.argv[2] if len(sys.argv) > 2 else "studies/figures"
    os.makedirs(figs, exist_ok=True)
    data = series(read(os.path.join(out, "errors.csv")))
    fits = {(r["problem"], r["quantity"], r["strain"]): r
            for r in read(os.path.join(out, "orders.csv"))}

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    cant = [k for k in sorted(data) if k[0].startswith("cantilever")]
    panel(axes[0], data, fits, cant, "cantilever tip (extensible elastica §2, Mattiasson k = 3 §1)")
    reference_slope(axes[0], 4, 2, 1e-2, "h^4")
    panel(axes[1], data, fits, [k for k in sorted(data) if k[0] == "catenary"],
          "elastic catenary (Irvine, EA = 1e3 N)")
    reference_slope(axes[1], 6, 2, 1e-4, "h^6")
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "mesh_convergence_statics.png"), dpi=130)

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
    for ax, problem, title, order in [
        (axes[0], "beam", "clamped-free beam, bending", 4),
        (axes[1], "bar", "fixed-free bar, axial", 6),
        (axes[2], "string", "taut string (stretch 1.01)", 6),
    ]:
        panel(ax, data, fits, [k for k in sorted(data) if k[0] == problem],
              title + " (solid: Green, dashed: elastic line)")
        reference_slope(ax, order, 2, 1e-3, f"h^{order}")
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "mesh_convergence_frequencies.png"), dpi=130)


if __name__ == "__main__":
    main()
