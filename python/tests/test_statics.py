"""Statics and modes through the library's solvers, on builder scenes."""

import numpy as np
import pytest

import ancf

# Mattiasson (1981), k = P L²/EI = 1: tip shortening u/L, deflection w/L, rotation [rad]
# (REFERENCES §1; test/test_statics_reference.cpp runs the same case in C++).
MATTIASSON_K1 = (0.05643324, 0.30172077, 0.46135195)
# First clamped-free Euler–Bernoulli eigenvalue (βL)² = 1.87510406871196².
BETA1_SQUARED = 1.87510406871196**2


def cantilever(elements, tip_force=0.0, gravity=0.0):
    """L = 1 m, EI = 1 N m², EA = 1e7 N (EA L²/EI = 1e7: extensibility error O(P/EA) ~ 1e-7),
    ρA = 1 kg/m, clamped at x = 0."""
    b = ancf.SceneBuilder("cantilever", gravity=[0.0, 0.0, gravity])
    b.cable(name="beam", elements=elements,
            geometry={"kind": "straight", "start": [0, 0, 0], "end": [1, 0, 0]},
            section={"EA": 1e7, "EI": 1.0, "mass_per_length": 1.0})
    b.joint(name="root", kind="clamp", at={"cable": "beam", "node": 0})
    if tip_force:
        b.load(kind="force", at={"cable": "beam", "node": -1}, force=[0.0, -tip_force, 0.0])
    return b.build()


def test_mattiasson_cantilever():
    """64 elements, as the C++ reference test: relative errors below its 1e-5 target."""
    n = 64
    r = ancf.solve_statics(cantilever(n, tip_force=1.0), load_steps=4)
    q = r["q"]
    tip, slope = q[6 * n:6 * n + 3], q[6 * n + 3:6 * n + 6]
    u, w, rotation = 1.0 - tip[0], -tip[1], np.arctan2(-slope[1], slope[0])
    for value, ref in zip((u, w, rotation), MATTIASSON_K1):
        assert abs(value - ref) < 1e-5 * ref
    assert tip[2] == 0.0  # planar
    s = r["statistics"]
    assert s["load_steps"] == 4 and s["newton_iterations"] > 0 and s["residual_norm"] < 1e-6
    assert r["lam"].shape == (5,)  # clamp: position and slope direction


def test_natural_modes_converge_at_fourth_order():
    """The first bending frequency of the clamped beam against Euler–Bernoulli: cubic Hermite
    elements converge as h⁴ (a factor 16 per halving, observed 15.7 and 15.9)."""
    errors = []
    for n in (4, 8, 16):
        m = ancf.natural_modes(cantilever(n), component=1)
        errors.append(abs(m["omega"][0] - BETA1_SQUARED) / BETA1_SQUARED)
        coords = cantilever(n).info()["coordinates"]
        assert m["shapes"].shape[0] == coords
        assert m["frequency_hz"][0] == pytest.approx(m["omega"][0] / (2 * np.pi))
        assert np.all(np.diff(m["omega_squared"]) >= 0)
    for coarse, fine in zip(errors, errors[1:]):
        assert 12.0 < coarse / fine < 20.0  # order 4 within ±0.4 of the exponent


def test_modes_at_a_static_equilibrium():
    """A hanging cantilever under gravity: modes at the solved equilibrium (q and λ)."""
    scene = cantilever(8, gravity=-1.0)
    eq = ancf.solve_statics(scene, load_steps=2)
    m = ancf.natural_modes(scene, q=eq["q"], lam=eq["lam"])
    assert m["omega"][0] > 0 and m["constraint_rank"] == 5
    with pytest.raises(ValueError, match="q"):
        ancf.natural_modes(scene, q=np.zeros(3))


def test_singular_statics_is_a_solver_error():
    b = ancf.SceneBuilder("free", gravity=[0.0, 0.0, -9.81])
    b.cable(name="c", elements=2, geometry={"kind": "straight", "start": [0, 0, 0],
                                            "end": [1, 0, 0]},
            section={"EA": 1e3, "EI": 1.0, "mass_per_length": 1.0})
    with pytest.raises(ancf.SolverError, match="singular") as e:
        ancf.solve_statics(b.build())
    assert e.value.time is None and "cable 'c'" in str(e.value)


