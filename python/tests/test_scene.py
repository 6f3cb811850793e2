"""Scenes: loading from files and strings, overrides, the builder, located errors."""

import numpy as np
import pytest

import ancf
from conftest import PENDULUM, SMALL, SCENES


def test_load_file_and_properties(small_pendulum):
    s = small_pendulum
    assert s.name == "cable_pendulum"
    assert s.path == str(PENDULUM)
    info = s.info()
    assert info["coordinates"] == 6 * 5 and info["multipliers"] == 3 and info["cables"] == 1
    assert s.names["cables"] == {"pendulum": 0}
    assert s.integrator["method"] == "ida" and s.integrator["t_end"] == 0.05
    assert s.integrator["genalpha"]["step"] == 1e-3
    assert s.output_interval == 0.01
    np.testing.assert_array_equal(s.output_times(), [0.01, 0.02, 0.03, 0.04, 0.05])
    assert s.q0.shape == (30,) and s.v0.shape == (30,)
    assert s.q0[6] == pytest.approx(0.25)  # node 1 of 4 equal elements on [0, 1] m
    assert "pendulum" in s.describe_coordinate(0)
    assert s.overrides == [("cable[0].elements", "4"), ("integrator.t_end", "0.05")]
    assert "Scene 'cable_pendulum'" in repr(s)


def test_loads_string_and_toml_round_trip(small_pendulum):
    again = ancf.loads(small_pendulum.toml(), "again.toml")
    assert again.info() == small_pendulum.info()
    np.testing.assert_array_equal(again.q0, small_pendulum.q0)
    assert again.path == "again.toml"
    assert ancf.load(PENDULUM).text == PENDULUM.read_text()


def test_override_forms_are_equivalent():
    a = ancf.load(PENDULUM, {"integrator.genalpha.step": 5e-4, "integrator.method": "genalpha"})
    b = ancf.load(PENDULUM, ["integrator.genalpha.step=5e-4", 'integrator.method="genalpha"'])
    c = ancf.load(PENDULUM).with_overrides(method="genalpha", genalpha={"step": 5e-4})
    for s in (a, b, c):
        assert s.integrator["method"] == "genalpha" and s.integrator["genalpha"]["step"] == 5e-4


def test_override_creates_missing_tables_and_changes_the_model():
    s = ancf.load(PENDULUM, {"integrator.ida.max_order": 2, "cable[0].section.density": 4000.0})
    assert s.integrator["ida"]["max_order"] == 2
    m0 = ancf.load(PENDULUM)
    # Half the density: same geometry, the initial energy of gravity differs (checked in a run
    # elsewhere); here the model is rebuilt with the same size.
    assert s.info() == m0.info()


def test_scene_error_is_located(tmp_path):
    bad = tmp_path / "bad.toml"
    text = PENDULUM.read_text().replace("density = 8000.0", "density = -1.0")
    bad.write_text(text)
    with pytest.raises(ancf.SceneError) as e:
        ancf.load(bad)
    err = e.value
    assert err.file == str(bad)
    assert err.key == "cable[0].section.density"
    assert err.line == text.splitlines().index("density = -1.0") + 1
    assert "expected" in err.message and str(err).startswith(f"{bad}:{err.line}:")
    assert isinstance(err, ancf.ModelError) and isinstance(err, ancf.Error)


def test_override_errors_are_scene_errors():
    with pytest.raises(ancf.SceneError) as e:
        ancf.load(PENDULUM, {"cable[0].section.EA": -3.0})  # value checked by the loader
    assert e.value.key == "cable[0].section.EA" and e.value.line == 0
    with pytest.raises(ancf.SceneError, match="has 1 entries"):
        ancf.load(PENDULUM, {"cable[3].elements": 2})
    with pytest.raises(ancf.SceneError, match="unknown|not"):
        ancf.load(PENDULUM, {"integrator.no_such_key": 1})
    with pytest.raises(ancf.SceneError, match="not TOML"):
        ancf.load(PENDULUM, ["integrator.method=ida"])  # a string needs quotes
    with pytest.raises(ValueError):
        ancf.load(PENDULUM, ["no equals sign"])


def test_syntax_and_missing_file_errors(tmp_path):
    with pytest.raises(ancf.SceneError) as e:
        ancf.loads("[scene]\nname = \n", "broken.toml")
    assert e.value.line == 2 and "syntax" in e.value.message
    with pytest.raises(ancf.SceneError, match="no such file"):
        ancf.load(tmp_path / "absent.toml")
    with pytest.raises(ancf.SceneError, match="directory"):
        ancf.load(tmp_path)


def test_check_refuses_runaway_runs(small_pendulum):
    small_pendulum.check()
    with pytest.raises(ancf.ModelError, match="max-steps"):
        small_pendulum.check(max_steps=3)
    with pytest.raises(ancf.SceneError, match="t_end >= the generalized-alpha step"):
        small_pendulum.with_overrides(method="genalpha", genalpha={"step": 1.0})


