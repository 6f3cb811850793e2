#!/usr/bin/python3
"""Overhead of the Python module against `ancf run` (docs/python.md, issue 18).

1. The benchmark pendulum (studies/scenes/cable_pendulum.toml, REFERENCES §10: 20 elements,
   t in [0, 1] s, output every 0.01 s) with IDA and generalized-α, each run writing the same
   outputs (probes.csv, VTK frames, run.json): `ancf run` as a child process against
   ancf.run() in this process. Measured as CPU time (the child's from getrusage, this process's
   from time.process_time; robust on a shared machine) and as wall time, the best of REPEATS
   alternating runs each. Python's time includes loading the scene; `ancf run`'s includes
   process start-up.
2. A per-step observer: generalized-α on the pendulum with 2 elements for 5 s, the output
   interval equal to the step (5 000 outputs), with no observer, an observer that does nothing, and one that reads the tip
   height through the q view; cost per call = (difference in CPU time) / calls.

Usage: PYTHONPATH=build-release/python studies/python_overhead.py [build-release/src/app/ancf]
       [--repeats N]
"""

import argparse
import os
import pathlib
import resource
import subprocess
import sys
import tempfile
import time

import ancf

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENE = ROOT / "studies" / "scenes" / "cable_pendulum.toml"


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def cli_run(exe, scene, method, out):
    c0, w0 = child_cpu(), time.perf_counter()
    subprocess.run([exe, "run", str(scene), "--integrator", method, "--quiet", "--out", out],
                   check=True)
    return child_cpu() - c0, time.perf_counter() - w0


def python_run(scene_path, method, out, observer=None, overrides=None):
    c0, w0 = time.process_time(), time.perf_counter()
    scene = ancf.load(scene_path, dict(overrides or {}, **{"integrator.method": method}))
    sim = ancf.Simulation(scene, out=out, observer=observer).run()
    assert sim.status == "completed"
    return time.process_time() - c0, time.perf_counter() - w0, sim


def main():
    p = argparse.ArgumentParser()
    p.add_argument("exe", nargs="?", default=str(ROOT / "build-release" / "src" / "app" / "ancf"))
    p.add_argument("--repeats", type=int, default=3)
    a = p.parse_args()
    print(f"ancf {ancf.__version__}, {SCENE.name}, best of {a.repeats} (CPU s / wall s)")
    with tempfile.TemporaryDirectory() as tmp:
        # The same scene without VTK frames (probes.csv and run.json only): the integration
        # without the file-system time of 101 frames, which dominates the wall time of
        # generalized-α and varies most on a shared machine.
        no_vtk = pathlib.Path(tmp) / "cable_pendulum_no_vtk.toml"
        no_vtk.write_text(ancf.load(SCENE, {"output.vtk": False}).toml())
        for scene, method in ((SCENE, "ida"), (SCENE, "genalpha"), (no_vtk, "genalpha")):
            cli, py = [], []
            for k in range(a.repeats):
                cli.append(cli_run(a.exe, scene, method, os.path.join(tmp, f"cli{k}")))
                py.append(python_run(scene, method, os.path.join(tmp, f"py{k}"))[:2])
            same = all((pathlib.Path(tmp) / f"cli{k}" / "probes.csv").read_bytes() ==
                       (pathlib.Path(tmp) / f"py{k}" / "probes.csv").read_bytes()
                       for k in range(a.repeats))
            c_cpu, c_wall = min(c for c, _ in cli), min(w for _, w in cli)
            p_cpu, p_wall = min(c for c, _ in py), min(w for _, w in py)
            label = method + (" no VTK" if scene == no_vtk else "")
            print(f"{label:16s} ancf run {c_cpu:7.3f} / {c_wall:7.3f}   python {p_cpu:7.3f} / "
                  f"{p_wall:7.3f}   python/ancf run: CPU {100 * (p_cpu / c_cpu - 1):+6.2f} %, "
                  f"wall {100 * (p_wall / c_wall - 1):+6.2f} %   probes.csv identical: {same}")

        # Two elements and 5 s: 5 000 steps, cheap enough that the observer's share is visible.
        per_step = {"output.interval": 1e-3, "output.vtk": False, "cable[0].elements": 2,
                    "integrator.t_end": 5.0}
        tip = []
        cases = [("no observer", None), ("observer: pass", lambda s: None),
                 ("observer: reads q[-4]", lambda s: tip.append(s.q[-4]))]
        best = {}
        for name, observer in cases * a.repeats:
            cpu, wall, sim = python_run(SCENE, "genalpha", None, observer, per_step)
            calls = sim.probes.shape[0]
            best[name] = min(best.get(name, (1e9, 0))[0], cpu), calls
        base = best["no observer"][0]
        for name, (cpu, calls) in best.items():
            extra = (cpu - base) / calls * 1e6
            print(f"genalpha, 2 elements, {calls} outputs, {name:24s} CPU {cpu:7.3f} s"
                  + ("" if name == "no observer" else f"   {extra:+7.2f} µs per call"))


if __name__ == "__main__":
    sys.exit(main())
