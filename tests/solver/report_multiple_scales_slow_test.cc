// A multiple-scales result file gets from the report's functions what a
// harmonic-balance one does (ComputeReportCurves, as `beamid report`): the
// residual map per step, channel and harmonic — the very whitened residuals
// the fit minimised —, the model's backbone at the reference sensor and its
// frequency response per level, each beside the harmonic-balance fit of the
// same campaign (an independent model of the same beam: they agree to the
// multiple-scales model's own error at these small amplitudes).
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <numbers>

#include <gtest/gtest.h>

#include "solver/estimation/fit_problem.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/multiple_scales_problem.h"
#include "solver/estimation/prediction.h"
#include "solver/estimation/result_file.h"
#include "solver/estimation/result_io.h"
#include "solver/report/report_curves.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::solver {
namespace {

constexpr double kLossFactor = 2e-4;

// The multiple-scales identification test's campaign (small amplitudes,
// where the seed's ordering holds), two levels.
const std::string kScenario = testing::PaperScenarioJson("report of a multiple-scales result", R"([
  {"label": "low", "force_amplitude_N": 0.25, "frequencies_Hz": {"start": 52.6, "stop": 55.6, "step": 0.5}},
  {"label": "high", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 52.6, "stop": 55.6, "step": 0.5}}])", 11);

struct FittedResult {
  ResultFile file;             // as read back from result.json
  Eigen::VectorXd residuals;   // the fit's own whitened residuals at its solution
};

class ReportOfMultipleScalesResult : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    simulated_ = new testing::SimulatedCampaign(kScenario, "beamid_report_ms_slow_test");
    ms_ = new FittedResult(Fit(MultipleScalesFamily(), "ms_result.json"));
    hb_ = new FittedResult(Fit(HarmonicBalanceFamily(), "hb_result.json"));
    const ReportCurveOptions options{.frc_max_points = 240, .backbone_points = 30};
    ms_curves_ = new ReportCurves(ComputeReportCurves(ms_->file, simulated_->campaign, simulated_->phasors, options));
    hb_curves_ = new ReportCurves(ComputeReportCurves(hb_->file, simulated_->campaign, simulated_->phasors, options));
  }
  static void TearDownTestSuite() {
    delete hb_curves_;
    delete ms_curves_;
    delete hb_;
    delete ms_;
    delete simulated_;
  }

  // Identify with the family, write result.json and read it back.
  static FittedResult Fit(const ModelFamily& family, const std::string& name) {
    const FitData fit = MakeFitData(simulated_->campaign, simulated_->phasors, {.channels = {"acc1", "acc2"}});
    const FitData held_out = MakeFitData(simulated_->campaign, simulated_->phasors, {.channels = {"acc3"}});
    const ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
    IdentifyOptions options;
    options.family = &family;
    options.model.beam_loss_factor = kLossFactor;
    const IdentifyResult result = Identify(fit, structure, options);
    const std::unique_ptr<FitProblem> problem = family.MakeProblem(fit, structure, options.model);
    problem->FeasiblePoint(result.starts[result.best_start].scaled_at);  // the winning run's scales
    FitData fit_with_loss = fit;
    fit_with_loss.beam.loss_factor = kLossFactor;
    const auto path = simulated_->folder / name;
    WriteResultFile(path, MakeResultFile(fit_with_loss, held_out, *problem, result, {.family = &family}));
    return {.file = ReadResultFile(path), .residuals = problem->WeightedResiduals(result.x)};
  }

  static testing::SimulatedCampaign* simulated_;
  static FittedResult* ms_;
  static FittedResult* hb_;
  static ReportCurves* ms_curves_;
  static ReportCurves* hb_curves_;
};

testing::SimulatedCampaign* ReportOfMultipleScalesResult::simulated_ = nullptr;
FittedResult* ReportOfMultipleScalesResult::ms_ = nullptr;
FittedResult* ReportOfMultipleScalesResult::hb_ = nullptr;
ReportCurves* ReportOfMultipleScalesResult::ms_curves_ = nullptr;
ReportCurves* ReportOfMultipleScalesResult::hb_curves_ = nullptr;

TEST_F(ReportOfMultipleScalesResult, ResidualMapIsTheFitsOwnWhitenedResiduals) {
  ASSERT_EQ(ms_->file.model.kind, ModelKind::kMultipleScales);
  for (const FittedResult* fitted : {ms_, hb_}) {
    const ResidualMap& map = (fitted == ms_ ? ms_curves_ : hb_curves_)->residuals;
    const int k_fit = fitted->file.model.num_fit_harmonics;
    ASSERT_EQ(map.rows.size(), 2u * k_fit);  // acc1, acc2 × harmonics
    ASSERT_EQ(map.whitened_norm.cols(), static_cast<Eigen::Index>(fitted->file.steps.size()));
    // The fit's residuals are step-major, then channel, then harmonic (Re, Im).
    for (Eigen::Index i = 0; i < map.whitened_norm.cols(); ++i)
      for (Eigen::Index row = 0; row < map.whitened_norm.rows(); ++row) {
        const double expected = fitted->residuals.segment<2>(2 * (i * map.whitened_norm.rows() + row)).norm();
        EXPECT_NEAR(map.whitened_norm(row, i), expected, 1e-6 * expected + 1e-9)
            << (fitted == ms_ ? "ms" : "hb") << " step " << i << " " << map.rows[row];
      }
  }
}

