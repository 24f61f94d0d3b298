#include "hb/support_law.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace beamid::hb {

PeriodicMoment SupportLaw::EvaluatePeriodic(const Eigen::VectorXd& theta_rad,
                                            const Eigen::VectorXd& theta_rate_rad_s) const {
  if (NumInternalStates() != 0)
    throw std::logic_error(Name() + ": a hysteretic law must override EvaluatePeriodic");
  const Eigen::Index n = theta_rad.size();
  PeriodicMoment out;
  out.moment_Nm.resize(n);
  out.d_moment_d_theta = Eigen::MatrixXd::Zero(n, n);
  out.d_moment_d_theta_rate = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const SupportLawResponse r = Evaluate(theta_rad[i], theta_rate_rad_s[i], {}, {});
    out.moment_Nm[i] = r.moment_Nm;
    out.d_moment_d_theta(i, i) = r.d_moment_d_theta_Nm_rad;
    out.d_moment_d_theta_rate(i, i) = r.d_moment_d_theta_rate_Nms_rad;
  }
  return out;
}

Eigen::MatrixXd SupportLaw::PeriodicParameterJacobian(const Eigen::VectorXd& theta_rad,
                                                      const Eigen::VectorXd& theta_rate_rad_s) const {
  const std::vector<LawParameter> parameters = Parameters();
  std::vector<double> values;
  for (const auto& p : parameters) values.push_back(p.value);
  Eigen::MatrixXd jacobian(theta_rad.size(), static_cast<Eigen::Index>(values.size()));
  std::unique_ptr<SupportLaw> probe = Clone();
  for (std::size_t j = 0; j < values.size(); ++j) {
    const double step = 1e-6 * std::max(std::abs(values[j]), 1e-9);
    std::vector<double> shifted = values;
    shifted[j] = values[j] + step;
    probe->SetParameterValues(shifted);
    const Eigen::VectorXd up = probe->EvaluatePeriodic(theta_rad, theta_rate_rad_s).moment_Nm;
    shifted[j] = values[j] - step;
    probe->SetParameterValues(shifted);
    const Eigen::VectorXd down = probe->EvaluatePeriodic(theta_rad, theta_rate_rad_s).moment_Nm;
    jacobian.col(static_cast<Eigen::Index>(j)) = (up - down) / (2.0 * step);
  }
  return jacobian;
}

// ---------------------------------------------------------------- polynomial

std::unique_ptr<SupportLaw> PolynomialSupportLaw::Clone() const {
  return std::make_unique<PolynomialSupportLaw>(*this);
}

SupportLawResponse PolynomialSupportLaw::Evaluate(double theta, double theta_rate,
                                                  std::span<const double>, std::span<double>) const {
  const auto& k = coefficients_;
  return {.moment_Nm = ((k.k3_Nm_rad3 * theta + k.k2_Nm_rad2) * theta + k.k1_Nm_rad) * theta +
                       k.c_Nms_rad * theta_rate,
          .d_moment_d_theta_Nm_rad = (3.0 * k.k3_Nm_rad3 * theta + 2.0 * k.k2_Nm_rad2) * theta + k.k1_Nm_rad,
          .d_moment_d_theta_rate_Nms_rad = k.c_Nms_rad};
}

std::vector<LawParameter> PolynomialSupportLaw::Parameters() const {
  return {{"k1", coefficients_.k1_Nm_rad, "N*m/rad"},
          {"k2", coefficients_.k2_Nm_rad2, "N*m/rad^2"},
          {"k3", coefficients_.k3_Nm_rad3, "N*m/rad^3"},
          {"c", coefficients_.c_Nms_rad, "N*m*s/rad"}};
}

void PolynomialSupportLaw::SetParameterValues(std::span<const double> values) {
  if (values.size() != 4) throw std::invalid_argument("polynomial support law takes 4 parameters (k1, k2, k3, c)");
  coefficients_ = {values[0], values[1], values[2], values[3]};
}

