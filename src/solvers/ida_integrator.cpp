#include "ancf/solvers/ida_integrator.hpp"

#include <fmt/format.h>
#include <ida/ida.h>
#include <ida/ida_ls.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <utility>

#include "ancf/core/stopwatch.hpp"
#include "ida_vector_ops.hpp"
#include "klu_linear_solver.hpp"

namespace ancf {
namespace {

// RAII owners of the SUNDIALS objects (each destructor is the matching SUNDIALS free function).
struct ContextFree {
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};
struct VectorFree {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixFree {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct SolverFree {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
struct MemoryFree {
  void operator()(void* mem) const { IDAFree(&mem); }
};
using Context = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextFree>;
using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorFree>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixFree>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, SolverFree>;
using Memory = std::unique_ptr<void, MemoryFree>;

std::string flag_name(int flag) {
  char* name = IDAGetReturnFlagName(flag);  // malloc'ed by SUNDIALS
  std::string s = name ? name : "unknown flag";
  std::free(name);
  return s;
}

// Every SUNDIALS call is checked; a negative flag is a programming or set-up error here (the
// names are IDA's; other modules share the small negative codes).
void check(int flag, const char* call) {
  if (flag < 0)
    throw SolverError(fmt::format("SUNDIALS: {} returned {} ({})", call, flag, flag_name(flag)));
}
template <class T>
T* check_pointer(T* p, const char* call) {
  if (!p) throw SolverError(fmt::format("SUNDIALS: {} returned NULL", call));
  return p;
}

std::span<double> view(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<std::size_t>(N_VGetLength(v))};
}

}  // namespace

struct IdaIntegrator::Impl {
  DaeProblem& problem;
  const IdaOptions& options;
  Index n = 0;
  Context context;
  Vector y, yp, id, atol;
  Matrix jacobian;
  LinearSolver klu;
  std::unique_ptr<detail::KluLinearSolver> own_klu;  // content of klu with ancf_klu
  Memory mem;
  double cj_pivoted = 0.0;      // c_j of the last factorization with fresh pivoting (0: none yet)
  IdaStatistics before_reinit;  // IDAReInit resets IDA's counters: the sums up to then
  long repivots = 0, reinitializations = 0;
  long pattern_changes = 0,
       symbolic_analyses = 1;  // KLU analyses: the first setup's and each ReInit
  double wall_time = 0.0;
  double residual_seconds = 0.0, jacobian_seconds = 0.0;  // inside the callbacks
  std::exception_ptr fatal;      // a non-recoverable exception caught in a callback
  std::string message;           // IDA's last error message
  std::string callback_message;  // the last recoverable error raised in a callback
  std::vector<int> roots;

  Impl(DaeProblem& p, const IdaOptions& o) : problem(p), options(o), n(p.size()) {}

  // Runs f for a callback: 0 on success, +1 on a recoverable error, −1 on any other exception.
  template <class F>
  int guard(F&& f) noexcept {
    try {
      return f() ? 0 : 1;
    } catch (const std::domain_error& e) {
      callback_message = e.what();
      return 1;
    } catch (const SolverError& e) {
      callback_message = e.what();
      return 1;
    } catch (...) {
      fatal = std::current_exception();
      return -1;
    }
  }

  static int residual_fn(realtype t, N_Vector y, N_Vector yp, N_Vector r, void* user) {
    auto& self = *static_cast<Impl*>(user);
    const Stopwatch watch(self.residual_seconds);
    return self.guard([&] {
      const auto out = view(r);
      self.problem.residual(t, view(y), view(yp), out);
      const bool finite =
          std::all_of(out.begin(), out.end(), [](double x) { return std::isfinite(x); });
      if (!finite) self.callback_message = fmt::format("non-finite residual at t = {:.10g}", t);
      return finite;
    });
  }

