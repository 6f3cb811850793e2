"""ancf-capture --fast: the preset's generalized-alpha settings reach the run (events.json), flags
given explicitly take precedence, and the preset is refused with IDA. --scene-set: a scene key by
its path from the root reaches the run and is recorded; a bad value is refused naming the key.
Usage: capture_preset_test.py ANCF_CAPTURE SOURCE_DIR OUT_DIR"""
import json
import subprocess
import sys

capture, source, out = sys.argv[1:4]


def run(*args):
    return subprocess.run([capture, *args], cwd=source, capture_output=True, text=True)


r = run("--fast", "--t-end", "0.05", "--out", out + "/fast")
assert r.returncode == 0, r.stderr
o = json.load(open(out + "/fast/events.json"))["options"]
expected = {"fast": True, "genalpha_stepping": "error_controlled", "rtol": 1e-4, "rho_infinity": 0.5,
            "cable_tangent": "tension_only", "genalpha_ceiling_rate": 0.3}
for key, value in expected.items():
    assert o[key] == value, (key, o[key], value)

r = run("--fast", "--rho-inf", "0.3", "--set", "genalpha.ceiling_rate=0.2", "--t-end", "0.02",
        "--out", out + "/fast_override")
assert r.returncode == 0, r.stderr
o = json.load(open(out + "/fast_override/events.json"))["options"]
assert o["rho_infinity"] == 0.3 and o["genalpha_ceiling_rate"] == 0.2, o

r = run("--fast", "--integrator", "ida", "--t-end", "0.02", "--out", out + "/fast_ida")
assert r.returncode != 0 and "--fast" in r.stderr, (r.returncode, r.stderr)
r = run("--scene-set", "integrator.genalpha.step=5e-4", "--t-end", "0.01", "--out", out + "/scene_set")
assert r.returncode == 0, r.stderr
o = json.load(open(out + "/scene_set/events.json"))["options"]
assert o["step"] == 5e-4 and o["scene_set"] == {"integrator.genalpha.step": "5e-4"}, o

r = run("--scene-set", "cable[0].grading.end_ratio=2.0", "--t-end", "0.01", "--out", out + "/bad")
assert r.returncode != 0 and "cable[0].grading.end_ratio" in r.stderr, (r.returncode, r.stderr)
print("ok")
