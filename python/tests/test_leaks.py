"""Reference counts and memory over a long loop of loads and runs: nothing accumulates."""

import gc
import sys

import numpy as np

import ancf
from conftest import PENDULUM


def rss_kib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4  # resident pages of 4 KiB


def one_run(scene, keep):
    sim = scene.simulation(method="genalpha", t_end=0.01, genalpha={"step": 2e-3},
                           observer=lambda s: keep.append(float(s.t)))
    sim.run()
    q = sim.q  # a view: keeps sim alive until dropped
    p = sim.probe_dict()
    return float(q[-1]) + float(p["t"][-1]) + len(sim.counters()) + len(sim.metadata())


def test_no_growth_over_many_runs():
    scene = ancf.load(PENDULUM, {"cable[0].elements": 2})
    keep = []
    for _ in range(50):  # warm-up: allocator pools, numpy and json imports
        one_run(scene, keep)
    gc.collect()
    refs, objects, rss = sys.getrefcount(scene), len(gc.get_objects()), rss_kib()
    for _ in range(400):
        one_run(scene, keep)
        try:
            ancf.load(PENDULUM, {"cable[0].section.EA": -1.0})
        except ancf.SceneError:
            pass
    keep.clear()
    gc.collect()
    assert sys.getrefcount(scene) == refs
    assert len(gc.get_objects()) <= objects + 10  # no Python objects left behind
    # 400 runs that each allocate about 100 kB: a leak of one model, state or probe table per
    # run would add tens of MB; allocator noise stays within a few MB.
    assert rss_kib() - rss < 4096


def test_views_keep_the_simulation_alive():
    scene = ancf.load(PENDULUM, {"cable[0].elements": 2, "integrator.t_end": 0.01})
    sim = scene.simulation().run()
    q, expected = sim.q, sim.q.copy()
    refs = sys.getrefcount(sim)
    del sim
    gc.collect()
    np.testing.assert_array_equal(q, expected)  # still valid memory
    assert q.base is not None and refs >= 3
