#!/usr/bin/python3
"""Capture work-precision study (issue 15): wall time against the error of the pole-tilt and
ring-angle histories of studies/scenes/capture.toml, for fixed-step and variable-step
generalized-alpha and for IDA, against a fixed-step generalized-alpha reference (h = 2.5e-4 s).

Every run is one `ancf-capture` process (its samples.csv on the 0.01 s output grid and its
events.json with wall time, counters and the event table); this script only sweeps, compares and
plots. Errors are max over the output times of |tilt - tilt_ref| and |ring angle - ring_ref| [deg],
and the differences of the locked state (lock time, ring angle at stall, rope tensions at lock,
final tilt) from the reference's.

Usage (from the repository root, after scripts/bench or a Release build):
  /usr/bin/python3 studies/capture_work_precision.py [--out out/capture-wp] [--t-end T]
      [--elements N] [--quick] [--only LABEL,...]
--quick: a short sweep (two configurations per method) for a smoke run.
Writes OUT/results.csv, OUT/results.json and OUT/work_precision.png.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

BIN = "build-release/studies/ancf-capture"

# label -> ancf-capture arguments. Variable-step generalized-alpha uses the scene keys of the
# step controller ([integrator.genalpha] stepping = "error_controlled", error_rtol).
REFERENCE = ("genalpha h=2.5e-4", ["--integrator", "genalpha", "--step", "2.5e-4"])
FULL = [
    ("genalpha h=2e-3", ["--integrator", "genalpha", "--step", "2e-3"]),
    ("genalpha h=1e-3", ["--integrator", "genalpha", "--step", "1e-3"]),
    ("genalpha h=5e-4", ["--integrator", "genalpha", "--step", "5e-4"]),
    ("genalpha adaptive rtol=1e-3", ["--integrator", "genalpha", "--set",
                                     'genalpha.stepping="error_controlled"',
                                     "--set", "genalpha.error_rtol=1e-3"]),
    ("genalpha adaptive rtol=1e-4", ["--integrator", "genalpha", "--set",
                                     'genalpha.stepping="error_controlled"',
                                     "--set", "genalpha.error_rtol=1e-4"]),
    ("genalpha adaptive rtol=1e-5", ["--integrator", "genalpha", "--set",
                                     'genalpha.stepping="error_controlled"',
                                     "--set", "genalpha.error_rtol=1e-5"]),
    ("genalpha adaptive --fast", ["--integrator", "genalpha", "--fast"]),
    ("ida rtol=1e-4", ["--integrator", "ida", "--rtol", "1e-4",
                       "--set", 'ida.slope_scale="position_equivalent"']),
    ("ida rtol=1e-5", ["--integrator", "ida", "--rtol", "1e-5",
                       "--set", 'ida.slope_scale="position_equivalent"']),
    ("ida rtol=1e-6", ["--integrator", "ida", "--rtol", "1e-6",
                       "--set", 'ida.slope_scale="position_equivalent"']),
]
QUICK = [FULL[0], FULL[1], FULL[3], FULL[7]]


def run(label, args, opt):
    out = os.path.join(opt.out, label.replace(" ", "_").replace("=", ""))
    cmd = [BIN, "--out", out] + args
    if opt.t_end:
        cmd += ["--t-end", str(opt.t_end)]
    if opt.elements:
        cmd += ["--elements", str(opt.elements)]
    print("  " + " ".join(cmd), flush=True)
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    with open(os.path.join(out, "ancf-capture.log"), "w") as f:
        f.write(done.stdout)
    with open(os.path.join(out, "events.json")) as f:
        meta = json.load(f)
    with open(os.path.join(out, "samples.csv")) as f:
        rows = list(csv.DictReader(f))
    series = {round(float(r["t"]), 6): (float(r["tilt_deg"]), float(r["ring_angle_deg"])) for r in rows}
    return {"label": label, "meta": meta, "series": series, "status": meta["status"]}


def nan_diff(a, b):
    if a is None or b is None:
        return math.nan
    return abs(a - b)


def compare(r, ref):
    common = sorted(set(r["series"]) & set(ref["series"]))
    tilt = max((abs(r["series"][t][0] - ref["series"][t][0]) for t in common), default=math.nan)
    ring = max((abs(r["series"][t][1] - ref["series"][t][1]) for t in common), default=math.nan)
    e, e0 = r["meta"]["events"], ref["meta"]["events"]
    tensions = max(nan_diff(e[f"tension_at_lock_{i}"], e0[f"tension_at_lock_{i}"]) for i in (1, 2, 3))
    c = r["meta"]["counters"]
    return {
        "label": r["label"], "status": r["status"], "wall_s": r["meta"]["wall_time_s"],
        "steps": c.get("steps", 0), "newton": c.get("Newton iterations", 0),
        "tilt_error_deg": tilt, "ring_error_deg": ring,
        "lock_dt_s": nan_diff(e["lock"], e0["lock"]),
        "ring_at_stall_ddeg": nan_diff(e["ring_angle_at_stall_deg"], e0["ring_angle_at_stall_deg"]),
        "tension_dN": tensions,
        "final_tilt_ddeg": nan_diff(e["final_tilt_deg"], e0["final_tilt_deg"]),
        "lock_s": e["lock"], "first_contacts_s": [e[f"first_contact_rope_{i}"] for i in (1, 2, 3)],
        "all_three_s": e["all_three"],
    }


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--out", default="out/capture-wp")
    p.add_argument("--t-end", type=float, default=0.0)
    p.add_argument("--elements", type=int, default=0)
    p.add_argument("--quick", action="store_true")
    p.add_argument("--only", default="")
    opt = p.parse_args()
    os.makedirs(opt.out, exist_ok=True)
    configs = QUICK if opt.quick else FULL
    if opt.only:
        keep = set(opt.only.split(","))
        configs = [c for c in configs if c[0] in keep]
    print("reference:", flush=True)
    ref = run(*REFERENCE, opt)
    results = [compare(ref, ref)]
    for label, args in configs:
        results.append(compare(run(label, args, opt), ref))
    keys = list(results[0].keys())
    with open(os.path.join(opt.out, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in results:
            w.writerow(r)
    with open(os.path.join(opt.out, "results.json"), "w") as f:
        json.dump({"reference": REFERENCE[0], "t_end": opt.t_end, "elements": opt.elements,
                   "results": results}, f, indent=1, default=str)
    print(f"{'run':<30} {'status':<10} {'wall [s]':>9} {'steps':>8} {'tilt err':>10} "
          f"{'ring err':>10} {'lock dt':>8} {'stall ring':>10} {'tension':>8} {'tilt end':>9}")
    for r in results:
        print(f"{r['label']:<30} {r['status']:<10} {r['wall_s']:9.1f} {r['steps']:8d} "
              f"{r['tilt_error_deg']:10.2e} {r['ring_error_deg']:10.2e} {r['lock_dt_s']:8.3f} "
              f"{r['ring_at_stall_ddeg']:10.3f} {r['tension_dN']:8.2f} {r['final_tilt_ddeg']:9.2e}")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no plot", file=sys.stderr)
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, key, title in ((axes[0], "tilt_error_deg", "pole tilt"),
                           (axes[1], "ring_error_deg", "ring angle")):
        for family, marker in (("genalpha h", "o-"), ("genalpha adaptive", "s-"), ("ida", "^-")):
            pts = [(r[key], r["wall_s"]) for r in results[1:]
                   if r["label"].startswith(family) and r["status"] == "completed"
                   and r[key] > 0 and math.isfinite(r[key])]
            if pts:
                xs, ys = zip(*sorted(pts))
                ax.loglog(xs, ys, marker, label=family.replace(" h", " fixed step"))
        ax.set_xlabel(f"max |{title} - reference| [deg]")
        ax.set_ylabel("wall time [s]")
        ax.set_title(f"capture: {title} history")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(opt.out, "work_precision.png"), dpi=120)
    print("wrote", os.path.join(opt.out, "work_precision.png"))


if __name__ == "__main__":
    main()
