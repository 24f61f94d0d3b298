// Support laws: the moment M that the contact support exerts against the
// beam's end rotation θ = y'(L). The beam's boundary condition is
//     EI·y''(L) = −M(θ, θ̇, history)          (docs/derivation.md, corrected seed Eq. 3)
// A law is evaluated two ways, sharing one implementation of its physics:
//  - incrementally in time (the time-domain simulator): Evaluate() maps the
//    current θ, θ̇ and the internal state at the previous step to the moment,
//    its consistent tangents and the new state;
//  - on one steady-state period sampled at N equispaced instants (harmonic
//    balance, alternating frequency–time): EvaluatePeriodic() returns M(t_n)
//    on the converged periodic loop and the Jacobians ∂M(t_n)/∂θ(t_m) and
//    ∂M(t_n)/∂θ̇(t_m).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace beamid::hb {

struct SupportLawResponse {
  double moment_Nm = 0.0;
  double d_moment_d_theta_Nm_rad = 0.0;
  double d_moment_d_theta_rate_Nms_rad = 0.0;
};

// Moment over one sampled period and its Jacobians (N × N; diagonal for a
// memoryless law).
struct PeriodicMoment {
  Eigen::VectorXd moment_Nm;
  Eigen::MatrixXd d_moment_d_theta;
  Eigen::MatrixXd d_moment_d_theta_rate;
};

// A named physical parameter of a law, in SI.
struct LawParameter {
  std::string name;   // e.g. "k3"
  double value = 0.0;
  std::string unit;   // e.g. "N*m/rad^3"
};

class SupportLaw {
 public:
  virtual ~SupportLaw() = default;

  virtual std::string Name() const = 0;
  virtual std::unique_ptr<SupportLaw> Clone() const = 0;

  // Internal state variables carried between time steps (0: memoryless).
  virtual int NumInternalStates() const { return 0; }

  // False for a law with corners (a slider that sticks and slips, a contact
  // that opens): its moment over a period has harmonics decaying only like
  // 1/k², which alias onto the low ones in the alternating frequency–time
  // step unless the period is sampled densely (hb/harmonic_balance.h). A
  // memoryless polynomial is smooth; a hysteretic law has corners.
  virtual bool IsSmooth() const { return NumInternalStates() == 0; }

  // One time step. state_in/state_out have NumInternalStates() entries; the
  // tangents are consistent with the update (for Newton in the integrator).
  virtual SupportLawResponse Evaluate(double theta_rad, double theta_rate_rad_s,
                                      std::span<const double> state_in,
                                      std::span<double> state_out) const = 0;

  // One steady-state period, N = theta_rad.size() equispaced samples. The
  // default serves memoryless laws; hysteretic laws override it.
  virtual PeriodicMoment EvaluatePeriodic(const Eigen::VectorXd& theta_rad,
                                          const Eigen::VectorXd& theta_rate_rad_s) const;

  // ∂M(t_n)/∂p_j on one steady-state period (N × number of parameters), for
  // identification. The default differentiates EvaluatePeriodic by central
  // differences in each parameter; laws linear in their parameters override it.
  virtual Eigen::MatrixXd PeriodicParameterJacobian(const Eigen::VectorXd& theta_rad,
                                                    const Eigen::VectorXd& theta_rate_rad_s) const;

  // Tangent stiffness and viscous damping at θ = θ̇ = 0 on first loading
  // [N·m/rad], [N·m·s/rad]: the linear behaviour at vanishing amplitude.
  virtual double InitialStiffness_Nm_rad() const = 0;
  virtual double InitialDamping_Nms_rad() const { return 0.0; }

  // Named parameters (for reports and identification) and their update, in
  // the order Parameters() lists them.
  virtual std::vector<LawParameter> Parameters() const = 0;
  virtual void SetParameterValues(std::span<const double> values) = 0;
};

// The seed's law: M = k1·θ + k2·θ² + k3·θ³ + c·θ̇.
class PolynomialSupportLaw final : public SupportLaw {
 public:
  struct Coefficients {
    double k1_Nm_rad = 0.0;
    double k2_Nm_rad2 = 0.0;
    double k3_Nm_rad3 = 0.0;
    double c_Nms_rad = 0.0;
  };
  explicit PolynomialSupportLaw(const Coefficients& coefficients) : coefficients_(coefficients) {}
  const Coefficients& coefficients() const { return coefficients_; }

  std::string Name() const override { return "polynomial"; }
  std::unique_ptr<SupportLaw> Clone() const override;
  SupportLawResponse Evaluate(double theta_rad, double theta_rate_rad_s,
                              std::span<const double> state_in,
                              std::span<double> state_out) const override;
  double InitialStiffness_Nm_rad() const override { return coefficients_.k1_Nm_rad; }
  double InitialDamping_Nms_rad() const override { return coefficients_.c_Nms_rad; }
  std::vector<LawParameter> Parameters() const override;
  void SetParameterValues(std::span<const double> values) override;
  // Exact: M is linear in (k1, k2, k3, c), the columns are θ, θ², θ³, θ̇.
  Eigen::MatrixXd PeriodicParameterJacobian(const Eigen::VectorXd& theta_rad,
                                            const Eigen::VectorXd& theta_rate_rad_s) const override;