Eigen::MatrixXd PolynomialSupportLaw::PeriodicParameterJacobian(const Eigen::VectorXd& theta,
                                                                const Eigen::VectorXd& theta_rate) const {
  Eigen::MatrixXd jacobian(theta.size(), 4);
  jacobian.col(0) = theta;
  jacobian.col(1) = theta.array().square();
  jacobian.col(2) = theta.array().cube();
  jacobian.col(3) = theta_rate;
  return jacobian;
}

// ------------------------------------------------------------------- Jenkins

JenkinsSupportLaw::JenkinsSupportLaw(const Parameters_& parameters) : parameters_(parameters) {
  if (!(parameters_.stiffness_Nm_rad > 0.0) || !(parameters_.slip_moment_Nm > 0.0))
    throw std::invalid_argument("Jenkins support law: stiffness_Nm_rad and slip_moment_Nm must be positive");
}

std::unique_ptr<SupportLaw> JenkinsSupportLaw::Clone() const {
  return std::make_unique<JenkinsSupportLaw>(*this);
}

// Return mapping: elastic trial, then projection onto |M| <= M_slip.
SupportLawResponse JenkinsSupportLaw::Evaluate(double theta, double, std::span<const double> state_in,
                                               std::span<double> state_out) const {
  const double k = parameters_.stiffness_Nm_rad;
  const double limit = parameters_.slip_moment_Nm;
  const double slider = state_in.empty() ? 0.0 : state_in[0];
  const double trial = k * (theta - slider);
  SupportLawResponse r;
  double new_slider = slider;
  if (std::abs(trial) <= limit) {
    r.moment_Nm = trial;
    r.d_moment_d_theta_Nm_rad = k;
  } else {
    r.moment_Nm = std::copysign(limit, trial);
    new_slider = theta - r.moment_Nm / k;
  }
  if (!state_out.empty()) state_out[0] = new_slider;
  return r;
}

// The periodic loop is the fixed point of one period of the return mapping.
// If the rotation range exceeds 2·M_slip/k_t the element slips on every
// cycle and forgets its past. Otherwise it sticks throughout, linear about a slider offset that history
// alone fixes; we take the mid-range rotation, the limit reached from rest
// under a symmetric build-up. Derivatives are carried through the recursion:
// row n holds ∂M_n/∂θ_m for all m.
PeriodicMoment JenkinsSupportLaw::EvaluatePeriodic(const Eigen::VectorXd& theta,
                                                   const Eigen::VectorXd&) const {
  const Eigen::Index n = theta.size();
  const double k = parameters_.stiffness_Nm_rad;
  const double limit = parameters_.slip_moment_Nm;
  PeriodicMoment out;
  out.moment_Nm.resize(n);
  out.d_moment_d_theta_rate = Eigen::MatrixXd::Zero(n, n);

  Eigen::Index arg_max = 0, arg_min = 0;
  const double theta_max = theta.maxCoeff(&arg_max);
  const double theta_min = theta.minCoeff(&arg_min);
  if (k * (theta_max - theta_min) <= 2.0 * limit) {
    out.d_moment_d_theta = Eigen::MatrixXd::Zero(n, n);
    const double offset = 0.5 * (theta_max + theta_min);
    out.moment_Nm = k * (theta.array() - offset);
    out.d_moment_d_theta.diagonal().setConstant(k);
    out.d_moment_d_theta.col(arg_max).array() -= 0.5 * k;
    out.d_moment_d_theta.col(arg_min).array() -= 0.5 * k;
    return out;
  }

  // Any slider state is forgotten at the first slip, and a period with this
  // range must slip: pass 1 (from an arbitrary state) ends on the loop, and
  // pass 2 records it with its exact derivatives.
  const Eigen::Index start = arg_max;
  double moment = limit;
  Eigen::RowVectorXd d_moment = Eigen::RowVectorXd::Zero(n);
  // Written a row per sample: row-major, then stored once (a row of the
  // column-major result is strided, which cost more than the loop itself).
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows(n, n);
  for (int pass = 0; pass < 2; ++pass) {
    for (Eigen::Index step = 1; step <= n; ++step) {
      const Eigen::Index i = (start + step) % n;
      const Eigen::Index previous = (start + step - 1) % n;
      const double trial = moment + k * (theta[i] - theta[previous]);
      if (std::abs(trial) <= limit) {
        moment = trial;
        d_moment(i) += k;
        d_moment(previous) -= k;
      } else {
        moment = std::copysign(limit, trial);
        d_moment.setZero();
      }
      if (pass == 1) {
        out.moment_Nm[i] = moment;
        rows.row(i) = d_moment;
      }
    }
  }
  out.d_moment_d_theta = rows;
  return out;
}

