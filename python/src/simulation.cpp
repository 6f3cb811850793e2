// ancf.Simulation: a dynamic run of a scene with IDA or generalized-α (the scene's [integrator]),
// advanced step by step, to a time or to the end, with the state as NumPy arrays, probes kept in
// memory, an optional Python observer at output times and, with an output directory, exactly the
// files `ancf run` writes (RunOutputs, run_json). The GIL is released while C++ integrates.
#include <chrono>
#include <fstream>
#include <optional>

#include "ancf/io/probe_recorder.hpp"
#include "ancf/io/run_limits.hpp"
#include "ancf/io/run_outputs.hpp"
#include "ancf/io/run_record.hpp"
#include "bindings.hpp"

namespace ancf::python {

namespace {

class PySimulation {
 public:
  PySimulation(SceneHandle scene, std::optional<std::string> out, double max_steps,
               py::object observer)
      : handle_(std::move(scene)),
        scene_(*handle_.scene),
        start_(std::chrono::steady_clock::now()),
        workspace_(scene_.model),
        recorder_(scene_.model, scene_.output.probes),
        observer_(std::move(observer)) {
    require_runnable(scene_.integrator, scene_.output.interval, max_steps);
    const std::vector<double> times = output_times(scene_.output.interval, scene_.integrator.t_end);
    // Every output row fits without reallocation (t = 0 and each output time).
    rows_.reserve((times.size() + 1) * recorder_.columns().size());
    {
      py::gil_scoped_release release;
      sim_ = std::make_unique<Simulation>(scene_.model, scene_.integrator, times);
    }
    if (out) {
      out_dir_ = *out;
      outputs_.emplace(scene_, out_dir_);
    }
    record();
  }

  const Simulation& sim() const { return *sim_; }
  const Scene& scene() const { return scene_; }
  const SceneHandle& handle() const { return handle_; }
  py::object& observer() { return observer_; }

  bool advance() {
    observe_initial();
    if (sim_->finished()) return false;
    guarded([&] {
      py::gil_scoped_release release;
      sim_->advance_to_next_output();
      record();
    });
    observe();
    return true;
  }

  void advance_to(double t) {
    observe_initial();
    const double t_end = scene_.integrator.t_end;
    if (!(t > sim_->time() && t <= t_end * (1.0 + 1e-12)))
      throw py::value_error("advance_to: expected time() < t <= t_end = " + std::to_string(t_end) +
                            ", got " + std::to_string(t));
    while (!sim_->finished() && sim_->times()[sim_->next_output()] <= t) advance();
    if (!sim_->finished() && sim_->time() < t)
      guarded([&] {
        py::gil_scoped_release release;
        sim_->advance_to(t);
      });
  }

  bool step() {
    observe_initial();
    bool reached = false;
    guarded([&] {
      py::gil_scoped_release release;
      reached = sim_->step();
      if (reached) record();
    });
    if (reached) observe();
    return reached;
  }

  void run() {
    while (advance()) {
    }
  }

  void set_state(const std::optional<VecX>& q, const std::optional<VecX>& v) {
    const SystemState& s = sim_->state();
    const VecX q_new = q ? *q : s.q, v_new = v ? *v : s.v;
    guarded([&] {
      py::gil_scoped_release release;
      sim_->set_state(q_new, v_new);
    });
  }

  /// Probe rows so far as a (rows, columns) array (a copy).
  py::array_t<double> probes() const {
    const auto cols = static_cast<py::ssize_t>(recorder_.columns().size());
    const py::ssize_t rows = cols ? static_cast<py::ssize_t>(rows_.size()) / cols : 0;
    py::array_t<double> a({rows, cols});
    std::copy(rows_.begin(), rows_.end(), a.mutable_data());
    return a;
  }
  const std::vector<std::string>& columns() const { return recorder_.columns(); }

  py::dict energies() {
    const Energies e = ancf::energies(scene_.model, sim_->state(), workspace_);
    return py::dict(py::arg("kinetic") = e.kinetic, py::arg("strain") = e.strain,
                    py::arg("spring") = e.spring, py::arg("load") = e.load,
                    py::arg("potential") = e.potential(), py::arg("total") = e.total());
  }
  py::dict violation() {
    const ConstraintViolation c = constraint_violation(scene_.model, sim_->state(), workspace_);
    return py::dict(py::arg("position") = c.position, py::arg("velocity") = c.velocity);
  }

