#include "solver/estimation/prediction.h"

#include "solver/estimation/result_io.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "hb/errors.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

}  // namespace

double LargestStateAmplitude(const IdentifiedModel& model, int entry) {
  double largest = 0.0;
  for (const IdentifiedStep& s : model.steps)
    if (s.state.size() > entry) largest = std::max(largest, std::abs(s.state[entry]));
  return largest;
}

hb::HarmonicBalance IdentifiedHarmonicBalance(const IdentifiedModel& model, const std::vector<double>& p) {
  ModelStructure structure = model.structure;
  if (!p.empty()) structure.SetValues(p);
  const hb::LinearBeam beam(structure.ApplyLinear(model.beam), model.force_position_m);
  return hb::HarmonicBalance(beam, *structure.law, {.num_harmonics = model.num_harmonics});
}

IdentifiedModel ReadIdentifiedModel(const std::filesystem::path& result_file) {
  const ResultFile result = ReadResultFile(result_file);
  try {
    return ToIdentifiedModel(result);
  } catch (const std::invalid_argument& e) {
    throw InputError(result_file.string() + ": " + e.what());
  }
}

IdentifiedModel ToIdentifiedModel(const ResultFile& result) {
  IdentifiedModel model;
  model.family = &FindModelFamily(result.model.kind);
  model.beam.beam = result.model.beam;
  model.beam.attachments.point_masses = result.model.sensor_masses;
  model.force_position_m = result.model.force_position_m;
  model.num_harmonics = result.model.num_harmonics;
  if (result.model.law != "polynomial")
    throw InputError("model.law '" + result.model.law + "': only the polynomial law can be predicted so far");
  model.structure = PolynomialModel({});
  for (const auto& name : result.linear_parameters) {
    try {
      model.structure.linear.push_back(LinearParameterByName(name, 0.0));
    } catch (const std::invalid_argument& e) {
      throw InputError("linear_parameters: " + std::string(e.what()));
    }
  }
  // The values go to the structure by position: the names must line up.
  std::vector<std::string> names;
  std::vector<double> values;
  for (const auto& p : result.parameters) {
    names.push_back(p.name);
    values.push_back(p.value);
  }
  if (names != model.structure.Names()) {
    std::string expected;
    for (const auto& name : model.structure.Names()) expected += (expected.empty() ? "" : ", ") + name;
    throw InputError("parameter_order: the " + result.model.law + " law with linear_parameters takes the parameters " +
                     expected);
  }
  model.structure.SetValues(values);
  model.covariance = result.covariance;
  for (const auto& s : result.steps)
    model.steps.push_back({.level = s.level,
                           .file = s.file,
                           .omega_rad_s = 2 * std::numbers::pi * s.frequency_hz,
                           .force_N = s.force_N,
                           .state = s.state});
  return model;
}

std::vector<PredictedStep> PredictAt(const IdentifiedModel& model, double position_m, int samples_per_period) {
  if (!(position_m >= 0.0 && position_m <= model.beam.beam.length_m))
    throw std::invalid_argument("--x " + std::to_string(position_m) + " m lies outside the beam [0, " +
                                std::to_string(model.beam.beam.length_m) + "] m");
  const std::vector<double> p = model.structure.Values();
  const int np = static_cast<int>(p.size()), h = model.num_harmonics;
  std::vector<bool> converged(model.steps.size(), true);
  const std::vector<Eigen::VectorXcd> nominal = model.family->DisplacementAt(model, p, position_m, &converged);
  // ∂Y/∂p_j, j = 1..P, central differences of the re-solved model.
  std::vector<std::vector<Eigen::VectorXcd>> derivative(np);
  const auto bounds = model.structure.Bounds();
  for (int j = 0; j < np; ++j) {
    const double step = 1e-4 * std::max(std::abs(p[j]), bounds[j].typical * 1e-2);
    // One-sided at a bound (a loss factor fitted to ~0 must not go negative).
    std::vector<double> up = p, down = p;
    up[j] = std::min(p[j] + step, bounds[j].upper);
    down[j] = std::max(p[j] - step, bounds[j].lower);
    const auto y_up = model.family->DisplacementAt(model, up, position_m, nullptr);
    const auto y_down = model.family->DisplacementAt(model, down, position_m, nullptr);
    for (std::size_t i = 0; i < model.steps.size(); ++i)
      derivative[j].push_back((y_up[i] - y_down[i]) / (up[j] - down[j]));
  }
  std::vector<PredictedStep> out;
  for (std::size_t i = 0; i < model.steps.size(); ++i) {
    const IdentifiedStep& s = model.steps[i];
    PredictedStep step{.level = s.level, .file = s.file, .frequency_hz = s.omega_rad_s / (2 * std::numbers::pi),
                       .displacement_m = nominal[i], .converged = converged[i]};
    step.std_real_m.resize(h + 1);
    step.std_imag_m.resize(h + 1);
    Eigen::MatrixXd jr(h + 1, np), ji(h + 1, np);
    for (int j = 0; j < np; ++j) {
      jr.col(j) = derivative[j][i].real();
      ji.col(j) = derivative[j][i].imag();
    }
    step.std_real_m = (jr * model.covariance * jr.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
    step.std_imag_m = (ji * model.covariance * ji.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
    // a(t) = Σ Re(−(kω)² Y_k e^{ikωt}); its sensitivity row per sample.
    step.time_s.resize(samples_per_period);
    step.acceleration_m_s2.resize(samples_per_period);
    step.acceleration_std_m_s2.resize(samples_per_period);
    for (int n = 0; n < samples_per_period; ++n) {
      const double t = 2 * std::numbers::pi / s.omega_rad_s * n / samples_per_period;
      step.time_s[n] = t;
      double a = 0.0;
      Eigen::RowVectorXd sensitivity = Eigen::RowVectorXd::Zero(np);
      for (int k = 1; k <= h; ++k) {
        const double kw = k * s.omega_rad_s;
        const Complex e = std::polar(1.0, kw * t);
        a += std::real(-kw * kw * nominal[i][k] * e);
        for (int j = 0; j < np; ++j) sensitivity[j] += std::real(-kw * kw * derivative[j][i][k] * e);
      }
      step.acceleration_m_s2[n] = a;
      step.acceleration_std_m_s2[n] = std::sqrt(std::max(0.0, (sensitivity * model.covariance * sensitivity.transpose())(0, 0)));
    }
    out.push_back(std::move(step));
  }
  return out;
}

}  // namespace beamid::solver