def test_rod_quarter_circle_out_of_plane():
    """A quarter-circle rod (R = 1, EI = 1, GJ = 0.7) clamped with its twist, small tip force
    normal to its plane: δ = F R³ [π/(4EI) + (3π/4 − 2)/GJ] (Castigliano; docs/rod.md measures
    −1.4e-6 at 16 elements with the quadratic twist, which this must reproduce through Python).
    A torsion-free cable has no stiffness against this load."""
    n, force = 16, 1e-7
    b = ancf.SceneBuilder("quarter circle")
    b.rod(name="arc", elements=n,
          geometry={"kind": "arc", "centre": [0, 0, 0], "u": [1, 0, 0], "w": [0, 1, 0],
                    "radius": 1.0, "angle": np.pi / 2},
          section={"EA": 1e7, "EI": 1.0, "GJ": 0.7, "mass_per_length": 1.0,
                   "polar_inertia": 1e-3})
    b.joint(name="root", kind="clamp", at={"cable": "arc", "node": 0})
    b.load(kind="force", at={"cable": "arc", "node": -1}, force=[0.0, 0.0, force])
    q = ancf.solve_statics(b.build(), load_steps=1)["q"]
    twist_block = 2 * (n + 1) - 1  # node angles and one interior twist per element, first
    tip_z = q[twist_block + 6 * n + 2]
    exact = force * (np.pi / 4 + (0.75 * np.pi - 2) / 0.7)
    assert abs(tip_z / exact - 1.0) < 1e-5


def test_rod_uniform_distributed_torque():
    """A straight rod (L = 2, GJ = 2) clamped with its twist under a uniform distributed torque
    m = 1 N m/m along its axis ([[load]] kind = "distributed", moment): φ(s) = m(Ls − s²/2)/GJ,
    1 rad at the tip, which the quadratic twist holds exactly (test_distributed_load: 1e-16)."""
    n, length, gj, m = 3, 2.0, 2.0, 1.0
    b = ancf.SceneBuilder("twisted by a distributed torque")
    b.rod(name="shaft", elements=n,
          geometry={"kind": "straight", "start": [0, 0, 0], "end": [length, 0, 0]},
          frame={"normal": [0, 1, 0]},
          section={"EA": 1e7, "EI": 3.0, "GJ": gj, "mass_per_length": 1.0,
                   "polar_inertia": 1e-3})
    b.joint(name="root", kind="clamp", at={"cable": "shaft", "node": 0})
    b.load(kind="distributed", cable="shaft", moment=[m, 0.0, 0.0])
    q = ancf.solve_statics(b.build(), load_steps=1)["q"]
    s = np.linspace(0.0, length, n + 1)
    node_angles = q[: n + 1]  # the twist block comes first: node angles, then interior twists
    assert np.max(np.abs(node_angles - m * (length * s - 0.5 * s * s) / gj)) < 1e-12


def test_rod_modes_about_a_static_solution_use_its_frames(tmp_path, executable):
    """A rod turned into a two-turn helix by an inclined end moment: its static q holds twist
    angles relative to frames the solver updated on the way, returned as 'rod_frames'. The modes
    about that state with them equal `ancf modes --static` (the same computation); without them
    (the reference frames) they do not (until 2026-12-06 that was the only way)."""
    import subprocess

    from conftest import SOURCE

    scene_file = SOURCE / "test" / "scenes" / "statics" / "rod_helix_moment.toml"
    scene = ancf.load(scene_file)
    static = ancf.solve_statics(scene, load_steps=40)
    assert isinstance(static["rod_frames"], ancf.RodFrames)
    with_frames = ancf.natural_modes(scene, static["q"], static["lam"],
                                     rod_frames=static["rod_frames"])["omega_squared"]
    without = ancf.natural_modes(scene, static["q"], static["lam"])["omega_squared"]
    subprocess.run([executable, "modes", str(scene_file), "--static", "--load-steps", "40",
                    "--no-vtk", "--quiet", "--out", str(tmp_path)], check=True)
    command = np.loadtxt(tmp_path / "modes.csv", delimiter=",", skiprows=1, usecols=1)
    k = len(command)
    scale = np.max(np.abs(command))
    assert np.max(np.abs(with_frames[:k] - command)) < 1e-9 * scale
    assert np.max(np.abs(without[:k] - command)) > 1e-3 * scale
    # Without rods there are no frames to return.
    b = ancf.SceneBuilder("bar")
    b.cable(name="bar", elements=2, geometry={"kind": "straight", "start": [0, 0, 0],
                                             "end": [1, 0, 0]},
            section={"EA": 1e3, "EI": 1.0, "mass_per_length": 1.0})
    b.joint(name="root", kind="clamp", at={"cable": "bar", "node": 0})
    assert ancf.solve_statics(b.build())["rod_frames"] is None
