"""Runs: both integrators, bit-for-bit agreement with `ancf run`, stepping, state access,
observers, the GIL, outputs and metadata."""

import json
import subprocess
import threading
import time

import numpy as np
import pytest

import ancf
from conftest import PENDULUM

METHODS = ["ida", "genalpha"]


def read_csv(path):
    lines = path.read_text().splitlines()
    return lines[0].split(","), np.array([[float(x) for x in l.split(",")] for l in lines[1:]])


@pytest.mark.parametrize("method", METHODS)
def test_identical_to_ancf_run(method, tmp_path, small_pendulum_file, executable):
    """The same scene file through `ancf run` and through Python: every output file identical
    byte for byte (probes.csv at full precision, the VTK frames), the same deterministic
    counters, and the in-memory probes equal to the CSV values exactly."""
    cli, py = tmp_path / "cli", tmp_path / "py"
    subprocess.run([executable, "run", str(small_pendulum_file), "--integrator", method,
                    "--quiet", "--out", str(cli)], check=True)
    scene = ancf.load(small_pendulum_file)
    sim = scene.simulation(out=str(py), method=method).run()
    assert sim.status == "completed" and sim.finished and sim.t == 0.05
    assert (py / "probes.csv").read_bytes() == (cli / "probes.csv").read_bytes()
    frames = sorted(p.name for p in (cli / "frames").iterdir())
    assert frames == sorted(p.name for p in (py / "frames").iterdir()) and len(frames) == 6
    for f in frames:
        assert (py / "frames" / f).read_bytes() == (cli / "frames" / f).read_bytes()
    assert (py / "cable_pendulum.pvd").read_bytes() == (cli / "cable_pendulum.pvd").read_bytes()
    columns, values = read_csv(cli / "probes.csv")
    assert columns == sim.probe_columns
    np.testing.assert_array_equal(sim.probes, values)
    a, b = json.loads((cli / "run.json").read_text()), json.loads((py / "run.json").read_text())
    assert a["counters"] == b["counters"] == sim.counters()
    assert a["results"] == b["results"]
    for key in ("ancf_version", "scene", "scene_name", "status"):
        assert a[key] == b[key]
    assert {k: v for k, v in a["options"].items() if k != "out"} == \
        {k: v for k, v in b["options"].items() if k != "out"}
    assert sim.metadata()["counters"] == a["counters"]


@pytest.mark.parametrize("method", METHODS)
def test_stepping_gives_the_same_outputs(method, small_pendulum):
    reference = small_pendulum.simulation(method=method).run()
    sim = small_pendulum.simulation(method=method)
    steps, outputs = 0, 0
    while not sim.finished:
        outputs += sim.step()
        steps += 1
    # IDA: after an output reached by interpolation, the next step() returns the end of the IDA
    # step that passed it (one call without a new step per interior output time).
    extra = 4 if method == "ida" else 0
    assert outputs == 5 and steps == reference.counters()["steps"] + extra
    np.testing.assert_array_equal(sim.probes, reference.probes)
    assert sim.counters() == reference.counters()
    sim2 = small_pendulum.simulation(method=method)
    while sim2.advance():
        pass
    assert not sim2.advance()
    np.testing.assert_array_equal(sim2.probes, reference.probes)


def test_advance_to_between_outputs(small_pendulum):
    ida = small_pendulum.simulation()
    ida.advance_to(0.025)
    assert ida.t == 0.025 and ida.probes.shape[0] == 3  # t = 0, 0.01, 0.02
    ida.run()
    # IDA interpolates at 0.025: its steps and outputs are those of a plain run.
    np.testing.assert_array_equal(ida.probes, small_pendulum.simulation().run().probes)
    ga = small_pendulum.simulation(method="genalpha")
    ga.advance_to(0.0255)
    assert ga.t == 0.0255
    with pytest.raises(ValueError):
        ga.advance_to(0.01)
    with pytest.raises(ValueError):
        ga.advance_to(1.0)


@pytest.mark.parametrize("method", METHODS)
def test_state_views_and_set_state(method, small_pendulum):
    sim = small_pendulum.simulation(method=method)
    n, m = small_pendulum.info()["coordinates"], small_pendulum.info()["multipliers"]
    q, v, a, lam = sim.q, sim.v, sim.a, sim.lam
    assert q.shape == v.shape == a.shape == (n,) and lam.shape == (m,)
    assert not q.flags.writeable and not q.flags.owndata  # a view, not a copy
    with pytest.raises(ValueError):
        q[0] = 1.0
    q0 = q.copy()
    sim.advance()
    assert sim.t == 0.01 and not np.array_equal(q, q0)  # the view follows the run
    np.testing.assert_array_equal(q, sim.q)
    # Restart from the initial state at t = 0.01: the pendulum starts again from rest there.
    sim.set_state(q=small_pendulum.q0, v=np.zeros(n))
    np.testing.assert_allclose(sim.q, small_pendulum.q0, atol=1e-12)
    assert np.abs(sim.v).max() < 1e-12
    assert sim.constraint_violation()["position"] < 1e-12
    sim.run()
    # Same motion, shifted by 0.01 s: the tip at t_end matches the plain run at t_end − 0.01.
    plain = small_pendulum.with_overrides(t_end=0.04).simulation(method=method).run()
    assert sim.probe_dict()["tip.z"][-1] == pytest.approx(plain.probe_dict()["tip.z"][-1],
                                                           rel=1e-3)
    with pytest.raises(ValueError, match="30 values"):
        sim.set_state(q=np.zeros(3))


