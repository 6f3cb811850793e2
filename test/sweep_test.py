"""`ancf sweep` end to end on a tiny scene (test/scenes/sweep/): worker processes and MPI give the
same table; a sweep killed mid-way resumes without rerunning finished cases; failing cases (the
scene rejects a value, the time limit, a crashing process, a solver failure) are recorded with
their messages and do not stop the good ones.
Usage: sweep_test.py ANCF WORKDIR {mpi MPIRUN | resume | failing}"""
import csv
import os
import shutil
import signal
import subprocess
import sys
import time

ANCF, WORK, WHAT = sys.argv[1], sys.argv[2], sys.argv[3]
HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes", "sweep")


def sweep(name, out, *extra, launcher=(), env=None):
    shutil.rmtree(out, ignore_errors=True)
    cmd = [*launcher, ANCF, "sweep", os.path.join(HERE, name), "--out", out, *extra]
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    assert r.returncode == 0, f"{cmd} exited {r.returncode}:\n{r.stdout}\n{r.stderr}"
    return r.stdout


def table(out, drop=("wall_s",)):
    with open(os.path.join(out, "results.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    return [{k: v for k, v in row.items() if k not in drop} for row in rows]


def check(ok, what):
    if not ok:
        sys.exit("FAILED: " + what)


os.makedirs(WORK, exist_ok=True)
if WHAT == "mpi":
    mpirun = sys.argv[4]
    sweep("grid.toml", os.path.join(WORK, "w"), "-j", "2")
    sweep("grid.toml", os.path.join(WORK, "m"),
          launcher=(mpirun, "--oversubscribe", "--allow-run-as-root", "-n", "2"))
    w, m = table(os.path.join(WORK, "w")), table(os.path.join(WORK, "m"))
    check(len(w) == 6 and all(r["status"] == "completed" for r in w), f"6 completed cases: {w}")
    check([r["case"] for r in w] == [str(k) for k in range(6)], "table sorted by case")
    check(w == m, f"worker-process and MPI tables differ:\n{w}\n{m}")
    # The counters differ between cases (E and g change the dynamics), so equal tables are not trivial.
    check(len({r["counters.Newton iterations"] for r in w}) > 1, "cases differ")
    check('"mode": "mpi"' in open(os.path.join(WORK, "m", "run.json")).read(), "run.json mode mpi")
elif WHAT == "resume":
    ref = os.path.join(WORK, "ref")
    sweep("resume.toml", ref, "-j", "1")
    out = os.path.join(WORK, "killed")
    shutil.rmtree(out, ignore_errors=True)
    p = subprocess.Popen([ANCF, "sweep", os.path.join(HERE, "resume.toml"), "--out", out, "-j", "1"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    csv_path = os.path.join(out, "results.csv")
    deadline = time.time() + 60
    while time.time() < deadline:
        if os.path.exists(csv_path) and len(open(csv_path).read().splitlines()) >= 2:
            break
        time.sleep(0.005)
    p.send_signal(signal.SIGKILL)
    p.wait()
    before = table(out)
    check(1 <= len(before) < 6, f"killed after the first case and before the last: {len(before)} rows")
    first = os.path.join(out, "cases", "case-%04d" % int(before[0]["case"]), "results.toml")
    stamp = os.stat(first).st_mtime_ns
    time.sleep(0.02)
    r = subprocess.run([ANCF, "sweep", os.path.join(HERE, "resume.toml"), "--out", out, "-j", "1"],
                       capture_output=True, text=True)
    check(r.returncode == 0, r.stderr)
    check(f"{len(before)} already finished, {6 - len(before)} to run" in r.stdout, r.stdout)
    check(os.stat(first).st_mtime_ns == stamp, "a finished case was rerun")
    check(table(out) == table(ref), "resumed table differs from an uninterrupted sweep")
elif WHAT == "failing":
    env = dict(os.environ, ANCF_REAL=ANCF)
    out = os.path.join(WORK, "failing")
    sweep("failing.toml", out, "-j", "2", "--ancf", os.path.join(HERE, "crashing_ancf.sh"), env=env)
    rows = {r["note"]: r for r in table(out)}
    statuses = [r["status"] for r in table(out)]
    check(statuses == ["completed", "error", "timeout", "crashed", "failed", "completed"],
          f"statuses {statuses}")
    check("cable[0].section.E" in rows["bad E"]["message"], rows["bad E"]["message"])
    check("time limit" in rows["too long"]["message"], rows["too long"]["message"])
    check("signal 11" in rows["crash me"]["message"], rows["crash me"]["message"])
    failed = rows["solver fails"]["message"]
    check("local error estimate" in failed and "h_min" in failed, failed)
    check(rows["solver fails"]["t_reached"] == "0", f"solver failure at t = 0: {rows['solver fails']}")
    check(rows["good"]["counters.steps"] == "50", "good cases ran to the end")
else:
    sys.exit("unknown test " + WHAT)
print("OK", WHAT)
