// The compiled part of the Python package `ancf` (python/ancf/__init__.py imports it as
// ancf._ancf): scenes, simulations, statics and modes over the C++ library (docs/python.md).
#include "ancf/io/run_record.hpp"
#include "bindings.hpp"

namespace ancf::python {

py::array_t<double> view(const VecX& v, py::handle owner) {
  py::array_t<double> a({v.size()}, {static_cast<py::ssize_t>(sizeof(double))}, v.data(), owner);
  a.attr("flags").attr("writeable") = false;  // state changes go through set_state
  return a;
}

py::array_t<double> copy(const VecX& v) {
  py::array_t<double> a(v.size());
  std::copy(v.data(), v.data() + v.size(), a.mutable_data());
  return a;
}

VecX to_vector(const py::array_t<double, py::array::c_style | py::array::forcecast>& a, Index n,
               const char* what) {
  if (a.ndim() != 1 || a.shape(0) != n)
    throw py::value_error(
        std::string(what) + ": expected a 1-D array of " + std::to_string(n) +
        " values, got shape " +
        py::str(py::tuple(py::cast(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()))))
            .cast<std::string>());
  return Eigen::Map<const VecX>(a.data(), n);
}

}  // namespace ancf::python

PYBIND11_MODULE(_ancf, m) {
  using namespace ancf::python;
  m.doc() = "ancf: ANCF cable and rigid-body multibody dynamics (compiled core; use `import ancf`)";
  m.attr("__version__") = ancf::ancf_version();
  bind_errors(m);
  bind_scene(m);
  bind_simulation(m);
  bind_statics(m);
}