def test_observer_at_every_output_and_stop(small_pendulum):
    seen = []
    sim = small_pendulum.simulation(observer=lambda s: seen.append((s.t, s.q[-4])))
    sim.run()
    assert [t for t, _ in seen] == [0.0, 0.01, 0.02, 0.03, 0.04, 0.05]
    np.testing.assert_array_equal([z for _, z in seen], sim.probe_dict()["tip.z"])

    class Stop(Exception):
        pass

    def stop_at_002(s):
        if s.t >= 0.02:
            raise Stop(s.t)

    stopped = small_pendulum.simulation(observer=stop_at_002)
    with pytest.raises(Stop):
        stopped.run()
    assert stopped.status == "stopped" and stopped.t == 0.02 and stopped.probes.shape[0] == 3
    stopped.observer = None  # resume without it: the rest of the run is unchanged
    stopped.run()
    np.testing.assert_array_equal(stopped.probes, sim.probes)


def test_gil_released_while_integrating(small_pendulum):
    """Another Python thread runs while C++ integrates (one output interval at a time)."""
    # 20 elements; one output interval of 0.05 s (IDA: thousands of steps, tens of ms now that its
    # vector work is compiled with the project)
    scene = ancf.load(PENDULUM, {"integrator.t_end": 0.1, "output.interval": 0.05})
    ticks, done = [], threading.Event()

    def ticker():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    sim = scene.simulation()
    thread = threading.Thread(target=ticker)
    thread.start()
    start = time.perf_counter()
    sim.advance()  # 0.05 s of the 20-element pendulum with IDA
    elapsed = time.perf_counter() - start
    done.set()
    thread.join()
    during = [t for t in ticks if start <= t <= start + elapsed]
    assert elapsed > 0.02, "the interval must be long enough to see the thread run"
    assert len(during) >= 5


def test_counters_metadata_and_failure(small_pendulum, tmp_path):
    sim = small_pendulum.simulation()
    assert sim.method == "ida" and sim.status == "running" and sim.failure is None
    meta = sim.metadata()
    assert meta["status"] == "running" and meta["scene_name"] == "cable_pendulum"
    sim.run()
    c = sim.counters()
    assert c["steps"] > 0 and set(c) >= {"Newton iterations", "Jacobian evaluations"}
    assert sim.timings()["wall"] > 0.0
    e = sim.energies()
    assert e["total"] == pytest.approx(e["kinetic"] + e["potential"])
    # Energy is conserved by the undamped pendulum up to the integration tolerance.
    assert abs(e["total"] - sim.probe_dict()["energy.total"][0]) < 1e-3 * abs(e["load"])
    assert sim.scene.name == "cable_pendulum"


def test_solver_failure_is_raised_with_its_report(small_pendulum, tmp_path):
    """Error-controlled generalized-α with an unreachable tolerance at h = h_min fails on its
    first step: SolverError with time, step size and steps; the results so far stay readable and
    run.json records the failure."""
    scene = small_pendulum.with_overrides(method="genalpha", genalpha={
        "stepping": "error_controlled", "error_rtol": 1e-14, "error_atol": 1e-16,
        "step": 1e-3, "h_min": 1e-3})
    sim = scene.simulation(out=str(tmp_path / "failed"))
    with pytest.raises(ancf.SolverError) as e:
        sim.run()
    err = e.value
    assert err.time == 0.0 and err.step_size == 1e-3 and err.steps == 0
    assert "h_min" in str(err) and isinstance(err.component, str)
    assert sim.status == "failed" and sim.failure["time"] == 0.0
    assert sim.probes.shape[0] == 1 and sim.t == 0.0  # the state at t = 0 is kept
    record = json.loads((tmp_path / "failed" / "run.json").read_text())
    assert record["status"] == "failed" and "h_min" in record["message"]
    with pytest.raises(ancf.ModelError, match="failed earlier"):
        sim.advance()


def test_newton_failure_names_the_component(small_pendulum):
    """A fixed-step generalized-α run whose Newton cannot converge even after halvings: the
    report names the unknown with the largest increment."""
    scene = small_pendulum.with_overrides({"integrator.genalpha.atol_position": 1e-300,
                                           "integrator.genalpha.atol_velocity": 1e-300,
                                           "integrator.genalpha.atol_multiplier": 1e-300,
                                           "integrator.rtol": 1e-300},
                                          method="genalpha")
    with pytest.raises(ancf.SolverError) as e:
        scene.simulation().run()
    assert e.value.component == "constraint 'pivot' row 2"
    assert e.value.time == 0.0 and e.value.step_size < 1e-3


def test_run_function_and_outputs(tmp_path, small_pendulum_file):
    sim = ancf.run(str(small_pendulum_file), out=str(tmp_path / "o"), method="genalpha")
    assert sim.method == "genalpha" and (tmp_path / "o" / "run.json").exists()
    (tmp_path / "o" / "run.json").unlink()
    sim.write_record()
    assert json.loads((tmp_path / "o" / "run.json").read_text())["status"] == "completed"
    d = sim.probe_dict()
    assert list(d) == sim.probe_columns and d["t"][-1] == 0.05
