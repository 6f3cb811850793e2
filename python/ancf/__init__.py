"""ancf: ANCF cable and rigid-body multibody dynamics from Python (docs/python.md).

Scenes are loaded and checked by the C++ scene loader (docs/scenes.md) from a file, a string
or a SceneBuilder, with overrides of any value; runs go through the same integrator driver as
`ancf run` (same results, bit for bit), statics and modes through the library's solvers.

    import ancf
    scene = ancf.load("studies/scenes/cable_pendulum.toml", {"integrator.t_end": 0.5})
    sim = scene.simulation(method="genalpha", genalpha={"step": 1e-3}).run()
    t, z = sim.probe_dict()["t"], sim.probe_dict()["tip.z"]
"""

from ._ancf import (  # noqa: F401  (the compiled core)
    Error,
    ModelError,
    SceneError,
    SolverError,
    Scene,
    Simulation,
    solve_statics,
    natural_modes,
    RodFrames,
    __version__,
)
from . import _ancf
from . import toml_text
from .builder import SceneBuilder

__all__ = [
    "Error", "ModelError", "SceneError", "SolverError", "Scene", "Simulation", "SceneBuilder",
    "load", "loads", "run", "solve_statics", "natural_modes", "RodFrames",
    "integrator_overrides", "__version__",
]


def _override_pairs(overrides):
    """{key: value} or [(key, value)] or ["KEY=VALUE"] → [(key, TOML text)]. Python values are
    converted (toml_text.value); a "KEY=VALUE" string keeps VALUE as TOML text."""
    if overrides is None:
        return []
    items = overrides.items() if isinstance(overrides, dict) else overrides
    pairs = []
    for item in items:
        if isinstance(item, str):
            key, eq, text = item.partition("=")
            if not eq or not key:
                raise ValueError(f"override {item!r}: expected KEY=VALUE")
            pairs.append((key.strip(), text.strip()))
        else:
            key, v = item
            pairs.append((str(key), toml_text.value(v)))
    return pairs


def load(path, overrides=None):
    """Load, validate and build the scene file `path`, with `overrides` applied before it is built
    (a dict {"cable[0].section.EA": 2e6, "integrator.method": "genalpha"}, pairs, or "KEY=VALUE"
    strings with TOML values). Raises SceneError (file, line, key, message)."""
    return _ancf._load(str(path), _override_pairs(overrides))


def loads(text, path="<string>", overrides=None):
    """Load a scene from TOML text; `path` names it in messages (and its default name)."""
    return _ancf._loads(text, str(path), _override_pairs(overrides))


def integrator_overrides(**settings):
    """Keyword settings of [integrator] as override pairs: method, t_end, rtol, contact_pattern,
    and the sub-tables ida={...} / genalpha={...} with their keys (docs/scenes.md), e.g.
    integrator_overrides(method="genalpha", genalpha={"step": 5e-4, "rho_infinity": 0.6})."""
    pairs = []
    for key, v in settings.items():
        if isinstance(v, dict):
            pairs += [(f"integrator.{key}.{k}", toml_text.value(x)) for k, x in v.items()]
        else:
            pairs.append((f"integrator.{key}", toml_text.value(v)))
    return pairs


def _with_overrides(self, overrides=None, **integrator):
    """A new Scene: this one's text with these overrides (and integrator settings, as in
    integrator_overrides) applied after the earlier ones."""
    return self._with_overrides(_override_pairs(overrides) + integrator_overrides(**integrator))


def _simulation(self, out=None, observer=None, max_steps=1e7, **integrator):
    """A Simulation of this scene, with integrator settings overridden as in
    integrator_overrides(**integrator) (method, t_end, rtol, ida={...}, genalpha={...})."""
    scene = self.with_overrides(**integrator) if integrator else self
    return Simulation(scene, out=out, max_steps=max_steps, observer=observer)


Scene.with_overrides = _with_overrides
Scene.simulation = _simulation


def run(scene, out=None, observer=None, max_steps=1e7, **integrator):
    """Run `scene` (a Scene, or a path to load) to t_end and return the Simulation, whose
    probes, counters() and metadata() hold the results; `out` writes what `ancf run` writes."""
    if not isinstance(scene, Scene):
        scene = load(scene)
    return scene.simulation(out=out, observer=observer, max_steps=max_steps, **integrator).run()