std::vector<LawParameter> JenkinsSupportLaw::Parameters() const {
  return {{"jenkins_stiffness", parameters_.stiffness_Nm_rad, "N*m/rad"},
          {"jenkins_slip_moment", parameters_.slip_moment_Nm, "N*m"}};
}

void JenkinsSupportLaw::SetParameterValues(std::span<const double> values) {
  if (values.size() != 2) throw std::invalid_argument("Jenkins support law takes 2 parameters");
  *this = JenkinsSupportLaw(Parameters_{values[0], values[1]});
}

// ---------------------------------------------------------------- one-sided

std::unique_ptr<SupportLaw> OneSidedStiffnessLaw::Clone() const {
  return std::make_unique<OneSidedStiffnessLaw>(*this);
}

SupportLawResponse OneSidedStiffnessLaw::Evaluate(double theta, double, std::span<const double>,
                                                  std::span<double>) const {
  const bool engaged = theta > 0.0;
  return {.moment_Nm = engaged ? stiffness_Nm_rad_ * theta : 0.0,
          .d_moment_d_theta_Nm_rad = engaged ? stiffness_Nm_rad_ : 0.0,
          .d_moment_d_theta_rate_Nms_rad = 0.0};
}

std::vector<LawParameter> OneSidedStiffnessLaw::Parameters() const {
  return {{"one_sided_stiffness", stiffness_Nm_rad_, "N*m/rad"}};
}

void OneSidedStiffnessLaw::SetParameterValues(std::span<const double> values) {
  if (values.size() != 1) throw std::invalid_argument("one-sided stiffness law takes 1 parameter");
  stiffness_Nm_rad_ = values[0];
}

Eigen::MatrixXd OneSidedStiffnessLaw::PeriodicParameterJacobian(const Eigen::VectorXd& theta,
                                                                const Eigen::VectorXd&) const {
  return theta.cwiseMax(0.0);
}

// ----------------------------------------------------------------- composite

CompositeSupportLaw::CompositeSupportLaw(const CompositeSupportLaw& other) {
  for (const auto& law : other.laws_) laws_.push_back(law->Clone());
}

void CompositeSupportLaw::Add(std::unique_ptr<SupportLaw> law) {
  if (!law) throw std::invalid_argument("CompositeSupportLaw::Add: null law");
  laws_.push_back(std::move(law));
}

std::string CompositeSupportLaw::Name() const {
  std::string name;
  for (const auto& law : laws_) name += (name.empty() ? "" : "+") + law->Name();
  return name.empty() ? "none" : name;
}

std::unique_ptr<SupportLaw> CompositeSupportLaw::Clone() const {
  return std::make_unique<CompositeSupportLaw>(*this);
}

int CompositeSupportLaw::NumInternalStates() const {
  int count = 0;
  for (const auto& law : laws_) count += law->NumInternalStates();
  return count;
}

bool CompositeSupportLaw::IsSmooth() const {
  return std::all_of(laws_.begin(), laws_.end(), [](const auto& law) { return law->IsSmooth(); });
}

SupportLawResponse CompositeSupportLaw::Evaluate(double theta, double theta_rate,
                                                 std::span<const double> state_in,
                                                 std::span<double> state_out) const {
  SupportLawResponse sum;
  std::size_t offset = 0;
  for (const auto& law : laws_) {
    const auto count = static_cast<std::size_t>(law->NumInternalStates());
    const auto in = state_in.empty() ? std::span<const double>() : state_in.subspan(offset, count);
    const auto out = state_out.empty() ? std::span<double>() : state_out.subspan(offset, count);
    const SupportLawResponse r = law->Evaluate(theta, theta_rate, in, out);
    sum.moment_Nm += r.moment_Nm;
    sum.d_moment_d_theta_Nm_rad += r.d_moment_d_theta_Nm_rad;
    sum.d_moment_d_theta_rate_Nms_rad += r.d_moment_d_theta_rate_Nms_rad;
    offset += count;
  }
  return sum;
}

