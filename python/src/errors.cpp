// ancf.Error and its subclasses, and the translation of the library's C++ exceptions into them:
//   ancf.ModelError  (ancf::ModelError: a model that cannot be built, a run refused)
//   ancf.SceneError  (ancf::SceneError, a ModelError: .file, .line, .column, .key, .message)
//   ancf.SolverError (a solver failure: .time, .step_size, .steps, .component)
// A C++ exception never crosses into Python untranslated (pybind11 maps the standard ones).
#include "bindings.hpp"

namespace ancf::python {

namespace {

// Owned by the module (its attributes); handles stay valid for the interpreter's lifetime.
PyObject* error_type = nullptr;
PyObject* model_error_type = nullptr;
PyObject* scene_error_type = nullptr;
PyObject* solver_error_type = nullptr;

PyObject* new_type(py::module_& m, const char* name, PyObject* base, const char* doc) {
  const std::string qualified = std::string("ancf.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, nullptr);
  if (!type) throw py::error_already_set();
  m.attr(name) = py::handle(type);  // the module holds a reference from here on
  Py_DECREF(type);
  return type;
}

void raise(PyObject* type, const char* what, const py::dict& attributes) {
  py::object error = py::reinterpret_borrow<py::object>(type)(what);
  for (const auto& [key, value] : attributes) error.attr(key) = value;
  PyErr_SetObject(type, error.ptr());
}

}  // namespace

void bind_errors(py::module_& m) {
  error_type = new_type(m, "Error", PyExc_Exception, "Base class of every error ancf raises.");
  model_error_type =
      new_type(m, "ModelError", error_type,
               "A model or run that cannot be built as given (bad parameter, undefined reference, "
               "redundant constraints, a run refused before it starts).");
  scene_error_type =
      new_type(m, "SceneError", model_error_type,
               "A scene that cannot be loaded. Attributes: file, line (1-based, 0: unknown, e.g. a "
               "value set by an override), column, key (path such as 'cable[0].section.EA'), "
               "message (what was expected). str() is 'FILE:LINE:COLUMN: KEY: MESSAGE'.");
  solver_error_type = new_type(
      m, "SolverError", error_type,
      "A solver that could not go on. Attributes: time [s] of the last state reached, step_size "
      "[s] being tried, steps taken, component (the unknown the integrator names as the worst, "
      "'-' if none). The Simulation stays readable at the last state reached.");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& e) {
      raise(scene_error_type, e.what(),
            py::dict(py::arg("file") = e.file(), py::arg("line") = e.line(),
                     py::arg("column") = e.column(), py::arg("key") = e.key(),
                     py::arg("message") = e.message()));
    } catch (const ModelError& e) {
      raise(model_error_type, e.what(), py::dict());
    } catch (const RunFailure& e) {
      raise(
          solver_error_type, e.what(),
          py::dict(py::arg("time") = e.failure.t, py::arg("step_size") = e.failure.step_size,
                   py::arg("steps") = e.failure.steps, py::arg("component") = e.failure.component));
    } catch (const SolverError& e) {
      // Outside a Simulation (statics): the message names load factor and unknowns.
      raise(solver_error_type, e.what(),
            py::dict(py::arg("time") = py::none(), py::arg("step_size") = py::none(),
                     py::arg("steps") = py::none(), py::arg("component") = "-"));
    }
  });
}

}  // namespace ancf::python
