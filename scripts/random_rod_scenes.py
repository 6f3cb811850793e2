#!/usr/bin/env python3
"""Random Kirchhoff-rod scenes through every `ancf` command: a smoke test of the failure paths.

Usage: scripts/random_rod_scenes.py [--ancf PATH] [--first N] [--count N] [--timeout S]
                                    [--out DIR] [--keep]

Each seed gives one small scene (standard library only; reproducible from the seed): a rod of
1-10 elements on a straight, polyline, arc or helix reference, random stiffnesses over six decades,
optional damping and grading, the three strain/twist variants, clamped / pinned / twist-fixed ends,
up to three nodal forces, nodal moments or distributed moments (many far beyond what the rod can
carry), generalized-alpha (fixed or error-controlled steps) or IDA, and 1, 10 or 100 outputs.
It runs `ancf check`, `ancf static`, `ancf modes --static` and `ancf run` on it. Refusals (exit 1)
and reported solver failures (exit 2) are expected outcomes of such scenes, unless the report is a
SUNDIALS flag for a caller's misuse of IDA; what this looks for is everything else: an abort or
uncaught exception (exit codes other than 0, 1, 2; "terminate called"), a sanitizer report (run it
with a build of `scripts/test --sanitize`), and runs that do not end within --timeout seconds
(reported separately: a violent scene on IDA may legitimately need millions of steps; look at them
by hand). The reasons of the reported failures are tallied.

Exit status 1 when anything odd was found. docs/fuzzing.md, "Random rod scenes", records runs.
"""
import argparse
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile


def vec(values):
    return "[%s]" % ", ".join("%.6g" % v for v in values)


def magnitude(rng):
    """A signed factor over seven decades (1e-3 ... 1e4)."""
    return 10 ** rng.uniform(-3, 4) * rng.choice([1, -1])


def scene(seed):
    rng = random.Random(seed)
    n = rng.randint(1, 10)
    length = 10 ** rng.uniform(-1.5, 0.5)
    lines = ["[scene]", 'name = "random_rod_%d"' % seed]
    if rng.random() < 0.5:
        lines.append("gravity = [0.0, 0.0, -9.81]")
    lines += ["[[rod]]", 'name = "r"', "elements = %d" % n]
    kind = rng.choice(["straight", "arc", "helix", "polyline"])
    if kind == "straight":
        lines.append('geometry = { kind = "straight", start = [0.0, 0.0, 0.0], '
                     "end = [%g, 0.0, 0.0] }" % length)
        lines.append("frame = { normal = [0.0, 1.0, 0.0] }")
    elif kind == "polyline":
        lines.append('geometry = { kind = "polyline", points = [[0.0, 0.0, 0.0], [%g, 0.0, 0.0], '
                     "[%g, %g, %g]] }" % (length, 1.5 * length, 0.3 * length, 0.2 * length))
        lines.append("frame = { normal = [0.0, 0.0, 1.0] }")
    elif kind == "arc":
        lines.append('geometry = { kind = "arc", u = [1.0, 0.0, 0.0], w = [0.0, 1.0, 0.0], '
                     "radius = %g, angle = %g }" % (length, rng.uniform(0.3, 6.0)))
    else:
        lines.append('geometry = { kind = "helix", radius = %g, twist = %g, rise = %g }'
                     % (length, rng.uniform(1, 15), rng.uniform(0, 2) * length))
    if kind != "polyline" and rng.random() < 0.3:
        lines.append("grading = { end_ratio = %g, end_length = %g }"
                     % (rng.uniform(0.1, 1), length * rng.uniform(0.05, 0.5)))
    ei = 10 ** rng.uniform(-4, 2)
    lines += ["[rod.section]",
              "EA = %g" % (ei * 10 ** rng.uniform(2, 8) / length ** 2),
              "EI2 = %g" % ei, "EI3 = %g" % (ei * rng.uniform(0.5, 2)),
              "GJ = %g" % (ei * rng.uniform(0.3, 2)),
              "mass_per_length = %g" % 10 ** rng.uniform(-2, 1)]
    if rng.random() < 0.5:
        lines.append("polar_inertia = %g" % 10 ** rng.uniform(-9, -2))
    else:
        lines.append("radius = %g" % (0.01 * length))
    for key in ("axial_damping", "torsional_damping", "bending_damping"):
        if rng.random() < 0.3:
            lines.append("%s = %g" % (key, 10 ** rng.uniform(-5, 0)))
    for key, values in (("twist_interpolation", ("quadratic", "linear")),
                        ("axial_strain", ("collocated", "gauss_points")),
                        ("torsion_strain", ("projected", "gauss_points"))):
        if rng.random() < 0.3:
            lines.append('%s = "%s"' % (key, rng.choice(values)))
    ends = rng.choice(["clamp", "clamp_both", "pin_both", "pin_twist"])
    lines += ["[[joint]]", 'kind = "%s"' % ("pin" if ends == "pin_both" else "clamp"),
              'name = "a"', 'at = { cable = "r", node = 0 }']
    if ends != "clamp":
        lines += ["[[joint]]", 'kind = "%s"' % ("clamp" if ends == "clamp_both" else "pin"),
                  'name = "b"', 'at = { cable = "r", node = -1 }']
    if ends == "pin_both":
        lines += ["[[joint]]", 'kind = "fix_twist"', 'name = "c"',
                  'at = { cable = "r", node = %d }' % rng.randint(0, n)]
    for i in range(rng.randint(0, 3)):
        load = rng.choice(["moment", "distributed", "force"])
        node = 'at = { cable = "r", node = %d }' % rng.randint(-n - 1, n)
        if load == "moment":
            value = [magnitude(rng) * ei / length for _ in range(3)]
            lines += ["[[load]]", 'kind = "moment"', 'name = "m%d"' % i, node,
                      "moment = %s" % vec(value)]
        elif load == "distributed":
            value = [magnitude(rng) * ei / length ** 2 for _ in range(3)]
            lines += ["[[load]]", 'kind = "distributed"', 'name = "d%d"' % i, 'cable = "r"',
                      "moment = %s" % vec(value)]
        else:
            value = [magnitude(rng) * ei / length ** 2 for _ in range(3)]
            lines += ["[[load]]", 'kind = "force"', 'name = "f%d"' % i, node,
                      "force = %s" % vec(value)]
    method = rng.choice(["genalpha", "ida"])
    t_end = 10 ** rng.uniform(-3, -1)
    lines += ["[integrator]", 'method = "%s"' % method, "t_end = %g" % t_end,
              "rod_frame_turn = %g" % rng.choice([0, 0.1, 2])]
    if method == "genalpha":
        lines += ["[integrator.genalpha]", "step = %g" % min(t_end, 10 ** rng.uniform(-5, -2))]
    # Up to 100 outputs: IDA's steps then span several output times (interpolation paths).
    lines += ["[output]", "interval = %g" % (t_end / rng.choice([1, 10, 100])), "vtk = false",
              "[[output.probe]]",
              'kind = "rod"', 'at = { cable = "r", node = -1 }', 'label = "tip"']
    # Drawn after everything else, so that a seed's scene is otherwise what it was before.
    stepping = rng.choice(["fixed", "error_controlled"])
    if method == "genalpha":
        at = lines.index("[integrator.genalpha]") + 1
        lines.insert(at, 'stepping = "%s"' % stepping)
    return "\n".join(lines) + "\n"


