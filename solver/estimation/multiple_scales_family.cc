// The seed's multiple-scales family: MultipleScalesProblem to fit, and for
// prediction the root of the amplitude equation nearest the fitted modal
// phasor U (the branch the test was on), harmonics 0..3 from the force's
// fundamental. Its frequency response is the roots of the amplitude
// equation on a grid of frequencies, joined into one curve; its backbone
// the model's own (undamped, unforced Ω(|U|)) seen at the sensor.
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include "hb/errors.h"
#include "hb/multiple_scales.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/multiple_scales_problem.h"
#include "solver/estimation/prediction.h"
#include "solver/estimation/sensor_backbone.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

MultipleScalesProblemOptions ProblemOptions(const ModelOptions& options) {
  return {.beam_loss_factor = options.beam_loss_factor};
}

hb::MultipleScalesModel IdentifiedMultipleScales(const IdentifiedModel& model) {
  return MakeMultipleScalesModel(model.beam.beam, model.force_position_m, model.structure, model.structure.Values());
}

// The roots of one frequency of the grid: one, or three (small, middle =
// unstable, large) inside a fold.
struct GridRoots {
  double omega_rad_s = 0.0;
  std::vector<Complex> u;
};

// The branches of the grid in continuation order: along the frequency, and
// across a fold back along the middle (unstable) roots to the other outer
// branch. A closed loop of roots that never joins the curve is left out (a
// continuation would not find it either).
std::vector<std::pair<const GridRoots*, int>> ContinuationOrder(const std::vector<GridRoots>& grid) {
  std::vector<std::pair<const GridRoots*, int>> order;  // (frequency, root index)
  const int n = static_cast<int>(grid.size());
  auto nearest_outer = [](const GridRoots& g, Complex u) {
    return std::abs(g.u.front() - u) <= std::abs(g.u.back() - u) ? 0 : 2;
  };
  for (int j = 0; j < n;) {
    if (grid[j].u.size() == 1) {
      order.push_back({&grid[j], 0});
      ++j;
      continue;
    }
    int b = j;  // [j, b]: a fold region, three roots at each frequency
    while (b + 1 < n && grid[b + 1].u.size() == 3) ++b;
    const int entry = j > 0 ? nearest_outer(grid[j], grid[j - 1].u[0]) : -1;
    const int exit = b + 1 < n ? nearest_outer(grid[b], grid[b + 1].u[0]) : -1;
    const int first = entry >= 0 ? entry : (exit >= 0 ? 2 - exit : 0);
    const int last = exit >= 0 ? exit : 2 - first;
    for (int i = j; i <= b; ++i) order.push_back({&grid[i], first});
    if (first != last) {
      for (int i = b; i >= j; --i) order.push_back({&grid[i], 1});
      for (int i = j; i <= b; ++i) order.push_back({&grid[i], last});
    }
    j = b + 1;
  }
  return order;
}

class MultipleScalesFamilyImpl final : public ModelFamily {
 public:
  ModelKind Kind() const override { return ModelKind::kMultipleScales; }
  std::string Description() const override { return "multiple scales"; }
  std::string StateName() const override { return "modal_phasor_m"; }
  int StateSize(int) const override { return 1; }
  int ModelHarmonics(int) const override { return 3; }

  // The problem's constructor refuses sensor masses, more than 3 fitted
  // harmonics and another law.
  void CheckCanHold(const FitData& data, const ModelStructure& structure, const ModelOptions& options) const override {
    options.Validate();
    const MultipleScalesProblem check(data, structure, ProblemOptions(options));
  }
  std::unique_ptr<FitProblem> MakeProblem(const FitData& data, const ModelStructure& structure,
                                          const ModelOptions& options) const override {
    return std::make_unique<MultipleScalesProblem>(data, structure, ProblemOptions(options));
  }

  std::vector<Eigen::VectorXcd> DisplacementAt(const IdentifiedModel& model, const std::vector<double>& p,
                                               double position_m, std::vector<bool>* converged) const override {
    const hb::MultipleScalesModel ms =
        MakeMultipleScalesModel(model.beam.beam, model.force_position_m, model.structure, p);
    std::vector<Eigen::VectorXcd> out;
    for (std::size_t i = 0; i < model.steps.size(); ++i) {
      const IdentifiedStep& s = model.steps[i];
      Eigen::VectorXcd y = Eigen::VectorXcd::Zero(4);
      bool solved = false;
      try {
        const std::vector<Complex> roots = ms.Solve(s.omega_rad_s, s.force_N[1]);
        const Complex fitted = s.state[0];
        const Complex u = *std::min_element(roots.begin(), roots.end(), [&](Complex a, Complex b) {
          return std::abs(a - fitted) < std::abs(b - fitted);
        });
        const hb::MultipleScalesModel::Harmonics h = ms.Response(position_m, u, s.omega_rad_s, s.force_N[1]);
        y << h.h0_m, h.h1_m, h.h2_m, h.h3_m;
        solved = true;
      } catch (const std::runtime_error&) {
        // An internal resonance at 2Ω or 3Ω: the model has no steady state here.
      }
      if (converged) (*converged)[i] = solved;
      out.push_back(y);
    }
    return out;
  }

