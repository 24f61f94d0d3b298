#include "solver/estimation/internal/ipopt_program.h"

#include "hb/errors.h"

#include <exception>
#include <stdexcept>

#include <IpIpoptApplication.hpp>
#include <IpIpoptData.hpp>
#include <IpTNLP.hpp>

namespace beamid::solver::internal {
namespace {

using Ipopt::Index;
using Ipopt::Number;

// A thin adapter: every callback delegates to the problem, and no exception
// may cross Ipopt (it would look like a NaN): it is kept and rethrown after.
class IdentificationTnlp : public Ipopt::TNLP {
 public:
  IdentificationTnlp(FitProblem& problem, const Eigen::VectorXd& start)
      : problem_(problem), start_(start) {}

  std::exception_ptr error;
  IpoptOutcome outcome;

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = problem_.num_variables();
    m = problem_.num_constraints();
    nnz_jac_g = problem_.JacobianNonZeros();
    nnz_h_lag = problem_.HessianNonZeros();
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    return Guard([&] {
      Eigen::VectorXd lower, upper;
      problem_.Bounds(&lower, &upper);
      Eigen::Map<Eigen::VectorXd>(x_l, n) = lower;
      Eigen::Map<Eigen::VectorXd>(x_u, n) = upper;
      Eigen::Map<Eigen::VectorXd>(g_l, m).setZero();
      Eigen::Map<Eigen::VectorXd>(g_u, m).setZero();
    });
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool, Number*, Number*, Index, bool, Number*) override {
    if (init_x) Eigen::Map<Eigen::VectorXd>(x, n) = start_;
    return true;
  }

  bool eval_f(Index n, const Number* x, bool, Number& value) override {
    return Guard([&] { value = problem_.Objective(Eigen::Map<const Eigen::VectorXd>(x, n)); });
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* gradient) override {
    return Guard([&] {
      Eigen::VectorXd g;
      problem_.Gradient(Eigen::Map<const Eigen::VectorXd>(x, n), &g);
      Eigen::Map<Eigen::VectorXd>(gradient, n) = g;
    });
  }

  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    return Guard([&] {
      Eigen::VectorXd c;
      problem_.Constraints(Eigen::Map<const Eigen::VectorXd>(x, n), &c);
      Eigen::Map<Eigen::VectorXd>(g, m) = c;
    });
  }

  bool eval_jac_g(Index n, const Number* x, bool, Index, Index, Index* rows, Index* cols, Number* values) override {
    return Guard([&] {
      if (values == nullptr)
        problem_.JacobianStructure(rows, cols);
      else
        problem_.JacobianValues(Eigen::Map<const Eigen::VectorXd>(x, n), values);
    });
  }

  bool eval_h(Index n, const Number* x, bool, Number objective_factor, Index, const Number* lambda, bool, Index,
              Index* rows, Index* cols, Number* values) override {
    return Guard([&] {
      if (values == nullptr)
        problem_.HessianStructure(rows, cols);
      else
        problem_.HessianValues(Eigen::Map<const Eigen::VectorXd>(x, n), objective_factor, lambda, values);
    });
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*, const Number*, Index,
                         const Number*, const Number*, Number objective, const Ipopt::IpoptData* data,
                         Ipopt::IpoptCalculatedQuantities*) override {
    outcome.x = Eigen::Map<const Eigen::VectorXd>(x, n);
    outcome.objective = objective;
    outcome.iterations = data ? data->iter_count() : 0;
  }

 private:
  template <typename F>
  bool Guard(F&& f) {
    try {
      f();
      return true;
    } catch (...) {
      if (!error) error = std::current_exception();
      return false;
    }
  }

  FitProblem& problem_;
  Eigen::VectorXd start_;
};