  static int jacobian_fn(realtype t, realtype cj, N_Vector y, N_Vector yp, N_Vector, SUNMatrix jac,
                         void* user, N_Vector, N_Vector, N_Vector) {
    auto& self = *static_cast<Impl*>(user);
    const Stopwatch watch(self.jacobian_seconds);
    return self.guard([&] {
      // The pattern may follow the state (contact pairs that are near, DESIGN §5), asked for a
      // Jacobian that serves about one step: a change re-sizes the matrix and makes KLU's next
      // setup re-run its symbolic analysis.
      realtype h = 0.0;
      check(IDAGetCurrentStep(self.mem.get(), &h), "IDAGetCurrentStep");
      if (self.problem.update_jacobian_pattern(t, view(y), std::abs(h))) {
        self.pattern_changed(jac);
        self.cj_pivoted = cj;
      }
      // SUNDIALS 6.4 zeroed the index arrays too: restore the pattern first.
      const SparsityPattern& p = self.problem.jacobian_pattern();
      std::copy(p.column_start().begin(), p.column_start().end(),
                SUNSparseMatrix_IndexPointers(jac));
      std::copy(p.row_index().begin(), p.row_index().end(), SUNSparseMatrix_IndexValues(jac));
      const std::span<double> values(SUNSparseMatrix_Data(jac),
                                     static_cast<std::size_t>(p.nonzeros()));
      self.problem.jacobian(t, view(y), view(yp), cj, values);
      if (!std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); })) {
        self.callback_message = fmt::format("non-finite Jacobian at t = {:.10g}", t);
        return false;
      }
      const double ratio = self.options.klu_repivot_ratio;
      if (self.cj_pivoted == 0.0) {
        self.cj_pivoted = cj;  // the first factorization after (re)initialization pivots anyway
      } else if (ratio > 1.0 && (cj > ratio * self.cj_pivoted || cj * ratio < self.cj_pivoted)) {
        if (self.own_klu) {
          self.own_klu->klu.reset_pivoting();
        } else {
          check(SUNLinSol_KLUReInit(self.klu.get(), jac, p.nonzeros(), SUNKLU_REINIT_PARTIAL),
                "SUNLinSol_KLUReInit");
          ++self.symbolic_analyses;  // a partial ReInit frees the symbolic analysis as well
        }
        self.cj_pivoted = cj;
        ++self.repivots;
      }
      return true;
    });
  }  // The problem's pattern changed: the matrix takes its size, and the next setup analyses it.
  void pattern_changed(SUNMatrix jac) {
    const Index nnz = problem.jacobian_pattern().nonzeros();
    if (own_klu) {
      if (SUNSparseMatrix_Reallocate(jac, nnz) != 0)
        throw SolverError("SUNDIALS: SUNSparseMatrix_Reallocate failed");
      ++own_klu->pattern_revision;
    } else {
      check(SUNLinSol_KLUReInit(klu.get(), jac, nnz, SUNKLU_REINIT_FULL), "SUNLinSol_KLUReInit");
      ++symbolic_analyses;
    }
    ++pattern_changes;
  }

  static int root_fn(realtype t, N_Vector y, N_Vector yp, realtype* g, void* user) {
    auto& self = *static_cast<Impl*>(user);
    return self.guard([&] {
      self.problem.roots(t, view(y), view(yp),
                         {g, static_cast<std::size_t>(self.problem.root_count())});
      return true;
    });
  }

  // IDA's messages are kept for the failure report instead of going to stderr.
  static void error_fn(int code, const char*, const char* function, char* msg,
                       void* user) noexcept {
    if (code == IDA_WARNING) return;
    try {
      static_cast<Impl*>(user)->message = fmt::format("{}: {}", function, msg);
    } catch (...) {  // out of memory while formatting: keep the previous message
    }
  }

