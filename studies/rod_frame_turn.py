#!/usr/bin/env python3
"""Frame updates and the twist-inertia model of the Kirchhoff rod (docs/rod.md, "Frame updates").

Runs studies/scenes/rod_whirl.toml (a straight rod whirled by a suddenly applied end moment) and
studies/scenes/rod_helix_spin.toml (a helix under a suddenly applied distributed moment) through
`ancf run` with generalized-alpha at the steps h0, h0/2, ... for each node-frame update setting
([integrator] rod_frame_turn) and each polar inertia rho J given, reads the tip's material axis d2
at t_end (probe columns tip_frame.d2x/y/z), and prints

  * the differences of d2 between successive steps and the observed orders
    p = log2(|d2_h - d2_h/2| / |d2_h/2 - d2_h/4|): first order with updates after 0.1 rad, second
    with none (2 rad) or with an update at every step (0);
  * at the finest step, |d2(turn) - d2(turn = 0)|: the spread between the settings, i.e. the size
    of the constant twist mass's model error (it leaves out the smallest-rotation frame's own
    spin), against generalized-alpha's own time-step error;
  * optionally (--ida) IDA's steps for each setting.

  studies/rod_frame_turn.py [--scene S ...] [--rho-j 5e-6,2e-4,2e-3] [--turns 0,0.1,2] [--h0 1e-3] [--levels 6]
                            [--ida] [--ancf build-release/src/app/ancf] [--out DIR]

Only the standard library (no numpy needed)."""
import argparse
import csv
import json
import math
import os
import subprocess
import tempfile

SCENES = [os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes", name)
          for name in ("rod_whirl.toml", "rod_helix_spin.toml")]


def run(ancf, scene, out, sets, method):
    cmd = [ancf, "run", scene, "--integrator", method, "--quiet", "--out", out]
    for kv in sets:
        cmd += ["--set", kv]
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({done.returncode}):\n{done.stderr}")
    with open(os.path.join(out, "probes.csv")) as f:
        last = list(csv.DictReader(f))[-1]
    with open(os.path.join(out, "run.json")) as f:
        counters = json.load(f)["counters"]
    return [float(last[f"tip_frame.d2{c}"]) for c in "xyz"], counters


def distance(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", action="append", help="scene(s) with a rod probe 'tip_frame' "
                    "(default: rod_whirl.toml and rod_helix_spin.toml)")
    ap.add_argument("--rho-j", default="5e-6,2e-4,2e-3", help="polar inertias rho J [kg m]")
    ap.add_argument("--turns", default="0,0.1,2", help="rod_frame_turn values [rad]; 0 first")
    ap.add_argument("--h0", type=float, default=1e-3, help="largest step [s]")
    ap.add_argument("--levels", type=int, default=6, help="number of steps h0 / 2^k")
    ap.add_argument("--ida", action="store_true", help="also IDA's steps (rtol 1e-8)")
    ap.add_argument("--expect-order", action="append", default=[], metavar="TURN:MIN",
                    help="exit 1 unless the last observed order for rod_frame_turn TURN is >= MIN "
                    "(the smoke test in test/CMakeLists.txt)")
    ap.add_argument("--ancf", default="build-release/src/app/ancf")
    ap.add_argument("--out", default=None, help="keep the runs here (default: a temporary dir)")
    a = ap.parse_args()
    rho_js = [float(x) for x in a.rho_j.split(",")]
    turns = [float(x) for x in a.turns.split(",")]
    steps = [a.h0 / 2**k for k in range(a.levels)]
    expected = {float(t): float(m) for t, m in (x.split(":") for x in a.expect_order)}
    out = a.out or tempfile.mkdtemp(prefix="rod_frame_turn_")
    print(f"runs in {out}")
    failed = []
    for scene in a.scene or SCENES:
        for rho_j in rho_js:
            last_orders = study(a, scene, rho_j, turns, steps, out)
            failed += [f"{os.path.basename(scene)}, rho J {rho_j:g}, turn {t:g}: order "
                       f"{last_orders[t]:.2f} < {m:g}" for t, m in expected.items()
                       if t in last_orders and last_orders[t] < m]
    if failed:
        raise SystemExit("observed orders below the expected:\n  " + "\n  ".join(failed))


def study(a, scene, rho_j, turns, steps, out):
    """One scene at one polar inertia: the step-size table, the spread, IDA's steps. Returns the
    last observed order per turn."""
    name = os.path.splitext(os.path.basename(scene))[0]
    finest, last_orders = {}, {}
    print(f"\n{name}, rho J = {rho_j:g} kg m; generalized-alpha (rtol 1e-10), tip d2 at t_end")
    print("| rod_frame_turn | |d2_h - d2_h/2| for h = " + ", ".join(f"{h:.4g}" for h in steps[:-1])
          + " | observed orders | frame updates at the finest h |")
    print("|---|---|---|---|")
    for turn in turns:
        d2s, updates = [], 0
        for h in steps:
            d = os.path.join(out, f"{name}_rhoj{rho_j:g}_turn{turn:g}_h{h:.6g}")
            sets = [f"rod[0].section.polar_inertia={rho_j!r}",
                    f"integrator.rod_frame_turn={turn!r}", "integrator.rtol=1e-10",
                    f"integrator.genalpha.step={h!r}"]
            d2, counters = run(a.ancf, scene, d, sets, "genalpha")
            d2s.append(d2)
            updates = counters["rod frame updates"]
        diffs = [distance(d2s[i], d2s[i + 1]) for i in range(len(d2s) - 1)]
        orders = [math.log2(diffs[i] / diffs[i + 1]) for i in range(len(diffs) - 1)
                  if diffs[i + 1] > 0.0]
        finest[turn] = (d2s[-1], diffs[-1])
        if orders:
            last_orders[turn] = orders[-1]
        print(f"| {turn:g} | " + ", ".join(f"{x:.2e}" for x in diffs) + " | "
              + ", ".join(f"{p:.2f}" for p in orders) + f" | {updates} |")
    base = finest.get(turns[0])
    print(f"\nspread at h = {steps[-1]:.4g} against rod_frame_turn = {turns[0]:g} "
          "(its last step difference in brackets, a bound on its time-step error):")
    for turn in turns[1:]:
        print(f"  turn {turn:g}: |d2 - d2({turns[0]:g})| = {distance(finest[turn][0], base[0]):.2e}"
              f"  [{finest[turn][1]:.1e} vs {base[1]:.1e}]")
    if a.ida:
        parts = []
        for turn in turns:
            d = os.path.join(out, f"{name}_rhoj{rho_j:g}_turn{turn:g}_ida")
            sets = [f"rod[0].section.polar_inertia={rho_j!r}",
                    f"integrator.rod_frame_turn={turn!r}", "integrator.rtol=1e-8"]
            _, counters = run(a.ancf, scene, d, sets, "ida")
            parts.append(f"turn {turn:g}: {counters['steps']} steps "
                         f"({counters['rod frame updates']} with frame updates)")
        print("IDA (rtol 1e-8): " + "; ".join(parts))
    return last_orders


if __name__ == "__main__":
    main()