  std::vector<Eigen::MatrixXcd> FittedDisplacements(const IdentifiedModel& model,
                                                    const std::vector<double>& positions_m) const override {
    const hb::MultipleScalesModel ms = IdentifiedMultipleScales(model);
    std::vector<Eigen::MatrixXcd> out;
    for (const IdentifiedStep& s : model.steps) {
      Eigen::MatrixXcd y(positions_m.size(), 4);
      for (std::size_t c = 0; c < positions_m.size(); ++c) {
        const hb::MultipleScalesModel::Harmonics h = ms.Response(positions_m[c], s.state[0], s.omega_rad_s, s.force_N[1]);
        y.row(static_cast<Eigen::Index>(c)) << h.h0_m, h.h1_m, h.h2_m, h.h3_m;
      }
      out.push_back(y);
    }
    return out;
  }

  // Every root of the amplitude equation on an even grid of a third of
  // max_points frequencies (a fold visits the grid three times).
  ModelResponse FrequencyResponse(const IdentifiedModel& model, double force_amplitude_N, double omega_start_rad_s,
                                  double omega_end_rad_s, int max_points, const std::vector<double>& positions_m,
                                  const std::function<void(double)>& on_fraction) const override {
    const hb::MultipleScalesModel ms = IdentifiedMultipleScales(model);
    const Complex force(force_amplitude_N, 0.0);
    const int n = std::max(2, max_points / 3);
    std::vector<GridRoots> grid;
    ModelResponse response;
    for (int j = 0; j < n; ++j) {
      const double omega = omega_start_rad_s + (omega_end_rad_s - omega_start_rad_s) * j / (n - 1);
      try {
        std::vector<Complex> roots = ms.Solve(omega, force);
        if (roots.size() == 1 || roots.size() == 3) grid.push_back({.omega_rad_s = omega, .u = std::move(roots)});
      } catch (const std::runtime_error& error) {
        // An internal resonance at 2Ω or 3Ω: no steady state of this model there.
        response.reached_end = false;
        if (response.message.empty()) response.message = error.what();
      }
      if (on_fraction) on_fraction((j + 1.0) / n);
    }
    for (const auto& [g, root] : ContinuationOrder(grid)) {
      ModelResponsePoint point{.omega_rad_s = g->omega_rad_s, .stable = root != 1};
      point.displacement_m.resize(static_cast<Eigen::Index>(positions_m.size()), 4);
      for (std::size_t c = 0; c < positions_m.size(); ++c) {
        const auto y = ms.Response(positions_m[c], g->u[root], g->omega_rad_s, force);
        point.displacement_m.row(static_cast<Eigen::Index>(c)) << y.h0_m, y.h1_m, y.h2_m, y.h3_m;
      }
      response.points.push_back(std::move(point));
    }
    return response;
  }

  // The model's backbone Ω(a), a = |U| (undamped, unforced), at the sensor:
  // |Y_1| = |h1(x; U = a, Ω, F = 0)|, over the steps' |U|.
  std::vector<SensorBackbonePoint> BackboneAtSensor(const IdentifiedModel& model, double sensor_position_m,
                                                    int num_points) const override {
    const double u_max = LargestStateAmplitude(model, 0);
    if (u_max <= 0.0) return {};
    const hb::MultipleScalesModel ms = IdentifiedMultipleScales(model);
    std::vector<SensorBackbonePoint> out;
    std::string failure;
    for (int k = 0; k < num_points; ++k) {
      const double a = u_max / 30.0 + (1.3 * u_max - u_max / 30.0) * k / std::max(1, num_points - 1);
      try {
        const double omega = ms.Backbone_rad_s(a);
        out.push_back({.amplitude_m = std::abs(ms.Response(sensor_position_m, a, omega, 0.0).h1_m),
                       .frequency_hz = omega / (2 * std::numbers::pi)});
      } catch (const std::runtime_error& error) {
        failure = error.what();  // outside the model's range of amplitudes
      }
    }
    if (out.empty()) throw NumericalError("model backbone: " + failure);
    return out;
  }

  // U is the first mode's amplitude, not the rotation's harmonics.
  Eigen::VectorXcd SupportRotation_rad(const Eigen::VectorXcd&) const override { return {}; }
};

}  // namespace

const ModelFamily& MultipleScalesFamily() {
  static const MultipleScalesFamilyImpl family;
  return family;
}

}  // namespace beamid::solver