# SUNDIALS return flags that mean the caller used IDA wrongly (an output time outside the last
# step, bad input, memory not set up), whatever the scene.
DRIVER_MISUSE = ("IDA_BAD_T", "IDA_ILL_INPUT", "IDA_MEM_NULL", "IDA_NO_MALLOC", "IDA_BAD_K",
                 "IDA_BAD_DKY")


def failure_reason(stderr):
    """The gist of a reported failure: its first line, numbers and names replaced."""
    line = next((l for l in stderr.splitlines() if "failed" in l or "error" in l),
                stderr.strip().splitlines()[0] if stderr.strip() else "")
    return re.sub(r"'[^']*'", "'…'", re.sub(r"[-+]?\d[\d.eE+-]*", "#", line.strip()))[:110]


COMMANDS = (("check", []), ("static", ["--quiet"]), ("modes", ["--static", "--no-vtk"]),
            ("run", ["--quiet"]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ancf", default="build-release/src/app/ancf")
    parser.add_argument("--first", type=int, default=0)
    parser.add_argument("--count", type=int, default=50)
    parser.add_argument("--timeout", type=float, default=60.0)
    parser.add_argument("--out", help="directory for the scenes and outputs (default: temporary)")
    parser.add_argument("--keep", action="store_true", help="keep the outputs of clean seeds too")
    args = parser.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="random_rod_scenes_")
    counts, reasons = {}, {}
    odd, slow = [], []
    for seed in range(args.first, args.first + args.count):
        directory = os.path.join(out, str(seed))
        os.makedirs(directory, exist_ok=True)
        path = os.path.join(directory, "scene.toml")
        with open(path, "w") as f:
            f.write(scene(seed))
        clean = True
        for command, extra in COMMANDS:
            argv = [args.ancf, command, path] + extra
            if command != "check":
                argv += ["--out", os.path.join(directory, command)]
            try:
                r = subprocess.run(argv, capture_output=True, text=True, timeout=args.timeout)
                code, stderr = r.returncode, r.stderr
            except subprocess.TimeoutExpired:
                slow.append((seed, command))
                counts[(command, "timeout")] = counts.get((command, "timeout"), 0) + 1
                clean = False
                continue
            outcome = {0: "completed", 1: "refused", 2: "failed (reported)"}.get(code, "odd")
            if ("terminate called" in stderr or "Sanitizer" in stderr
                    or "runtime error" in stderr):
                outcome = "odd"
            if any(flag in stderr for flag in DRIVER_MISUSE):
                outcome = "odd"  # the driver misused IDA: not a property of the scene
            if outcome == "failed (reported)":
                reason = failure_reason(stderr)
                reasons[(command, reason)] = reasons.get((command, reason), 0) + 1
            counts[(command, outcome)] = counts.get((command, outcome), 0) + 1
            if outcome == "odd":
                odd.append((seed, command, code, stderr.strip()[-400:]))
                clean = False
            if command == "check" and code != 0:
                break  # refused scenes are not run
        if clean and not args.keep:
            shutil.rmtree(directory)
    for command, _ in COMMANDS:
        row = ", ".join("%s %d" % (o, counts[(command, o)])
                        for o in ("completed", "refused", "failed (reported)", "timeout", "odd")
                        if (command, o) in counts)
        print("%-7s %s" % (command, row))
    for (command, reason), n in sorted(reasons.items(), key=lambda x: (x[0][0], -x[1])):
        print("  %s failed %d x: %s" % (command, n, reason))
    for seed, command in slow:
        print("slow: seed %d, ancf %s (> %g s): %s" % (seed, command, args.timeout,
                                                      os.path.join(out, str(seed))))
    for seed, command, code, stderr in odd:
        print("ODD: seed %d, ancf %s, exit %s: %s" % (seed, command, code, stderr))
    print("scenes and outputs of flagged seeds: %s" % out)
    return 1 if odd else 0


if __name__ == "__main__":
    sys.exit(main())