PeriodicMoment CompositeSupportLaw::EvaluatePeriodic(const Eigen::VectorXd& theta,
                                                     const Eigen::VectorXd& theta_rate) const {
  const Eigen::Index n = theta.size();
  if (laws_.empty()) return {Eigen::VectorXd::Zero(n), Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n)};
  // The first law's matrices are the sum's start: 0 + x is x to the bit.
  PeriodicMoment sum = laws_.front()->EvaluatePeriodic(theta, theta_rate);
  for (std::size_t l = 1; l < laws_.size(); ++l) {
    const PeriodicMoment part = laws_[l]->EvaluatePeriodic(theta, theta_rate);
    sum.moment_Nm += part.moment_Nm;
    sum.d_moment_d_theta += part.d_moment_d_theta;
    sum.d_moment_d_theta_rate += part.d_moment_d_theta_rate;
  }
  return sum;
}

double CompositeSupportLaw::InitialStiffness_Nm_rad() const {
  double sum = 0.0;
  for (const auto& law : laws_) sum += law->InitialStiffness_Nm_rad();
  return sum;
}

double CompositeSupportLaw::InitialDamping_Nms_rad() const {
  double sum = 0.0;
  for (const auto& law : laws_) sum += law->InitialDamping_Nms_rad();
  return sum;
}

std::vector<LawParameter> CompositeSupportLaw::Parameters() const {
  std::vector<LawParameter> all;
  for (const auto& law : laws_)
    for (auto& p : law->Parameters()) all.push_back(std::move(p));
  return all;
}

Eigen::MatrixXd CompositeSupportLaw::PeriodicParameterJacobian(const Eigen::VectorXd& theta,
                                                               const Eigen::VectorXd& theta_rate) const {
  std::vector<Eigen::MatrixXd> parts;
  Eigen::Index columns = 0;
  for (const auto& law : laws_) {
    parts.push_back(law->PeriodicParameterJacobian(theta, theta_rate));
    columns += parts.back().cols();
  }
  Eigen::MatrixXd jacobian(theta.size(), columns);
  Eigen::Index offset = 0;
  for (const auto& part : parts) {
    jacobian.middleCols(offset, part.cols()) = part;
    offset += part.cols();
  }
  return jacobian;
}

void CompositeSupportLaw::SetParameterValues(std::span<const double> values) {
  std::size_t offset = 0;
  for (const auto& law : laws_) {
    const std::size_t count = law->Parameters().size();
    if (offset + count > values.size())
      throw std::invalid_argument("CompositeSupportLaw: too few parameter values");
    law->SetParameterValues(values.subspan(offset, count));
    offset += count;
  }
  if (offset != values.size()) throw std::invalid_argument("CompositeSupportLaw: too many parameter values");
}

std::unique_ptr<SupportLaw> MakePolynomialSupportLaw(const PolynomialSupportLaw::Coefficients& polynomial,
                                                     const std::optional<JenkinsSupportLaw::Parameters_>& jenkins,
                                                     double one_sided_stiffness_Nm_rad) {
  auto polynomial_law = std::make_unique<PolynomialSupportLaw>(polynomial);
  if (!jenkins && one_sided_stiffness_Nm_rad == 0.0) return polynomial_law;
  auto composite = std::make_unique<CompositeSupportLaw>();
  composite->Add(std::move(polynomial_law));
  if (jenkins) composite->Add(std::make_unique<JenkinsSupportLaw>(*jenkins));
  if (one_sided_stiffness_Nm_rad != 0.0) composite->Add(std::make_unique<OneSidedStiffnessLaw>(one_sided_stiffness_Nm_rad));
  return composite;
}

}  // namespace beamid::hb