  void set_tolerances() {
    const auto a = view(atol.get()), ids = view(id.get());
    const double rtol = options.rtol;
    auto factor = [&](double f) { return f < 0.0 ? rtol : f; };
    for (Index i = 0; i < n; ++i) {
      const VariableClass c = problem.variable_class(i);
      const double f = c == VariableClass::position   ? factor(options.atol_position)
                       : c == VariableClass::velocity ? factor(options.atol_velocity)
                                                      : factor(options.atol_multiplier);
      a[i] = f * problem.variable_scale(i);
      ids[i] = c == VariableClass::algebraic ? 0.0 : 1.0;
    }
    if (options.compiled_vector_ops)
      check(IDAWFtolerances(mem.get(), &Impl::weights_fn), "IDAWFtolerances");
    else
      check(IDASVtolerances(mem.get(), rtol, atol.get()), "IDASVtolerances");
    check(IDASetId(mem.get(), id.get()), "IDASetId");
    check(IDASetSuppressAlg(mem.get(), SUNTRUE), "IDASetSuppressAlg");
  }

  // IDA's error weights w_i = 1/(rtol |y_i| + atol_i) (IDASVtolerances' formula, evaluated as
  // IDAEwtSetSV does: rtol·|y_i| + atol_i, then the reciprocal, so the weights are the same
  // numbers) in one pass instead of four. −1 (IDA stops) if a denominator is not positive,
  // also when it is NaN.
  static int weights_fn(N_Vector y, N_Vector ewt, void* user) {
    const auto& self = *static_cast<const Impl*>(user);
    const double* ys = N_VGetArrayPointer(y);
    const double* a = N_VGetArrayPointer(self.atol.get());
    double* w = N_VGetArrayPointer(ewt);
    const double rtol = self.options.rtol;
    for (Index i = 0; i < self.n; ++i) {
      const double d = rtol * std::abs(ys[i]) + a[i];
      if (!(d > 0.0)) return -1;
      w[i] = 1.0 / d;
    }
    return 0;
  }

  // First step from a second-order estimate: the BDF1 local error ½h²‖y''‖ with ‖y''‖ ≈ ‖y'‖/T
  // (T = DaeProblem::time_scale()), in the error-weighted RMS norm over differential unknowns,
  // set to half the tolerance: h₀ = √(T/‖y'‖). 0 (IDA's estimate) if T or ‖y'‖ is unknown/zero.
  double first_step() const {
    const double time = problem.time_scale();
    if (!(time > 0.0)) return 0.0;
    const auto y0 = view(y.get()), yp0 = view(yp.get()), a = view(atol.get()), ids = view(id.get());
    double sum = 0.0;
    Index count = 0;
    for (Index i = 0; i < n; ++i) {
      if (ids[i] == 0.0) continue;
      const double w = 1.0 / (options.rtol * std::abs(y0[i]) + a[i]);
      sum += (yp0[i] * w) * (yp0[i] * w);
      ++count;
    }
    const double norm = count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
    if (!(norm > 0.0)) return 0.0;
    double h0 = std::min(std::sqrt(time / norm), 0.01 * time);
    if (options.max_step > 0.0) h0 = std::min(h0, options.max_step);
    return h0;
  }

  // The component with the largest |x_i|·w_i (error weights), over differential unknowns only if
  // `differential_only`.
  Index worst(N_Vector x, bool differential_only, double& value) {
    Vector weights(check_pointer(N_VClone(y.get()), "N_VClone"));
    if (IDAGetErrWeights(mem.get(), weights.get()) < 0) return -1;
    const auto xs = view(x), ws = view(weights.get()), ids = view(id.get());
    Index best = -1;
    value = 0.0;
    for (Index i = 0; i < n; ++i) {
      if (differential_only && ids[i] == 0.0) continue;
      const double e = std::abs(xs[i] * ws[i]);
      if (best < 0 || e > value) best = i, value = e;
    }
    return best;
  }