TEST_F(ReportOfMultipleScalesResult, BackboneAtTheReferenceSensorAgreesWithHarmonicBalance) {
  ASSERT_GE(ms_curves_->backbone.size(), 10u);
  ASSERT_FALSE(hb_curves_->backbone.empty());
  // The same beam's backbone by an independent model: at equal amplitude
  // the frequencies agree to 0.1 % (the first mode's share of the response
  // and the seed's ordering error at these amplitudes are far smaller; a
  // wrong position, unit or amplitude range is off by much more).
  int compared = 0;
  for (const AmplitudePoint& p : ms_curves_->backbone) {
    const AmplitudePoint* below = nullptr;
    const AmplitudePoint* above = nullptr;
    for (const AmplitudePoint& q : hb_curves_->backbone) {
      if (q.amplitude <= p.amplitude && (!below || q.amplitude > below->amplitude)) below = &q;
      if (q.amplitude >= p.amplitude && (!above || q.amplitude < above->amplitude)) above = &q;
    }
    if (!below || !above) continue;
    const double t = above->amplitude > below->amplitude
                         ? (p.amplitude - below->amplitude) / (above->amplitude - below->amplitude) : 0.0;
    const double hb_frequency = below->frequency_hz + t * (above->frequency_hz - below->frequency_hz);
    EXPECT_NEAR(p.frequency_hz, hb_frequency, 1e-3 * hb_frequency) << "amplitude " << p.amplitude;
    ++compared;
  }
  EXPECT_GE(compared, 5);
  // The measured phase resonances are set beside it.
  ASSERT_FALSE(ms_curves_->phase_resonance.empty());
  for (const MeasuredResonance& r : ms_curves_->phase_resonance) {
    if (r.amplitude > ms_curves_->backbone.front().amplitude && r.amplitude < ms_curves_->backbone.back().amplitude) {
      EXPECT_TRUE(std::isfinite(r.model_frequency_hz)) << r.level;
    }
  }
}

TEST_F(ReportOfMultipleScalesResult, ResponseCurvesOfEveryLevelAgreeWithHarmonicBalance) {
  ASSERT_EQ(ms_curves_->levels.size(), hb_curves_->levels.size());
  const std::size_t reference = static_cast<std::size_t>(ms_curves_->reference_channel);
  for (std::size_t l = 0; l < ms_curves_->levels.size(); ++l) {
    const LevelCurves& ms = ms_curves_->levels[l];
    const LevelCurves& hb = hb_curves_->levels[l];
    SCOPED_TRACE(ms.level);
    ASSERT_GE(ms.model.size(), 20u);
    EXPECT_TRUE(ms.model_complete) << ms.model_message;
    // The curves' peaks: same frequency to 0.1 %, same height to 2 % (the
    // multiple-scales identification test's prediction tolerance).
    auto peak = [&](const LevelCurves& level) {
      const ModelCurvePoint* best = &level.model.front();
      for (const ModelCurvePoint& p : level.model)
        if (p.amplitude[reference] > best->amplitude[reference]) best = &p;
      return *best;
    };
    const ModelCurvePoint ms_peak = peak(ms), hb_peak = peak(hb);
    EXPECT_NEAR(ms_peak.frequency_hz, hb_peak.frequency_hz, 1e-3 * hb_peak.frequency_hz);
    EXPECT_NEAR(ms_peak.amplitude[reference], hb_peak.amplitude[reference], 0.02 * hb_peak.amplitude[reference]);
    // And it is the multiple-scales model's own curve: every point is one
    // of that model's steady states at its frequency (the acceleration of
    // h1 at the reference sensor, to the last digits).
    const IdentifiedModel model = ToIdentifiedModel(ms_->file);
    const hb::MultipleScalesModel direct =
        MakeMultipleScalesModel(model.beam.beam, model.force_position_m, model.structure, model.structure.Values());
    const ReportChannel& channel = ms_curves_->channels[reference];
    for (std::size_t n = 0; n < ms.model.size(); n += 7) {
      const ModelCurvePoint& p = ms.model[n];
      const double omega = 2 * std::numbers::pi * p.frequency_hz;
      double nearest = std::numeric_limits<double>::infinity();
      for (const std::complex<double> u : direct.Solve(omega, ms.force_amplitude_N)) {
        const double a = std::abs(direct.Response(channel.position_m, u, omega, ms.force_amplitude_N).h1_m) * omega * omega;
        nearest = std::min(nearest, std::abs(a - p.amplitude[reference]));
      }
      EXPECT_LT(nearest, 1e-9 * p.amplitude[reference]) << p.frequency_hz << " Hz";
    }
  }
}

}  // namespace
}  // namespace beamid::solver