def pendulum_builder(elements=4):
    b = ancf.SceneBuilder("cable_pendulum", gravity=[0.0, 0.0, -9.81])
    b.cable(name="pendulum", elements=elements,
            geometry={"kind": "straight", "start": [0.0, 0.0, 0.0], "end": [1.0, 0.0, 0.0]},
            section={"E": 1.0e9, "diameter": 0.01, "density": 8000.0, "strain": "green",
                     "bending": True})
    b.joint(name="pivot", kind="pin", at={"cable": "pendulum", "node": 0})
    b.integrator(method="ida", t_end=0.05, rtol=1e-6, genalpha={"step": 1e-3})
    b.integrator(genalpha={"rho_infinity": 0.8})  # merged
    b.output(interval=0.01)
    b.probe(kind="node", at={"cable": "pendulum", "node": -1}, label="tip")
    b.probe(kind="energy")
    b.probe(kind="constraint_violation")
    return b


def test_builder_gives_the_file_scene(small_pendulum):
    built = pendulum_builder().build()
    assert built.info() == small_pendulum.info()
    np.testing.assert_array_equal(built.q0, small_pendulum.q0)
    a = built.simulation().run()
    b = small_pendulum.simulation().run()
    np.testing.assert_array_equal(a.probes, b.probes)  # the same model, bit for bit


def test_builder_every_entry_kind():
    """Bodies, frames, joints, drives, loads, shapes and contact pairs through the builder."""
    b = ancf.SceneBuilder("everything", gravity=[0, 0, -9.81])
    b.cable(name="rope", elements=2,
            geometry={"kind": "arc", "u": [1, 0, 0], "w": [0, 1, 0], "radius": 0.2, "angle": 1.0},
            section={"EA": 1e4, "EI": 1e-3, "mass_per_length": 0.02, "radius": 0.002})
    b.body(name="hub", mass=1.0, inertia=[0.01, 0.01, 0.01], position=[0, 0, 0])
    b.frame(name="spinner", axis=[0, 0, 1],
            law={"kind": "constant_rate", "rate": 1.0})
    b.joint(name="hinge", kind="revolute", body="hub", to="ground", point=[0, 0, 0],
            axis=[0, 0, 1])
    b.joint(name="tie", kind="attach", at={"cable": "rope", "node": 0}, to="hub")
    b.drive(name="motor", joint="hinge", kp=10.0, kd=1.0, torque_max=1.0,
            reference={"kind": "constant_rate", "rate": 1.0})
    b.load(kind="force", at={"cable": "rope", "node": -1}, force=[0, 0, -0.1])
    b.load(kind="spring", a={"body": "hub", "point": [0.1, 0, 0]},
           b={"frame": "spinner", "point": [0.2, 0, 0]}, stiffness=1.0)
    b.shape(name="floor", kind="plane", point=[0, 0, -0.5], normal=[0, 0, 1])
    b.contact(name="rope_floor", cable="rope", shape="floor", law={"stiffness": 1e4})
    b.probe(kind="drive", drive="motor")
    b.probe(kind="contact", pair="rope_floor")
    b.probe(kind="body", body="hub")
    b.integrator(method="genalpha", t_end=0.01, genalpha={"step": 1e-3})
    scene = b.build()
    info = scene.info()
    assert (info["bodies"], info["frames"], info["contact_pairs"], info["cables"]) == (1, 1, 1, 1)
    sim = scene.simulation().run()
    assert sim.status == "completed"
    assert {"motor.angle", "rope_floor.active", "hub.rx"} <= set(sim.probe_columns)


def test_builder_errors_point_into_its_text():
    b = pendulum_builder()
    b.cable(name="second", elements=0,
            geometry={"kind": "straight", "start": [0, 0, 1], "end": [1, 0, 1]},
            section={"EA": 1.0, "mass_per_length": 1.0, "bending": False})
    with pytest.raises(ancf.SceneError) as e:
        b.build()
    assert e.value.key == "cable[1].elements"
    assert b.to_toml().splitlines()[e.value.line - 1].startswith("elements = 0")
    b2 = pendulum_builder()
    b2.joint(kind="pin", at={"cable": "nope", "node": 0})
    with pytest.raises(ancf.SceneError, match="nope"):
        b2.build()


def test_ida_tolerance_scales():
    unit = ancf.load(PENDULUM)
    assert unit.integrator["ida"]["slope_scale"] == "unit"
    assert unit.integrator["ida"]["twist_scale"] == "unit"
    rod = ancf.load(SCENES / "capture_rod.toml")  # sets both (docs/capture.md)
    assert rod.integrator["ida"]["slope_scale"] == "position_equivalent"
    assert rod.integrator["ida"]["twist_scale"] == "position_equivalent"
    s = ancf.load(PENDULUM, {"integrator.ida.twist_scale": "position_equivalent"})
    assert s.integrator["ida"]["twist_scale"] == "position_equivalent"
    with pytest.raises(ancf.SceneError, match="twist_scale"):
        ancf.load(PENDULUM, {"integrator.ida.twist_scale": "radius"})


def test_every_study_scene_loads():
    for path in sorted(SCENES.glob("*.toml")):
        assert ancf.load(path).info()["coordinates"] > 0