 private:
  Coefficients coefficients_;
};

// Jenkins element: a spring k_t in series with a Coulomb slider that slips at
// |M| = M_slip. The state is the slider's rotation θ_s; M = k_t·(θ − θ_s) while
// sticking. Small amplitudes stick (linear, no dissipation); large ones slip
// (softening, friction damping).
class JenkinsSupportLaw final : public SupportLaw {
 public:
  struct Parameters_ {
    double stiffness_Nm_rad = 0.0;   // k_t
    double slip_moment_Nm = 0.0;     // M_slip > 0
  };
  explicit JenkinsSupportLaw(const Parameters_& parameters);

  std::string Name() const override { return "jenkins"; }
  std::unique_ptr<SupportLaw> Clone() const override;
  int NumInternalStates() const override { return 1; }
  SupportLawResponse Evaluate(double theta_rad, double theta_rate_rad_s,
                              std::span<const double> state_in,
                              std::span<double> state_out) const override;
  // The converged loop: two passes over the period, the second starting from
  // the slider state the first ended in; exact derivatives of that recursion.
  PeriodicMoment EvaluatePeriodic(const Eigen::VectorXd& theta_rad,
                                  const Eigen::VectorXd& theta_rate_rad_s) const override;
  double InitialStiffness_Nm_rad() const override { return parameters_.stiffness_Nm_rad; }
  std::vector<LawParameter> Parameters() const override;
  void SetParameterValues(std::span<const double> values) override;

 private:
  Parameters_ parameters_;
};

// A one-sided (asymmetric) stiffness: M = k_a·max(θ, 0). In parallel with
// the polynomial law the support is k1 + k_a stiff for positive rotation and
// k1 for negative rotation (a contact whose patch grows as the beam rotates
// into the rod, and lifts off the other way). Its moment is a fixed fraction
// of |θ|'s even harmonics at every amplitude, which k2·θ² (∝ θ²) cannot
// follow over several levels. k_a may be negative (softer for positive θ).
class OneSidedStiffnessLaw final : public SupportLaw {
 public:
  explicit OneSidedStiffnessLaw(double stiffness_Nm_rad) : stiffness_Nm_rad_(stiffness_Nm_rad) {}
  double stiffness_Nm_rad() const { return stiffness_Nm_rad_; }

  std::string Name() const override { return "one_sided"; }
  std::unique_ptr<SupportLaw> Clone() const override;
  SupportLawResponse Evaluate(double theta_rad, double theta_rate_rad_s,
                              std::span<const double> state_in,
                              std::span<double> state_out) const override;
  // The kink at θ = 0 (whatever k_a: an identification changes it after
  // the balance is set up).
  bool IsSmooth() const override { return false; }
  // The small-amplitude mean of the two senses' stiffness.
  double InitialStiffness_Nm_rad() const override { return 0.5 * stiffness_Nm_rad_; }
  std::vector<LawParameter> Parameters() const override;
  void SetParameterValues(std::span<const double> values) override;
  // Exact: the column is max(θ, 0).
  Eigen::MatrixXd PeriodicParameterJacobian(const Eigen::VectorXd& theta_rad,
                                            const Eigen::VectorXd& theta_rate_rad_s) const override;

 private:
  double stiffness_Nm_rad_ = 0.0;
};

// The sum of several laws acting in parallel (e.g. polynomial + Jenkins).
class CompositeSupportLaw final : public SupportLaw {
 public:
  CompositeSupportLaw() = default;
  CompositeSupportLaw(const CompositeSupportLaw& other);
  CompositeSupportLaw& operator=(const CompositeSupportLaw&) = delete;
  void Add(std::unique_ptr<SupportLaw> law);
  const std::vector<std::unique_ptr<SupportLaw>>& laws() const { return laws_; }

  std::string Name() const override;
  std::unique_ptr<SupportLaw> Clone() const override;
  int NumInternalStates() const override;
  bool IsSmooth() const override;  // all its laws are
  SupportLawResponse Evaluate(double theta_rad, double theta_rate_rad_s,
                              std::span<const double> state_in,
                              std::span<double> state_out) const override;
  PeriodicMoment EvaluatePeriodic(const Eigen::VectorXd& theta_rad,
                                  const Eigen::VectorXd& theta_rate_rad_s) const override;
  double InitialStiffness_Nm_rad() const override;
  double InitialDamping_Nms_rad() const override;
  // The laws' parameters in order (names are unique across the laws).
  std::vector<LawParameter> Parameters() const override;
  void SetParameterValues(std::span<const double> values) override;
  Eigen::MatrixXd PeriodicParameterJacobian(const Eigen::VectorXd& theta_rad,
                                            const Eigen::VectorXd& theta_rate_rad_s) const override;

 private:
  std::vector<std::unique_ptr<SupportLaw>> laws_;
};

// The polynomial law, with a Jenkins element and a one-sided stiffness in
// parallel when they are given (non-zero).
std::unique_ptr<SupportLaw> MakePolynomialSupportLaw(const PolynomialSupportLaw::Coefficients& polynomial,
                                                     const std::optional<JenkinsSupportLaw::Parameters_>& jenkins,
                                                     double one_sided_stiffness_Nm_rad = 0.0);

}  // namespace beamid::hb