  const std::string& status() const { return status_; }
  const std::string& message() const { return message_; }
  std::optional<py::dict> failure() const {
    if (status_ != "failed") return std::nullopt;
    const SimulationFailure& f = sim_->failure();
    return py::dict(py::arg("time") = f.t, py::arg("step_size") = f.step_size,
                    py::arg("steps") = f.steps, py::arg("component") = f.component,
                    py::arg("message") = message_);
  }

  /// run.json's document (also written to the output directory if there is one).
  std::string record_json() const {
    RunRecord r;
    r.scene_path = scene_.path;
    r.scene_text = handle_.overrides.empty()
                       ? handle_.text
                       : apply_scene_overrides(handle_.text, scene_.path, handle_.overrides);
    r.out_dir = out_dir_;
    r.status = status_;
    r.message = message_;
    r.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    r.counters = sim_->counters();
    r.timings = sim_->timings();
    return run_json(scene_, r, outputs_ ? &*outputs_ : nullptr).text();
  }
  void write_record() const {
    if (outputs_) std::ofstream(out_dir_ + "/run.json") << record_json() << '\n';
  }

 private:
  void record() {
    // With outputs, their recorder has evaluated the probes already (the same code and state).
    if (outputs_) outputs_->record(sim_->state());
    const std::vector<double>& row =
        outputs_ ? outputs_->probes().last_row() : recorder_.evaluate(sim_->state(), workspace_);
    rows_.insert(rows_.end(), row.begin(), row.end());
    if (sim_->finished() && status_ == "running") {
      status_ = "completed";
      write_record();
    }
  }

  // The output at t = 0 is recorded by the constructor and observed by the first call that
  // integrates (the Python object exists by then).
  void observe_initial() {
    if (observed_initial_) return;
    observed_initial_ = true;
    observe();
  }

  void observe() {
    if (observer_.is_none()) return;
    try {
      observer_(py::cast(this, py::return_value_policy::reference));
    } catch (py::error_already_set& e) {
      if (status_ == "running") {
        status_ = "stopped";
        message_ = std::string("the observer raised: ") + e.what();
        write_record();
      }
      throw;
    }
  }

  template <class F>
  void guarded(F&& f) {
    if (status_ == "failed") throw ModelError("the simulation failed earlier: " + message_);
    try {
      f();
    } catch (const SolverError& e) {
      status_ = "failed";
      message_ = e.what();
      write_record();
      throw RunFailure(e.what(), sim_->failure());
    }
  }

