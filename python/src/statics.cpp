// ancf.solve_statics and ancf.natural_modes: the library's static solver (Newton with load
// stepping on StaticModelProblem) and modal analysis (natural_modes), on a scene's model.
#include "ancf/solvers/static_solver.hpp"
#include "ancf/system/modal_analysis.hpp"
#include "ancf/system/rod_history.hpp"
#include "ancf/system/static_model_problem.hpp"
#include "bindings.hpp"

namespace ancf::python {

namespace {

/// The rod frame history a static solution was committed with (docs/rod.md, "History"): a rod's
/// twist coordinates in q are angles relative to it, so natural_modes must linearise under it.
struct RodFrames {
  RodHistory history;
};

py::dict solve(const SceneHandle& h, int load_steps, int max_iterations, int max_step_cuts,
               double increment_tolerance) {
  const Model& model = h.scene->model;
  StaticSolverOptions o;
  o.load_steps = load_steps;
  o.max_iterations = max_iterations;
  o.max_step_cuts = max_step_cuts;
  o.increment_tolerance = increment_tolerance;
  VecX y;
  StaticSolverStatistics st;
  RodFrames frames;
  {
    py::gil_scoped_release release;
    StaticModelProblem problem(model);
    y = problem.initial_guess();
    StaticSolver solver(problem, o);
    st = solver.solve(y);
    frames.history = problem.workspace().rods;
  }
  const Index n = model.coordinate_count();
  py::dict stats(py::arg("load_steps") = st.load_steps, py::arg("step_cuts") = st.step_cuts,
                 py::arg("newton_iterations") = st.newton_iterations,
                 py::arg("full_factorizations") = st.full_factorizations,
                 py::arg("refactorizations") = st.refactorizations,
                 py::arg("wall_seconds") = st.wall_seconds,
                 py::arg("smallest_singular_value") = st.smallest_singular_value,
                 py::arg("singular_direction") = st.singular_direction,
                 py::arg("residual_norm") = st.residual_norm);
  return py::dict(
      py::arg("q") = copy(y.head(n)), py::arg("lam") = copy(y.tail(y.size() - n)),
      py::arg("statistics") = stats,
      py::arg("rod_frames") = model.has_rods() ? py::cast(std::move(frames)) : py::none());
}

py::dict modes(const SceneHandle& h, std::optional<py::array_t<double>> q,
               std::optional<py::array_t<double>> lam, int component, double coupling_tolerance,
               double equilibrium_tolerance, const RodFrames* rod_frames) {
  const Model& model = h.scene->model;
  ModalAnalysisOptions o{.component = component, .coupling_tolerance = coupling_tolerance};
  NaturalModes r;
  if (!q) {
    if (lam) throw py::value_error("natural_modes: lam without q");
    py::gil_scoped_release release;
    r = natural_modes_at_initial_equilibrium(model, o, equilibrium_tolerance);
  } else {
    SystemState s = SystemState::initial(model);
    s.q = to_vector(*q, model.coordinate_count(), "q");
    s.lambda = lam ? to_vector(*lam, model.multiplier_count(), "lam")
                   : VecX::Zero(model.multiplier_count());
    s.v.setZero();
    if (rod_frames) {
      if (rod_frames->history.frames.size() != model.cables().size())
        throw py::value_error("natural_modes: rod_frames of another scene");
      s.rod_history = &rod_frames->history;
    }
    py::gil_scoped_release release;
    r = natural_modes(model, s, o);
  }
  VecX omega(r.omega_squared.size());
  for (Index i = 0; i < omega.size(); ++i) omega(i) = r.omega(i);
  py::array_t<double> shapes({r.shapes.rows(), r.shapes.cols()});
  auto s = shapes.mutable_unchecked<2>();
  for (Index i = 0; i < r.shapes.rows(); ++i)
    for (Index j = 0; j < r.shapes.cols(); ++j) s(i, j) = r.shapes(i, j);
  return py::dict(
      py::arg("omega_squared") = copy(r.omega_squared), py::arg("omega") = copy(omega),
      py::arg("frequency_hz") = copy(omega / (2.0 * 3.14159265358979323846)),
      py::arg("shapes") = shapes, py::arg("selected_coordinates") = r.selected_coordinates,
      py::arg("constraint_rank") = r.constraint_rank, py::arg("asymmetry") = r.asymmetry);
}

}  // namespace

void bind_statics(py::module_& m) {
  py::class_<RodFrames>(m, "RodFrames",
                        R"(The rod frame history a static solution was committed with (opaque).

Returned by solve_statics as 'rod_frames' for scenes with rods; pass it to natural_modes with the
q it came with: a rod's twist coordinates are angles relative to these frames.)");
  m.def("solve_statics", &solve, py::arg("scene"), py::arg("load_steps") = 1,
        py::arg("max_iterations") = 30, py::arg("max_step_cuts") = 10,
        py::arg("increment_tolerance") = 1e-11,
        R"(Static equilibrium of the scene's model under its loads (gravity, forces, prestrain).

Newton on R(q, λ) = [F(q) − sQ + Φ_qᵀλ; Φ(q)] = 0 from the initial configuration, the load
factor s raised to 1 in `load_steps` equal increments (a failed increment is halved, at most
max_step_cuts times). Returns {'q', 'lam', 'statistics', 'rod_frames'} (rod_frames: the rods'
frame history for natural_modes, None without rods). Raises ancf.SolverError (a singular
problem names the unknowns of the zero-stiffness direction and the load factor).)");
  m.def("natural_modes", &modes, py::arg("scene"), py::arg("q") = py::none(),
        py::arg("lam") = py::none(), py::arg("component") = -1,
        py::arg("coupling_tolerance") = 1e-12, py::arg("equilibrium_tolerance") = 1e-9,
        py::arg("rod_frames") = nullptr,
        R"(Natural frequencies and mode shapes linearised at an equilibrium (dense: small models).

Without q: at the initial configuration, which must be an equilibrium (λ by least squares); with
q (and lam, e.g. from solve_statics, with its rod_frames when the scene has rods): at that state.
component = 0, 1, 2 keeps only the x, y or z components (decoupled problems, e.g. a straight
cable). Returns {'omega_squared', 'omega' [rad/s],
'frequency_hz', 'shapes' (coordinates × modes, M-orthonormal), 'selected_coordinates',
'constraint_rank', 'asymmetry'}. Raises ValueError when the state is not an equilibrium or the
component is coupled.)");
}

}  // namespace ancf::python
