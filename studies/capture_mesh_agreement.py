#!/usr/bin/env python3
"""Mesh (or integrator) agreement of capture runs: the rope-pole gap histories and the pole-tilt
history of ancf-capture runs (their samples.csv on the same output grid) against the last run
given, up to that run's lock time (events.json), and the events and locked state side by side.

  studies/capture_mesh_agreement.py DIR_12 DIR_24 DIR_48 [--until T]

Issue 16 asks for gaps within 0.5 mm and tilt within 0.1 deg up to the lock over 12/24/48
elements per rope. Only the standard library (no numpy needed)."""
import argparse
import csv
import json
import os


def load(directory):
    with open(os.path.join(directory, "samples.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(directory, "events.json")) as f:
        run = json.load(f)
    return rows, run


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dirs", nargs="+", help="ancf-capture --out directories; the last is the reference")
    parser.add_argument("--until", type=float, help="compare up to this time [s] (default: the reference's lock)")
    a = parser.parse_args()
    runs = [load(d) for d in a.dirs]
    ref_rows, ref_run = runs[-1]
    until = a.until if a.until is not None else ref_run["events"].get("lock")
    if until is None:
        raise SystemExit(f"{a.dirs[-1]}: no lock in events.json; give --until")
    # event key -> format of its cell: times [s] to the 0.01 s output grid and beyond, angles, forces
    formats = {"first_contact_rope_1": ".3f", "first_contact_rope_2": ".3f",
               "first_contact_rope_3": ".3f", "all_three": ".3f", "lock": ".3f",
               "ring_angle_at_stall_deg": ".2f", "tension_at_lock_1": ".2f",
               "tension_at_lock_2": ".2f", "tension_at_lock_3": ".2f", "final_tilt_deg": ".4g"}
    keys = list(formats)
    print("| run | gap max diff [mm] (at t) | tilt max diff [deg] (at t) | " +
          " | ".join(keys) + " | steps | wall [s] |")
    print("|" + "---|" * (len(keys) + 5))
    ref_by_t = {row["t"]: row for row in ref_rows}
    for d, (rows, run) in zip(a.dirs, runs):
        gap, gap_t, tilt, tilt_t = 0.0, None, 0.0, None
        for row in rows:
            t = float(row["t"])
            if t > until + 1e-9:
                break
            ref = ref_by_t.get(row["t"])
            if ref is None:
                continue
            for i in (1, 2, 3):
                g = abs(float(row[f"pole_gap_mm_{i}"]) - float(ref[f"pole_gap_mm_{i}"]))
                if g > gap:
                    gap, gap_t = g, t
            dt = abs(float(row["tilt_deg"]) - float(ref["tilt_deg"]))
            if dt > tilt:
                tilt, tilt_t = dt, t
        ev = run["events"]
        cells = ["-" if ev.get(k) is None else format(ev[k], formats[k]) for k in keys]
        print(f"| {d} | {gap:.3f} ({gap_t}) | {tilt:.4f} ({tilt_t}) | " + " | ".join(cells) +
              f" | {run['counters']['steps']} | {run['wall_time_s']:.1f} |")
    print(f"(histories compared on the common output times up to t = {until} s)")


if __name__ == "__main__":
    main()