  SceneHandle handle_;  // keeps the Scene (and its Model) alive
  const Scene& scene_;
  std::chrono::steady_clock::time_point start_;
  std::unique_ptr<Simulation> sim_;
  Workspace workspace_;
  ProbeRecorder recorder_;
  std::vector<double> rows_;  // probe rows, row-major
  std::optional<RunOutputs> outputs_;
  std::string out_dir_;
  std::string status_ = "running", message_;
  py::object observer_;
  bool observed_initial_ = false;
};

}  // namespace

void bind_simulation(py::module_& m) {
  using Vector = py::array_t<double, py::array::c_style | py::array::forcecast>;
  py::class_<PySimulation>(m, "Simulation", R"(A dynamic run of a scene, from t = 0 to t_end.

Simulation(scene, out=None, max_steps=1e7, observer=None) builds the integrator of the scene's
[integrator] table (IDA on the GGL index-2 DAE or generalized-α; change it with
scene.with_overrides or ancf.Scene.simulation(...)), makes the initial values consistent and
records the first output (t = 0). It is then advanced by advance() (to the next output time),
advance_to(t), step() or run() (to the end). At every output time the probes are recorded in
memory, and with `out` the files of `ancf run` are written (probes.csv, SCENE.pvd and frames/,
run.json when the run ends, fails or is stopped). `observer(sim)` is called for each recorded
output (the one at t = 0 when the first advance/step/run begins); if it raises, the exception propagates and the run stops there (sim stays readable and
can be resumed). The GIL is released while C++ integrates.)")
      .def(py::init<SceneHandle, std::optional<std::string>, double, py::object>(),
           py::arg("scene"), py::arg("out") = py::none(), py::arg("max_steps") = kDefaultMaxSteps,
           py::arg("observer") = py::none())
      .def_property_readonly(
          "t", [](const PySimulation& s) { return s.sim().time(); }, "current time [s]")
      .def_property_readonly(
          "t_end", [](const PySimulation& s) { return s.scene().integrator.t_end; }, "[s]")
      .def_property_readonly(
          "finished", [](const PySimulation& s) { return s.sim().finished(); },
          "True once t_end is reached")
      .def_property_readonly(
          "method",
          [](const PySimulation& s) {
            return s.sim().kind() == IntegratorKind::ida ? "ida" : "genalpha";
          },
          "'ida' or 'genalpha'")
      .def_property_readonly(
          "scene", [](const PySimulation& s) { return s.handle(); }, "the Scene being run")
      .def_property(
          "observer", [](PySimulation& s) { return s.observer(); },
          [](PySimulation& s, py::object f) { s.observer() = std::move(f); },
          "callable(sim) called after every recorded output, or None")
      .def_property_readonly(
          "q",
          [](py::object self) { return view(self.cast<PySimulation&>().sim().state().q, self); },
          "coordinates q [m, -] at t: a read-only view (no copy) that follows the run; .copy() "
          "to keep a value")
      .def_property_readonly(
          "v",
          [](py::object self) { return view(self.cast<PySimulation&>().sim().state().v, self); },
          "velocities q' at t (read-only view)")
      .def_property_readonly(
          "a",
          [](py::object self) { return view(self.cast<PySimulation&>().sim().state().a, self); },
          "accelerations q'' at t (read-only view)")
      .def_property_readonly(
          "lam",
          [](py::object self) {
            return view(self.cast<PySimulation&>().sim().state().lambda, self);
          },
          "Lagrange multipliers λ at t (read-only view; one per constraint row)")
      .def(
          "set_state",
          [](PySimulation& s, std::optional<Vector> q, std::optional<Vector> v) {
            const Index n = s.scene().model.coordinate_count();
            std::optional<VecX> qv, vv;
            if (q) qv = to_vector(*q, n, "q");
            if (v) vv = to_vector(*v, n, "v");
            s.set_state(qv, vv);
          },
          py::arg("q") = py::none(), py::arg("v") = py::none(),
          "Restart the integrator at t from q and/or v (copied; the other keeps its value). λ and "
          "q'' are not set: they follow from the constraints and the equations of motion "
          "(generalized-α projects q, v onto the constraints; IDA makes the GGL values "
          "consistent).")
      .def("advance", &PySimulation::advance,
           "Integrate to the next output time and record it. False (nothing done) when finished.")
      .def("advance_to", &PySimulation::advance_to, py::arg("t"),
           "Integrate to t (t < t ≤ t_end), recording the output times passed. Stopping between "
           "output times shortens a generalized-α step (later steps then differ from a run that "
           "did not stop); IDA interpolates (its steps are unchanged).")
      .def("step", &PySimulation::step,
           "One step, ending at the next output time at the latest (generalized-α: one accepted "
           "step; IDA: one internal step). True if it reached the output time (then recorded).")
      .def(
          "run",
          [](py::object self) {
            self.cast<PySimulation&>().run();
            return self;
          },
          "Integrate to t_end (from wherever the run is); returns the simulation.")
      .def_property_readonly(
          "probes", &PySimulation::probes,
          "recorded probe rows, shape (outputs, columns), columns as probe_columns (t first)")
      .def_property_readonly("probe_columns", &PySimulation::columns,
                             "column names: 't', then each probe's 'label.suffix'")
      .def(
          "probe_dict",
          [](const PySimulation& s) {
            py::array_t<double> p = s.probes();
            py::dict d;
            const auto& c = s.columns();
            for (std::size_t j = 0; j < c.size(); ++j)
              d[py::str(c[j])] = p[py::make_tuple(py::slice(py::none(), py::none(), py::none()),
                                                  static_cast<py::ssize_t>(j))];
            return d;
          },
          "The probes as {column: 1-D array}.")
      .def(
          "counters", [](const PySimulation& s) { return to_dict(s.sim().counters()); },
          "the integrator's counters so far (those of run.json), as a dict")
      .def(
          "timings", [](const PySimulation& s) { return to_dict(s.sim().timings()); },
          "wall-time shares so far [s] (run.json's time_s)")
      .def("energies", &PySimulation::energies,
           "Energies at t [J]: kinetic, strain, spring, load, potential, total.")
      .def("constraint_violation", &PySimulation::violation, "max|Φ| and max|Φ_q v + Φ_t| at t.")
      .def_property_readonly("status", &PySimulation::status,
                             "'running', 'completed', 'failed' or 'stopped' (observer raised)")
      .def_property_readonly(
          "failure", &PySimulation::failure,
          "None, or after a solver failure {time, step_size, steps, component, message}")
      .def(
          "metadata",
          [](const PySimulation& s) {
            return py::module_::import("json").attr("loads")(s.record_json());
          },
          "run.json's contents now (version, scene, hash, status, options, counters, time_s, "
          "results) as a dict")
      .def("write_record", &PySimulation::write_record,
           "Write run.json into the output directory now (done by itself at the end).");
}

}  // namespace ancf::python