  IdaFailureReport report(int flag) {
    IdaFailureReport r;
    r.flag = flag;
    r.flag_name = flag_name(flag);
    r.ida_message = message;
    r.callback_message = callback_message;
    if (IDAGetCurrentTime(mem.get(), &r.t) != IDA_SUCCESS) r.t = std::nan("");
    if (IDAGetCurrentStep(mem.get(), &r.step) != IDA_SUCCESS) r.step = std::nan("");
    Index singular = -1;
    if (own_klu) {
      singular = own_klu->klu.singular_column();
    } else if (const sun_klu_common* common = SUNLinSol_KLUGetCommon(klu.get());
               common && common->status == KLU_SINGULAR) {
      singular = common->singular_col;
    }
    if ((flag == IDA_LSETUP_FAIL || flag == IDA_LSOLVE_FAIL) && singular >= 0 && singular < n) {
      r.component = singular;
      r.measure = "singular column";
      r.value = 0.0;
    } else if (flag == IDA_CONV_FAIL || flag == IDA_REP_RES_ERR || flag == IDA_RES_FAIL ||
               flag == IDA_NLS_FAIL) {
      // The Newton iterate against the predictor: the component that would not settle.
      realtype tcur = 0.0, cj = 0.0;
      N_Vector ypred = nullptr, yppred = nullptr, yyn = nullptr, ypn = nullptr, res = nullptr;
      void* user = nullptr;
      if (IDAGetNonlinearSystemData(mem.get(), &tcur, &ypred, &yppred, &yyn, &ypn, &res, &cj,
                                    &user) == IDA_SUCCESS &&
          ypred && yyn) {
        Vector diff(check_pointer(N_VClone(y.get()), "N_VClone"));
        N_VLinearSum(1.0, yyn, -1.0, ypred, diff.get());
        r.component = worst(diff.get(), false, r.value);
        r.measure = "Newton correction (weighted)";
      }
    }
    if (r.component < 0) {
      Vector ele(check_pointer(N_VClone(y.get()), "N_VClone"));
      if (IDAGetEstLocalErrors(mem.get(), ele.get()) == IDA_SUCCESS) {
        r.component = worst(ele.get(), true, r.value);
        r.measure = "local error (weighted)";
      }
    }
    if (r.component >= 0) r.component_name = problem.describe_row(r.component);
    return r;
  }
};

