// Statistics of the misfit location on synthetic phasors drawn at the
// whitening level (this tests the tests, not a model): a correct model
// raises no family-wise alarm more often than the nominal significance, and
// a misfit is found where it was put and described by its kind: a changed
// stiffness as stiffness-like, a changed damping as dissipation-like.
#include "solver/diagnosis/misfit_location.h"

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "hb/errors.h"
#include "solver/diagnosis/diagnosis_io.h"
#include "solver/estimation/chi_square.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

// P(χ²(ν) ≥ x) from statistical tables (independent of the code).
TEST(ChiSquareUpperTail, MatchesTabulatedQuantiles) {
  EXPECT_NEAR(ChiSquareUpperTail(3.841458820694124, 1), 0.05, 1e-12);
  EXPECT_NEAR(ChiSquareUpperTail(6.634896601021214, 1), 0.01, 1e-12);
  EXPECT_NEAR(ChiSquareUpperTail(18.307038053275146, 10), 0.05, 1e-12);
  EXPECT_NEAR(ChiSquareUpperTail(124.34211340400407, 100), 0.05, 1e-11);
  // Tabulated to 3 decimals: ±5e-4 in x is ±1.4e-7 in p.
  EXPECT_NEAR(ChiSquareUpperTail(1106.969, 1000), 0.01, 2e-7);
  EXPECT_DOUBLE_EQ(ChiSquareUpperTail(0.0, 4), 1.0);
  EXPECT_DOUBLE_EQ(ChiSquareUpperTail(5.0, 0), 1.0);
}