std::string StatusTextOf(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Solve_Succeeded: return "solved";
    case Ipopt::Solved_To_Acceptable_Level: return "solved to an acceptable level";
    case Ipopt::Infeasible_Problem_Detected: return "infeasible (the model cannot satisfy its equations)";
    case Ipopt::Search_Direction_Becomes_Too_Small: return "search direction too small";
    case Ipopt::Maximum_Iterations_Exceeded: return "maximum number of iterations reached";
    case Ipopt::Restoration_Failed: return "restoration phase failed";
    case Ipopt::Error_In_Step_Computation: return "error in step computation";
    case Ipopt::Invalid_Number_Detected: return "invalid number (NaN or Inf) in the model";
    case Ipopt::Maximum_CpuTime_Exceeded: return "CPU time limit reached";
    case Ipopt::User_Requested_Stop: return "stopped by beamid (a model evaluation failed or was cancelled)";
    case Ipopt::Feasible_Point_Found: return "feasible point found";
    case Ipopt::Diverging_Iterates: return "diverging iterates (a parameter ran off to infinity)";
    case Ipopt::Not_Enough_Degrees_Of_Freedom: return "not enough degrees of freedom (fewer residuals than parameters)";
    case Ipopt::Invalid_Problem_Definition: return "invalid problem definition";
    case Ipopt::Invalid_Option: return "invalid Ipopt option";
    case Ipopt::Unrecoverable_Exception: return "unrecoverable exception inside Ipopt";
    case Ipopt::NonIpopt_Exception_Thrown: return "an exception from the model inside Ipopt";
    case Ipopt::Insufficient_Memory: return "insufficient memory";
    case Ipopt::Internal_Error: return "internal error in Ipopt";
    default: return "Ipopt status " + std::to_string(static_cast<int>(status));
  }
}

}  // namespace

std::string IpoptStatusText(int status) { return StatusTextOf(static_cast<Ipopt::ApplicationReturnStatus>(status)); }

IpoptOutcome RunIpopt(FitProblem& problem, const Eigen::VectorXd& start, const IpoptOptions& options) {
  options.Validate();
  Ipopt::SmartPtr<IdentificationTnlp> program = new IdentificationTnlp(problem, start);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->RethrowNonIpoptException(false);
  auto set = [&](bool ok, const std::string& name) {
    if (!ok) throw std::logic_error("Ipopt rejected the option " + name);
  };
  set(app->Options()->SetIntegerValue("print_level", options.print_level), "print_level");
  set(app->Options()->SetStringValue("sb", "yes"), "sb");  // no banner
  set(app->Options()->SetIntegerValue("max_iter", options.max_iterations), "max_iter");
  if (options.max_cpu_seconds > 0.0)
    set(app->Options()->SetNumericValue("max_cpu_time", options.max_cpu_seconds), "max_cpu_time");
  set(app->Options()->SetNumericValue("tol", options.tolerance), "tol");
  set(app->Options()->SetNumericValue("constr_viol_tol", options.constraint_tolerance), "constr_viol_tol");
  // We start from a feasible point near the optimum (the direct estimate):
  // a small, monotonically decreasing barrier keeps the first steps there;
  // the adaptive strategy's first μ was seen to push the bounded k1 and c
  // far away.
  set(app->Options()->SetStringValue("mu_strategy", "monotone"), "mu_strategy");
  set(app->Options()->SetNumericValue("mu_init", 1e-4), "mu_init");
  // χ² grows with the data: per residual the objective is ~½ at the optimum.
  set(app->Options()->SetNumericValue("obj_scaling_factor", 1.0 / std::max(1, problem.num_residuals())),
      "obj_scaling_factor");
  if (options.derivative_test) {
    set(app->Options()->SetStringValue("derivative_test", "second-order"), "derivative_test");
    set(app->Options()->SetNumericValue("derivative_test_perturbation", 1e-6), "derivative_test_perturbation");
  }
  // Read no ipopt.opt lying around in the working folder.
  if (app->Initialize("") != Ipopt::Solve_Succeeded) throw EnvironmentError("Ipopt failed to initialise");
  const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(program);
  if (program->error) std::rethrow_exception(program->error);
  IpoptOutcome outcome = program->outcome;
  if (outcome.x.size() != start.size()) outcome.x = start;
  outcome.status = static_cast<int>(status);
  outcome.status_text = StatusTextOf(status);
  outcome.success = status == Ipopt::Solve_Succeeded || status == Ipopt::Solved_To_Acceptable_Level;
  return outcome;
}

}  // namespace beamid::solver::internal