IdaIntegrator::IdaIntegrator(DaeProblem& problem, IdaOptions options)
    : options_(std::move(options)), impl_(std::make_unique<Impl>(problem, options_)) {
  Impl& s = *impl_;
  if (!(options_.rtol > 0.0)) throw SolverError("IdaIntegrator: rtol must be positive");
  if (options_.rtol > kIdaMaxRtol)
    throw SolverError(fmt::format(
        "IdaIntegrator: rtol = {:g} is looser than {:g}; IDA would accept steps with errors of the "
        "size of the solution (energy gains of several times the energy of the motion were seen "
        "at rtol 3e-2), use rtol <= {:g} (SUNDIALS recommends <= 1e-3)",
        options_.rtol, kIdaMaxRtol, kIdaMaxRtol));
  if (options_.max_order < 1 || options_.max_order > 5)
    throw SolverError("IdaIntegrator: max_order must be 1 … 5");
  SUNContext ctx = nullptr;
  check(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
  s.context.reset(ctx);
  s.y.reset(check_pointer(N_VNew_Serial(s.n, ctx), "N_VNew_Serial"));
  // Before any clone: IDA's own vectors are cloned from y and inherit its operations.
  if (options_.compiled_vector_ops) detail::use_compiled_serial_ops(s.y.get());
  s.yp.reset(check_pointer(N_VClone(s.y.get()), "N_VClone"));
  s.id.reset(check_pointer(N_VClone(s.y.get()), "N_VClone"));
  s.atol.reset(check_pointer(N_VClone(s.y.get()), "N_VClone"));

  t_ = options_.start_time;
  problem.initial_values(t_, view(s.y.get()), view(s.yp.get()));

  s.mem.reset(check_pointer(IDACreate(ctx), "IDACreate"));
  void* mem = s.mem.get();
  check(IDASetErrHandlerFn(mem, &Impl::error_fn, &s), "IDASetErrHandlerFn");
  check(IDAInit(mem, &Impl::residual_fn, t_, s.y.get(), s.yp.get()), "IDAInit");
  check(IDASetUserData(mem, &s), "IDASetUserData");
  s.set_tolerances();
  check(IDASetMaxOrd(mem, options_.max_order), "IDASetMaxOrd");
  check(IDASetMaxNumSteps(mem, options_.max_steps), "IDASetMaxNumSteps");
  check(IDASetMaxNonlinIters(mem, options_.max_nonlinear_iterations), "IDASetMaxNonlinIters");
  check(IDASetMaxConvFails(mem, options_.max_convergence_failures), "IDASetMaxConvFails");
  check(IDASetMaxErrTestFails(mem, options_.max_error_test_failures), "IDASetMaxErrTestFails");
  if (options_.max_step > 0.0) check(IDASetMaxStep(mem, options_.max_step), "IDASetMaxStep");
  if (options_.min_step > 0.0) check(IDASetMinStep(mem, options_.min_step), "IDASetMinStep");
  const double h0 = options_.initial_step > 0.0 ? options_.initial_step : s.first_step();
  if (h0 > 0.0) check(IDASetInitStep(mem, h0), "IDASetInitStep");
  if (std::isfinite(options_.stop_time))
    check(IDASetStopTime(mem, options_.stop_time), "IDASetStopTime");

  const SparsityPattern& p = problem.jacobian_pattern();
  if (!p.frozen() || p.size() != s.n)
    throw SolverError(
        "IdaIntegrator: the Jacobian pattern must be frozen and of the problem's size");
  s.jacobian.reset(
      check_pointer(SUNSparseMatrix(s.n, s.n, p.nonzeros(), CSC_MAT, ctx), "SUNSparseMatrix"));
  if (options_.linear_solver == IdaLinearSolver::ancf_klu) {
    s.own_klu = std::make_unique<detail::KluLinearSolver>(p);
    s.own_klu->klu.set_solve(options_.klu_solve);
    s.own_klu->klu.set_refactor(options_.klu_refactor);
    s.klu.reset(detail::make_klu_linear_solver(*s.own_klu, ctx));
  } else {
    s.klu.reset(check_pointer(SUNLinSol_KLU(s.y.get(), s.jacobian.get(), ctx), "SUNLinSol_KLU"));
  }
  check(IDASetLinearSolver(mem, s.klu.get(), s.jacobian.get()), "IDASetLinearSolver");
  check(IDASetJacFn(mem, &Impl::jacobian_fn), "IDASetJacFn");
  if (problem.root_count() > 0) {
    check(IDARootInit(mem, problem.root_count(), &Impl::root_fn), "IDARootInit");
    s.roots.assign(static_cast<std::size_t>(problem.root_count()), 0);
    if (!options_.root_directions.empty()) {
      if (options_.root_directions.size() != s.roots.size())
        throw SolverError("IdaIntegrator: root_directions needs one entry per event function");
      std::vector<int> directions = options_.root_directions;
      check(IDASetRootDirection(mem, directions.data()), "IDASetRootDirection");
    }
  }
}

IdaIntegrator::~IdaIntegrator() = default;

std::span<const double> IdaIntegrator::y() const {
  return view(impl_->y.get());
}
std::span<const double> IdaIntegrator::yp() const {
  return view(impl_->yp.get());
}

IdaStop IdaIntegrator::advance(double t_out) {
  return solve(t_out, IDA_NORMAL);
}

IdaStop IdaIntegrator::one_step(double t_out) {
  return solve(t_out, IDA_ONE_STEP);
}

IdaStop IdaIntegrator::solve(double t_out, int task) {
  Impl& s = *impl_;
  realtype t_reached = t_;
  const auto start = std::chrono::steady_clock::now();
  int flag = 0;
  if (!s.problem.keeps_history()) {
    flag = IDASolve(s.mem.get(), t_out, &t_reached, s.y.get(), s.yp.get(), task);
  } else if (task == IDA_ONE_STEP) {
    flag = IDASolve(s.mem.get(), t_out, &t_reached, s.y.get(), s.yp.get(), IDA_ONE_STEP);
    if (flag >= 0 && !s.fatal) s.problem.commit_step(t_reached, view(s.y.get()));
  } else {
    // One internal step at a time until a step reaches t_out, so that the problem commits each
    // accepted step's state (DaeProblem::commit_step); then IDA_NORMAL, which takes no further
    // step: it checks the rest of that step for roots and interpolates at t_out. A step taken for
    // an earlier output may already reach past t_out (steps longer than the output interval, e.g.
    // a rod at rest); another IDA_ONE_STEP would step first, leaving t_out outside the step.
    realtype t_internal = t_;
    check(IDAGetCurrentTime(s.mem.get(), &t_internal), "IDAGetCurrentTime");
    while (t_internal < t_out) {
      flag = IDASolve(s.mem.get(), t_out, &t_reached, s.y.get(), s.yp.get(), IDA_ONE_STEP);
      if (flag < 0 || s.fatal) break;
      // After an IDA_NORMAL return inside the last step, IDA_ONE_STEP first returns that step's
      // end state again, without stepping: it is committed already.
      if (!(flag == IDA_SUCCESS && t_reached == t_internal))
        s.problem.commit_step(t_reached, view(s.y.get()));
      t_internal = std::max(t_internal, t_reached);
      if (flag == IDA_ROOT_RETURN || flag == IDA_TSTOP_RETURN) break;
    }
    if (flag >= 0 && flag != IDA_ROOT_RETURN && flag != IDA_TSTOP_RETURN && !s.fatal)
      flag = IDASolve(s.mem.get(), t_out, &t_reached, s.y.get(), s.yp.get(), IDA_NORMAL);
  }
  s.wall_time += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  t_ = t_reached;
  if (s.fatal) std::rethrow_exception(std::exchange(s.fatal, nullptr));
  if (flag < 0) throw IdaFailure(s.report(flag));
  if (flag == IDA_ROOT_RETURN) {
    check(IDAGetRootInfo(s.mem.get(), s.roots.data()), "IDAGetRootInfo");
    return IdaStop::root;
  }
  if (flag == IDA_TSTOP_RETURN && t_ < t_out) return IdaStop::stop_time;
  return IdaStop::reached;
}

IdaStop IdaIntegrator::run(const Observer& observer, const EventHandler& on_event) {
  Impl& s = *impl_;
  std::vector<double> changed;
  for (const double t_out : options_.output_times) {
    if (t_out <= t_) continue;
    for (;;) {
      const IdaStop stop = advance(t_out);
      if (stop == IdaStop::stop_time) return stop;
      if (stop == IdaStop::reached) break;
      // The handler works on a copy of y: reinitialize() reads it into IDA's vector.
      changed.assign(y().begin(), y().end());
      const EventAction action =
          on_event ? on_event(t_, s.roots, changed, yp()) : EventAction::resume;
      if (action == EventAction::stop) return IdaStop::root;
      if (action == EventAction::reinitialize) reinitialize(t_, changed);
    }
    if (observer) observer(t_, y(), yp());
    if (t_ >= options_.stop_time) return IdaStop::stop_time;
  }
  return IdaStop::reached;
}

void IdaIntegrator::reinitialize(double t, std::span<const double> y_new, bool pattern_changed) {
  Impl& s = *impl_;
  if (static_cast<Index>(y_new.size()) != s.n)
    throw SolverError("IdaIntegrator::reinitialize: wrong state size");
  const auto y = view(s.y.get());
  if (y_new.data() != y.data()) std::copy(y_new.begin(), y_new.end(), y.begin());
  s.problem.consistent_values(t, y, view(s.yp.get()));
  if (pattern_changed) {
    const SparsityPattern& p = s.problem.jacobian_pattern();
    if (!p.frozen() || p.size() != s.n)
      throw SolverError(
          "IdaIntegrator::reinitialize: the new pattern must be frozen and of the same size");
    s.pattern_changed(s.jacobian.get());
    --s.pattern_changes;  // an event's re-initialization, not a contact-pattern change
  }
  const IdaStatistics so_far = statistics();
  check(IDAReInit(s.mem.get(), t, s.y.get(), s.yp.get()), "IDAReInit");
  s.before_reinit = so_far;
  s.set_tolerances();  // multiplier scales may have changed with the new consistent values
  const double h0 = options_.initial_step > 0.0 ? options_.initial_step : s.first_step();
  if (h0 > 0.0) check(IDASetInitStep(s.mem.get(), h0), "IDASetInitStep");
  if (std::isfinite(options_.stop_time) && options_.stop_time > t)
    check(IDASetStopTime(s.mem.get(), options_.stop_time), "IDASetStopTime");
  s.cj_pivoted = 0.0;
  ++s.reinitializations;
  t_ = t;
}

Index IdaIntegrator::worst_local_error(double& weighted) const {
  Impl& s = *impl_;
  weighted = 0.0;
  Vector ele(check_pointer(N_VClone(s.y.get()), "N_VClone"));
  if (IDAGetEstLocalErrors(s.mem.get(), ele.get()) != IDA_SUCCESS) return -1;
  return s.worst(ele.get(), true, weighted);
}

IdaStatistics IdaIntegrator::statistics() const {
  const Impl& s = *impl_;
  void* mem = s.mem.get();
  IdaStatistics st;  // IDA's counters since the last (re)initialization, then the earlier sums
  check(IDAGetNumSteps(mem, &st.steps), "IDAGetNumSteps");
  check(IDAGetNumResEvals(mem, &st.residual_evaluations), "IDAGetNumResEvals");
  check(IDAGetNumJacEvals(mem, &st.jacobian_evaluations), "IDAGetNumJacEvals");
  check(IDAGetNumLinSolvSetups(mem, &st.linear_solver_setups), "IDAGetNumLinSolvSetups");
  check(IDAGetNumNonlinSolvIters(mem, &st.nonlinear_iterations), "IDAGetNumNonlinSolvIters");
  check(IDAGetNumErrTestFails(mem, &st.error_test_failures), "IDAGetNumErrTestFails");
  check(IDAGetNumNonlinSolvConvFails(mem, &st.convergence_failures),
        "IDAGetNumNonlinSolvConvFails");
  if (s.problem.root_count() > 0)
    check(IDAGetNumGEvals(mem, &st.root_evaluations), "IDAGetNumGEvals");
  check(IDAGetLastOrder(mem, &st.last_order), "IDAGetLastOrder");
  check(IDAGetLastStep(mem, &st.last_step), "IDAGetLastStep");
  const IdaStatistics& b = s.before_reinit;
  st.steps += b.steps;
  st.residual_evaluations += b.residual_evaluations;
  st.jacobian_evaluations += b.jacobian_evaluations;
  st.linear_solver_setups += b.linear_solver_setups;
  st.nonlinear_iterations += b.nonlinear_iterations;
  st.error_test_failures += b.error_test_failures;
  st.convergence_failures += b.convergence_failures;
  st.root_evaluations += b.root_evaluations;
  if (st.steps == b.steps)
    st.last_order = b.last_order, st.last_step = b.last_step;  // no step since
  st.klu_repivots = s.repivots;
  st.reinitializations = s.reinitializations;
  st.pattern_changes = s.pattern_changes;
  st.symbolic_analyses = s.symbolic_analyses;
  if (s.own_klu) {
    const KluSolver& k = s.own_klu->klu;
    st.symbolic_analyses = k.symbolic_analyses();
    st.full_factorizations = k.full_factorizations();
    st.refactorizations = k.refactorizations();
    st.factor_seconds = k.factor_seconds();
    st.solve_seconds = k.solve_seconds();
  }
  st.wall_time = s.wall_time;
  st.residual_seconds = s.residual_seconds;
  st.jacobian_seconds = s.jacobian_seconds;
  return st;
}

}  // namespace ancf
