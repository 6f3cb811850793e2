// Shared by the translation units of the Python module _ancf (python/src): the scene handle the
// Python objects share, the failure type that carries a run's report to Python, and the
// registration function of each concept.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "ancf/io/scene.hpp"
#include "ancf/io/scene_overrides.hpp"
#include "ancf/io/simulation.hpp"

namespace ancf::python {

namespace py = pybind11;

/// A loaded scene as Python sees it: immutable, shared by every Simulation made from it (which
/// keeps it alive: the C++ Simulation refers to its Model).
struct SceneHandle {
  std::shared_ptr<const Scene> scene;
  std::string text;                      ///< the text as given (file contents or string)
  std::vector<SceneOverride> overrides;  ///< applied to `text`, in order
  bool from_file = false;
};

/// A solver failure of a Simulation, with where it happened (ancf.SolverError in Python).
class RunFailure : public std::runtime_error {
 public:
  RunFailure(const std::string& what, SimulationFailure f)
      : std::runtime_error(what), failure(std::move(f)) {}
  SimulationFailure failure;
};

/// Read-only NumPy view of `v` (no copy); `owner` keeps the memory alive.
py::array_t<double> view(const VecX& v, py::handle owner);
/// Copy of `v` into a new NumPy array.
py::array_t<double> copy(const VecX& v);
/// NumPy 1-D array → VecX of `n` entries; throws ValueError naming `what` on a wrong size.
VecX to_vector(const py::array_t<double, py::array::c_style | py::array::forcecast>& a, Index n,
               const char* what);
/// (name, value) pairs → dict, in order.
template <class Pairs>
py::dict to_dict(const Pairs& pairs) {
  py::dict d;
  for (const auto& [name, value] : pairs) d[py::str(name)] = value;
  return d;
}

void bind_errors(py::module_& m);
void bind_scene(py::module_& m);
void bind_simulation(py::module_& m);
void bind_statics(py::module_& m);

}  // namespace ancf::python
