"""SceneBuilder: a model assembled in Python, built by the scene loader.

Each method adds one entry of the scene format (docs/scenes.md) with its keys as keyword
arguments, exactly as in a file: the builder writes TOML and ancf.loads() reads it, so the
validation and the messages are the loader's (one key per line: SceneError.line points into
builder.to_toml()).

    b = ancf.SceneBuilder("pendulum", gravity=[0, 0, -9.81])
    b.cable(name="rope", elements=8,
            geometry={"kind": "straight", "start": [0, 0, 0], "end": [1, 0, 0]},
            section={"EA": 1e5, "EI": 1e-2, "mass_per_length": 0.1})
    b.joint(kind="pin", at={"cable": "rope", "node": 0})
    b.probe(kind="node", at={"cable": "rope", "node": -1}, label="tip")
    b.integrator(method="genalpha", t_end=1.0, genalpha={"step": 1e-3})
    scene = b.build()
"""

import copy

from . import toml_text

__all__ = ["SceneBuilder"]


class SceneBuilder:
    """Scene entries added one by one; build() returns an ancf.Scene."""

    def __init__(self, name=None, **scene):
        """`name` and the other [scene] keys (gravity, description)."""
        self._root = {}
        if name is not None:
            scene["name"] = name
        if scene:
            self._root["scene"] = dict(scene)

    def _add(self, array, keys):
        self._root.setdefault(array, []).append(copy.deepcopy(keys))
        return self

    def cable(self, **keys):
        """[[cable]]: name, elements, geometry {kind = straight|polyline|helix|arc, …},
        reference, section {EA | E+diameter, EI, mass_per_length | density, strain, damping, …},
        velocity, angular_velocity, rotation_centre, node_velocity [{…}]."""
        return self._add("cable", keys)

    def rod(self, **keys):
        """[[rod]]: a Kirchhoff rod that can twist (docs/rod.md): the [[cable]] keys plus frame
        {normal}, section {EA, EI | EI2+EI3, GJ | G, mass_per_length, polar_inertia,
        twist_interpolation, axial_strain, …}. Joints, loads and probes name it as `cable`."""
        return self._add("rod", keys)

    def body(self, **keys):
        """[[body]]: name, mass, inertia, centre_of_mass, position, rotation, velocity, …"""
        return self._add("body", keys)

    def frame(self, **keys):
        """[[frame]]: name, origin, rotation, axis, law (a driven frame)."""
        return self._add("frame", keys)

    def joint(self, **keys):
        """[[joint]]: kind = pin | align_slope | clamp | attach | join | spherical | revolute |
        fixed, and that kind's keys."""
        return self._add("joint", keys)

    def drive(self, **keys):
        """[[drive]]: name, joint (revolute), reference (angle law), kp, kd, torque_max."""
        return self._add("drive", keys)

    def load(self, **keys):
        """[[load]]: kind = force | torque | spring, and that kind's keys."""
        return self._add("load", keys)

    def shape(self, **keys):
        """[[shape]]: name, kind = sphere | cylinder | plane, on, geometry keys."""
        return self._add("shape", keys)

    def contact(self, **keys):
        """[[contact]]: a candidate contact pair (cable–shape or cable–cable) and its law."""
        return self._add("contact", keys)

    def probe(self, **keys):
        """[[output.probe]]: kind = node | body | energy | constraint_violation | contact |
        drive, label, and the target keys."""
        self._root.setdefault("output", {}).setdefault("probe", []).append(copy.deepcopy(keys))
        return self

    def integrator(self, **keys):
        """[integrator] keys (method, t_end, rtol, contact_pattern, ida {…}, genalpha {…}),
        merged into what was set before."""
        _merge(self._root.setdefault("integrator", {}), keys)
        return self

    def output(self, **keys):
        """[output] keys other than probes (interval, vtk, vtk_samples_per_element)."""
        _merge(self._root.setdefault("output", {}), keys)
        return self

    def to_toml(self):
        """The scene as TOML text (what build() loads)."""
        return toml_text.document(self._root)

    def build(self, path=None, overrides=None):
        """Load the scene (ancf.loads): validated and finalized, or SceneError."""
        from . import loads

        name = (self._root.get("scene") or {}).get("name", "builder")
        return loads(self.to_toml(), path or f"<builder {name}>", overrides)


def _merge(into, keys):
    for k, v in keys.items():
        if isinstance(v, dict) and isinstance(into.get(k), dict):
            _merge(into[k], v)
        else:
            into[k] = copy.deepcopy(v)