// Q(n, x) for integer n is the Poisson sum e^{−x} Σ_{j<n} x^j/j!.
TEST(RegularizedUpperGamma, EqualsThePoissonSumForIntegerOrders) {
  for (int n : {1, 2, 3, 7, 20, 60, 500}) {
    for (double x : {0.01, 0.5, 1.0, 3.0, 10.0, 25.0, 70.0, 150.0, 480.0, 553.0}) {
      double term = std::exp(-x), sum = 0.0;
      for (int j = 0; j < n; ++j) sum += term, term *= x / (j + 1);
      EXPECT_NEAR(RegularizedUpperGamma(n, x), sum, 1e-13 + 1e-12 * sum) << "n " << n << " x " << x;
    }
  }
  // Half-integer: Q(1/2, x) = erfc(√x).
  for (double x : {0.01, 0.3, 2.0, 9.0}) EXPECT_NEAR(RegularizedUpperGamma(0.5, x), std::erfc(std::sqrt(x)), 1e-13);
  EXPECT_THROW(RegularizedUpperGamma(0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(RegularizedUpperGamma(1.0, -1.0), std::invalid_argument);
}

constexpr int kHarmonics = 5;
constexpr int kFitted = 3;
const std::vector<std::string> kLevels{"low", "mid", "high"};
const std::vector<double> kForceN{1.0, 4.0, 9.0};

// A one-mode response seen by three accelerometers, with a small third
// harmonic; each (channel, harmonic, step) gets its own anisotropic noise
// covariance L·Lᵀ. The measurements of acc2 may come from a mode whose
// stiffness (ω_n²) and damping (ζ) differ from the model's by relative
// amounts that grow with the force level: that is the misfit to locate.
struct Synthetic {
  FitData data;
  std::vector<Eigen::MatrixXcd> model;
};

struct Acc2Truth {
  double stiffness_change_at_top = 0.0;  // δ(ω_n²)/ω_n² at the top level, ∝ F²
  double damping_change_at_top = 0.0;    // δζ/ζ at the top level, ∝ F²
};

Synthetic MakeSynthetic(std::mt19937& rng, const Acc2Truth& acc2 = {}) {
  Synthetic s;
  s.data.num_fit_harmonics = kHarmonics;
  s.data.levels = kLevels;
  const std::vector<double> shape{0.3, 0.8, 0.4};
  for (std::size_t c = 0; c < shape.size(); ++c)
    s.data.channels.push_back({.channel = "acc" + std::to_string(c + 1), .position_m = 0.1 + 0.2 * c});
  std::uniform_real_distribution<double> uniform(0.7, 1.3);
  const double omega_n = 2 * std::numbers::pi * 54.0, zeta = 0.01;
  const auto receptance = [](double omega, double natural2, double damping) {
    return 1.0 / (natural2 - omega * omega + Complex(0.0, 2 * damping * std::sqrt(natural2) * omega));
  };
  for (std::size_t l = 0; l < kLevels.size(); ++l) {
    const double growth = std::pow(kForceN[l] / kForceN.back(), 2);
    for (double f_hz = 50.0; f_hz <= 58.0; f_hz += 0.5) {
      FitStep step;
      step.level = kLevels[l];
      step.omega_rad_s = 2 * std::numbers::pi * f_hz;
      step.force_N = Eigen::VectorXcd::Zero(kHarmonics + 1);
      step.force_N[1] = kForceN[l];
      const double w = step.omega_rad_s;
      Eigen::MatrixXcd y = Eigen::MatrixXcd::Zero(3, kHarmonics);
      step.whitening.resize(3);
      step.std_amplitude.resize(3, kHarmonics);
      for (int c = 0; c < 3; ++c) {
        y(c, 0) = -w * w * shape[c] * receptance(w, omega_n * omega_n, zeta) * step.force_N[1];
        y(c, 2) = 1e-3 * std::abs(y(c, 0)) * std::pow(std::abs(y(c, 0)) / 100.0, 2) * std::polar(1.0, 0.4);
        for (int k = 0; k < kHarmonics; ++k) {
          // σ grows a little with the signal, as with relative noise.
          const double sigma = 0.01 + 1e-3 * std::abs(y(c, k));
          Eigen::Matrix2d chol;
          chol << sigma * uniform(rng), 0.0, 0.3 * sigma * (uniform(rng) - 1.0), sigma * uniform(rng);
          step.whitening[c].push_back(chol.inverse());
          step.std_amplitude(c, k) = std::sqrt(0.5 * (chol.row(0).squaredNorm() + chol.row(1).squaredNorm()));
        }
      }
      step.measured = y;
      step.measured(1, 0) = -w * w * shape[1] * step.force_N[1] *
                            receptance(w, omega_n * omega_n * (1.0 + acc2.stiffness_change_at_top * growth),
                                       zeta * (1.0 + acc2.damping_change_at_top * growth));
      s.data.steps.push_back(std::move(step));
      s.model.push_back(y);
    }
  }
  return s;
}

// Adds noise of each pair's own covariance: measured −= L·z, so r = z.
void AddNoise(Synthetic& s, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  for (FitStep& step : s.data.steps) {
    for (int c = 0; c < step.measured.rows(); ++c) {
      for (int k = 0; k < step.measured.cols(); ++k) {
        const Eigen::Vector2d z(normal(rng), normal(rng));
        const Eigen::Vector2d e = step.whitening[c][k].inverse() * z;
        step.measured(c, k) -= Complex(e[0], e[1]);
      }
    }
  }
}

const hb::LinearBeamModel kUnusedBeam{};
const MisfitLocationOptions kNoLoops{.analyse_loops = false};

TEST(LocateMisfit, ACorrectModelRaisesNoFamilyWiseAlarmMoreOftenThanTheSignificance) {
  std::mt19937 rng(11);
  const Synthetic clean = MakeSynthetic(rng);
  constexpr int kDraws = 2000;
  for (double alpha : {0.01, 0.05}) {
    int alarms = 0, groups_below = 0, groups = 0;
    for (int draw = 0; draw < kDraws; ++draw) {
      Synthetic noisy = clean;
      AddNoise(noisy, rng);
      MisfitLocationOptions options = kNoLoops;
      options.family_significance = alpha;
      options.model_relative_error = 0.0;  // the noise exactly as stated
      const MisfitLocation location = LocateMisfit(noisy.data, noisy.model, kFitted, kUnusedBeam, options);
      alarms += location.significant;
      for (const auto& g : location.groups) groups_below += g.p_value < alpha, ++groups;
    }
    const double rate = static_cast<double>(alarms) / kDraws;
    const double raw = static_cast<double>(groups_below) / groups;
    std::printf("alpha %.2f: family-wise false alarms %d / %d (%.4f); single groups below alpha %.4f\n", alpha, alarms,
                kDraws, rate, raw);
    // Holm keeps the family-wise rate ≤ α under any dependence of the groups;
    // the observed rate may exceed it by the binomial scatter of the draws.
    EXPECT_LE(rate, alpha + 2.0 * std::sqrt(alpha * (1.0 - alpha) / kDraws));
    // The single tests are calibrated (p uniform under noise): ±4σ of a
    // binomial over the groups (which are correlated, hence the margin).
    EXPECT_NEAR(raw, alpha, 4.0 * std::sqrt(alpha / groups) + 0.2 * alpha);
  }
}

TEST(LocateMisfit, ANoiseOnlyFindingSaysNoSignificantDiscrepancy) {
  std::mt19937 rng(3);
  Synthetic s = MakeSynthetic(rng);
  AddNoise(s, rng);
  const MisfitLocation location = LocateMisfit(s.data, s.model, kFitted, kUnusedBeam, kNoLoops);
  ASSERT_FALSE(location.significant);
  ASSERT_FALSE(location.findings.empty());
  EXPECT_NE(location.findings[0].find("No significant discrepancy"), std::string::npos) << location.findings[0];
  EXPECT_NE(location.findings[0].find("0.1 % of the fundamental allowed"), std::string::npos) << location.findings[0];
  // Without an allowance the finding says what the residuals were weighed by.
  MisfitLocationOptions stated = kNoLoops;
  stated.model_relative_error = 0.0;
  const MisfitLocation against_noise = LocateMisfit(s.data, s.model, kFitted, kUnusedBeam, stated);
  EXPECT_NE(against_noise.findings[0].find("against the phasors' stated uncertainty alone"), std::string::npos)
      << against_noise.findings[0];
}

Synthetic WithAcc2Truth(const Acc2Truth& truth, std::mt19937& rng) {
  Synthetic s = MakeSynthetic(rng, truth);
  AddNoise(s, rng);
  return s;
}

bool Contains(const std::string& text, const std::string& word) { return text.find(word) != std::string::npos; }

TEST(LocateMisfit, FindsAStiffnessChangeOnAcc2GrowingWithLevelAsStiffnessLike) {
  std::mt19937 rng(5);
  const Synthetic s = WithAcc2Truth({.stiffness_change_at_top = 2e-3}, rng);
  const MisfitLocation location = LocateMisfit(s.data, s.model, kFitted, kUnusedBeam, kNoLoops);
  ASSERT_TRUE(location.significant);
  EXPECT_GT(location.in_phase_fraction, 0.8);
  EXPECT_GT(location.fundamental_fraction, 0.9);
  EXPECT_GT(location.channel_excess_chi2[1], 0.9 * (location.channel_excess_chi2[0] + location.channel_excess_chi2[1] +
                                                    location.channel_excess_chi2[2]));
  EXPECT_GT(location.level_growth_exponent, 1.5);
  ASSERT_GE(location.findings.size(), 2u);
  const std::string& top = location.findings[1];
  std::printf("%s\n", top.c_str());
  EXPECT_TRUE(Contains(top, "acc2")) << top;
  EXPECT_TRUE(Contains(top, "fundamental")) << top;
  EXPECT_TRUE(Contains(top, "stiffness-like")) << top;
  EXPECT_TRUE(Contains(top, "grows with level faster")) << top;
}

TEST(LocateMisfit, FindsADampingChangeOnAcc2AsDissipationLike) {
  std::mt19937 rng(6);
  const Synthetic s = WithAcc2Truth({.damping_change_at_top = 0.2}, rng);
  const MisfitLocation location = LocateMisfit(s.data, s.model, kFitted, kUnusedBeam, kNoLoops);
  ASSERT_TRUE(location.significant);
  EXPECT_LT(location.in_phase_fraction, 0.2);
  ASSERT_GE(location.findings.size(), 2u);
  std::printf("%s\n", location.findings[1].c_str());
  EXPECT_TRUE(Contains(location.findings[1], "acc2")) << location.findings[1];
  EXPECT_TRUE(Contains(location.findings[1], "dissipation-like")) << location.findings[1];
}

TEST(LocateMisfit, ReportsContentInHarmonicsFourAndFiveAsBeyondTheFittedOnes) {
  std::mt19937 rng(8);
  Synthetic s = MakeSynthetic(rng);
  AddNoise(s, rng);
  for (std::size_t i = 0; i < s.model.size(); ++i) {
    // Measured harmonics 4 and 5 the model (fitting 1..3) has none of.
    const double a = 1e-2 * std::abs(s.model[i](0, 0));
    s.data.steps[i].measured(0, 3) += std::polar(2.0 * a, 0.3);
    s.data.steps[i].measured(2, 4) += std::polar(a, -1.0);
  }
  const MisfitLocation location = LocateMisfit(s.data, s.model, kFitted, kUnusedBeam, kNoLoops);
  ASSERT_TRUE(location.significant);
  EXPECT_GT(location.beyond_fitted_fraction, 0.9);
  bool said = false;
  for (const auto& f : location.findings) said = said || Contains(f, "harmonic truncation");
  EXPECT_TRUE(said);
  for (const auto& g : location.groups) {
    if (g.part == ResidualPart::kBoth && g.level.empty() && g.band == FrequencyBand::kAll) {
      const bool injected = (g.channel == "acc1" && g.harmonic == 4) || (g.channel == "acc3" && g.harmonic == 5);
      EXPECT_EQ(g.significant, injected) << g.channel << " harmonic " << g.harmonic << " p " << g.p_value;
    }
  }
}

// An even-harmonic misfit names an asymmetric support only when the
// recordings carry the even harmonics; when the model makes them and the
// recordings do not, the sentence blames the model's even-order term.
std::string EvenHarmonicFinding(const MisfitLocation& location) {
  for (const auto& f : location.findings)
    if (Contains(f, "even harmonics")) return f;
  return "";
}

TEST(LocateMisfit, AnEvenHarmonicMisfitIsTheSupportsAsymmetryOnlyWhenTheRecordingsCarryIt) {
  std::mt19937 rng(9);
  Synthetic in_recordings = MakeSynthetic(rng);
  AddNoise(in_recordings, rng);
  Synthetic in_model = in_recordings;
  for (std::size_t i = 0; i < in_recordings.model.size(); ++i) {
    const Complex second = std::polar(2e-2 * std::abs(in_recordings.model[i](1, 0)), 0.7);
    in_recordings.data.steps[i].measured(1, 1) += second;  // the support's even harmonic, unmodelled
    in_model.model[i](1, 1) += second;                     // a model's spurious k2, absent from the data
  }
  const MisfitLocation asymmetric = LocateMisfit(in_recordings.data, in_recordings.model, kFitted, kUnusedBeam, kNoLoops);
  ASSERT_TRUE(asymmetric.significant);
  EXPECT_TRUE(asymmetric.measured_even_harmonics);
  EXPECT_LT(asymmetric.measured_even_harmonics_p_value, 1e-6);
  const std::string said_asymmetric = EvenHarmonicFinding(asymmetric);
  EXPECT_TRUE(Contains(said_asymmetric, "the support is not symmetric")) << said_asymmetric;

  const MisfitLocation spurious = LocateMisfit(in_model.data, in_model.model, kFitted, kUnusedBeam, kNoLoops);
  ASSERT_TRUE(spurious.significant);
  EXPECT_GT(spurious.even_harmonic_fraction, 0.9);  // the same misfit share as above ...
  EXPECT_FALSE(spurious.measured_even_harmonics);   // ... but not in the recordings
  EXPECT_GT(spurious.measured_even_harmonics_p_value, 1e-3);
  const std::string said_spurious = EvenHarmonicFinding(spurious);
  EXPECT_TRUE(Contains(said_spurious, "recordings do not carry")) << said_spurious;
  EXPECT_FALSE(Contains(said_spurious, "not symmetric")) << said_spurious;
}

TEST(LocateMisfit, RejectsAModelOfTheWrongSize) {
  std::mt19937 rng(1);
  Synthetic s = MakeSynthetic(rng);
  s.model.pop_back();
  EXPECT_THROW(LocateMisfit(s.data, s.model, kFitted, kUnusedBeam, kNoLoops), std::invalid_argument);
  s = MakeSynthetic(rng);
  s.model[0] = Eigen::MatrixXcd::Zero(2, 3);
  EXPECT_THROW(LocateMisfit(s.data, s.model, kFitted, kUnusedBeam, kNoLoops), std::invalid_argument);
}

// Options out of range are refused by name, on data that would otherwise be
// located without complaint.
TEST(LocateMisfit, RefusesAnOptionOutOfRangeNamingIt) {
  std::mt19937 rng(1);
  const Synthetic s = MakeSynthetic(rng);
  ASSERT_NO_THROW(LocateMisfit(s.data, s.model, kFitted, kUnusedBeam, kNoLoops));
  const auto refused = [&](MisfitLocationOptions options, const std::string& expected) {
    try {
      LocateMisfit(s.data, s.model, kFitted, kUnusedBeam, options);
      ADD_FAILURE() << expected << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  MisfitLocationOptions o = kNoLoops;
  o.family_significance = 1.5;
  refused(o, "MisfitLocationOptions.family_significance = 1.5: must be in (0, 1)");
  o = kNoLoops;
  o.num_fitted_parameters = -2;
  refused(o, "MisfitLocationOptions.num_fitted_parameters = -2: must be at least 0");
  o = kNoLoops;
  o.model_relative_error = -1e-3;
  refused(o, "MisfitLocationOptions.model_relative_error = -0.001");
  o = kNoLoops;
  o.finding_min_share = 2.0;
  refused(o, "MisfitLocationOptions.finding_min_share = 2");
}

// The location goes to diagnosis.json (solver/diagnosis/diagnosis_io.h) and
// comes back whole.
TEST(LocateMisfit, DiagnosisFileHoldsTheFindingsFeaturesAndGroups) {
  std::mt19937 rng(5);
  const Synthetic s = WithAcc2Truth({.stiffness_change_at_top = 2e-3}, rng);
  DiagnosisFile file;
  file.diagnosis.location = LocateMisfit(s.data, s.model, kFitted, kUnusedBeam, kNoLoops);
  const MisfitLocation& location = *file.diagnosis.location;
  ASSERT_TRUE(location.significant);
  const DiagnosisFile read = DiagnosisFileFromJson(DiagnosisFileToJson(file), "diagnosis.json");
  ASSERT_TRUE(read.diagnosis.location.has_value());
  const MisfitLocation& back = *read.diagnosis.location;
  EXPECT_EQ(back.findings, location.findings);
  ASSERT_EQ(back.groups.size(), location.groups.size());
  for (std::size_t i = 0; i < back.groups.size(); ++i) {
    EXPECT_EQ(back.groups[i].channel, location.groups[i].channel);
    EXPECT_EQ(back.groups[i].harmonic, location.groups[i].harmonic);
    EXPECT_EQ(back.groups[i].part, location.groups[i].part);
    EXPECT_EQ(back.groups[i].chi2, location.groups[i].chi2);
    EXPECT_EQ(back.groups[i].significant, location.groups[i].significant);
  }
  EXPECT_EQ(back.in_phase_fraction, location.in_phase_fraction);
  EXPECT_EQ(back.channel_excess_chi2, location.channel_excess_chi2);
  EXPECT_TRUE(back.significant);
}

}  // namespace
}  // namespace beamid::solver
