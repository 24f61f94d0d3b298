#include "solver/diagnosis/misfit_location.h"

#include "hb/option_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <Eigen/Dense>
#include <fmt/core.h>

#include "hb/errors.h"
#include "solver/estimation/chi_square.h"
#include "solver/diagnosis/internal/weighted_slope.h"

namespace beamid::solver {

namespace {

using Complex = std::complex<double>;

// A model phasor must stand this many σ above the noise for its direction
// (and so the in-phase / quadrature split) to be defined.
constexpr double kDirectionMinSigma = 3.0;

double Excess(double chi2, int dof) { return std::max(chi2 - dof, 0.0); }

Eigen::Vector2d ReIm(Complex z) { return {z.real(), z.imag()}; }

// One standardised residual pair and where it sits.
struct Pair {
  int channel = 0, harmonic = 0, level = 0;
  bool near_resonance = false;
  bool has_parts = false;
  double chi2 = 0.0, in_phase = 0.0, quadrature = 0.0;
  double measured_chi2 = 0.0;  // the measured phasor against none, |L⁻¹Y_measured|² (noise only)
  // Unstandardised, on the channel's level-independent scale σ_c:
  double scaled_error2 = 0.0, scaled_noise2 = 0.0;
};

struct Accumulator {
  double chi2 = 0.0;
  int dof = 0;
};

std::string HarmonicName(int k) {
  return k == 1 ? "the fundamental" : "harmonic " + std::to_string(k);
}

std::string Percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f %%", 100.0 * fraction);
  return text;
}

std::string Number(double value, const char* format = "%.3g") {
  char text[48];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string PValue(double p) { return p < 1e-12 ? "p < 1e-12" : "p = " + Number(p, "%.2g"); }

// Holm's step-down adjustment: adjusted p_(i) = max_{j≤i} min(1, (m−j+1)·p_(j)).
std::vector<double> HolmAdjusted(const std::vector<double>& p) {
  std::vector<std::size_t> order(p.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p[a] < p[b]; });
  std::vector<double> adjusted(p.size());
  double running = 0.0;
  const double m = static_cast<double>(p.size());
  for (std::size_t j = 0; j < order.size(); ++j) {
    running = std::max(running, std::min(1.0, (m - static_cast<double>(j)) * p[order[j]]));
    adjusted[order[j]] = running;
  }
  return adjusted;
}

// Slope of log A_l vs log R_l (MisfitLocation::level_growth_exponent) over the
// pairs `selected` accepts; levels whose misfit is not beyond noise are left out.
double GrowthExponent(const std::vector<Pair>& pairs, const std::vector<double>& response2,
                      const std::vector<int>& response_count, int num_levels,
                      const std::function<bool(const Pair&)>& selected) {
  std::vector<double> excess(num_levels, 0.0), chi2(num_levels, 0.0);
  std::vector<int> count(num_levels, 0);
  for (const Pair& p : pairs) {
    if (!selected(p)) continue;
    excess[p.level] += p.scaled_error2 - p.scaled_noise2;
    chi2[p.level] += p.chi2;
    ++count[p.level];
  }
  std::vector<double> x, y, sigma;
  for (int l = 0; l < num_levels; ++l) {
    // Only levels whose misfit is beyond noise at 5 %: noise has no trend.
    if (count[l] == 0 || excess[l] <= 0.0 || ChiSquareUpperTail(chi2[l], 2 * count[l]) > 0.05) continue;
    x.push_back(0.5 * std::log(response2[l] / response_count[l]));
    y.push_back(0.5 * std::log(excess[l] / count[l]));
    sigma.push_back(1.0);
  }
  return internal::WeightedSlope(x, y, sigma).first;
}


double Share(double part, double whole) { return whole > 0.0 ? part / whole : 0.0; }

// ---- Per-residual statistics ----

// Throws std::invalid_argument unless model matches data in size (header).
void CheckSizes(const FitData& data, const std::vector<Eigen::MatrixXcd>& model) {
  const int num_channels = static_cast<int>(data.channels.size());
  const int k_max = data.num_fit_harmonics;
  if (k_max < 1) throw std::invalid_argument("LocateMisfit: the data hold no harmonics (num_fit_harmonics < 1)");
  if (model.size() != data.steps.size()) {
    throw std::invalid_argument("LocateMisfit: the model has " + std::to_string(model.size()) + " steps, the data " +
                                std::to_string(data.steps.size()));
  }
  for (std::size_t i = 0; i < model.size(); ++i) {
    if (model[i].rows() != num_channels || model[i].cols() > k_max) {
      throw std::invalid_argument("LocateMisfit: the model's phasors of step " + std::to_string(i) + " are " +
                                  std::to_string(model[i].rows()) + " × " + std::to_string(model[i].cols()) +
                                  ", the data have " + std::to_string(num_channels) + " channels × up to " +
                                  std::to_string(k_max) + " harmonics");
    }
  }
}

int LevelIndex(const FitData& data, const std::string& label) {
  const auto it = std::find(data.levels.begin(), data.levels.end(), label);
  if (it == data.levels.end()) throw std::invalid_argument("LocateMisfit: step level '" + label + "' is not a level");
  return static_cast<int>(it - data.levels.begin());
}

// What the measurements show per level, on level-independent scales.
struct MeasuredLevels {
  std::vector<double> channel_sigma;  // [c]: its median σ of the fundamental
  Eigen::MatrixXd peak;               // (level, channel): largest measured |Y₁|
  std::vector<double> response2;      // [l]: Σ |Y_c1|²/σ_c²
  std::vector<int> response_count;    // [l]: its terms
};

MeasuredLevels MeasureLevels(const FitData& data) {
  const int num_channels = static_cast<int>(data.channels.size());
  const int num_levels = static_cast<int>(data.levels.size());
  MeasuredLevels m{.channel_sigma = std::vector<double>(num_channels, 1.0),
                   .peak = Eigen::MatrixXd::Zero(num_levels, num_channels),
                   .response2 = std::vector<double>(num_levels, 0.0),
                   .response_count = std::vector<int>(num_levels, 0)};
  for (int c = 0; c < num_channels; ++c) {
    std::vector<double> sigmas;
    for (const FitStep& s : data.steps) sigmas.push_back(s.std_amplitude(c, 0));
    if (sigmas.empty()) continue;
    std::nth_element(sigmas.begin(), sigmas.begin() + sigmas.size() / 2, sigmas.end());
    m.channel_sigma[c] = std::max(sigmas[sigmas.size() / 2], 1e-300);
  }
  for (const FitStep& s : data.steps) {
    const int l = LevelIndex(data, s.level);
    for (int c = 0; c < num_channels; ++c) {
      m.peak(l, c) = std::max(m.peak(l, c), std::abs(s.measured(c, 0)));
      m.response2[l] += std::norm(s.measured(c, 0)) / std::pow(m.channel_sigma[c], 2);
      ++m.response_count[l];
    }
  }
  return m;
}

// The standardised residual of channel c, harmonic k at step i (header).
Pair StandardisedPair(const FitStep& s, const Eigen::MatrixXcd& model, int l, int c, int k,
                      const MeasuredLevels& measured, double model_relative_error) {
  const Complex force = s.force_N.size() > 1 ? s.force_N[1] : Complex(0.0);
  const Complex y_model = k <= model.cols() ? model(c, k - 1) : Complex(0.0);
  const Complex error = y_model - s.measured(c, k - 1);
  Eigen::Matrix2d whitening = s.whitening[c][k - 1];
  const double model_error = model_relative_error * std::abs(model.cols() > 0 ? model(c, 0) : Complex(0.0));
  if (model_error > 0.0) {
    const Eigen::Matrix2d root = whitening.inverse();
    const Eigen::Matrix2d covariance =
        root * root.transpose() + model_error * model_error * Eigen::Matrix2d::Identity();
    whitening = covariance.llt().matrixL().solve(Eigen::Matrix2d::Identity());
  }
  const Eigen::Vector2d r = whitening * ReIm(error);
  Pair p{.channel = c, .harmonic = k, .level = l};
  p.measured_chi2 = (s.whitening[c][k - 1] * ReIm(s.measured(c, k - 1))).squaredNorm();
  p.near_resonance = std::abs(s.measured(c, 0)) >= measured.peak(l, c) / std::numbers::sqrt2;
  p.chi2 = r.squaredNorm();
  // The direction a change of stiffness moves the response (header).
  const Complex direction = (k == 1 && std::abs(force) > 0.0) ? y_model * y_model / force : y_model;
  const Eigen::Vector2d u = whitening * ReIm(direction);
  if ((whitening * ReIm(y_model)).norm() >= kDirectionMinSigma && u.norm() > 0.0) {
    p.has_parts = true;
    p.in_phase = std::pow(u.normalized().dot(r), 2);
    p.quadrature = std::max(p.chi2 - p.in_phase, 0.0);
  }
  const double sigma_c2 = std::pow(measured.channel_sigma[c], 2);
  p.scaled_error2 = std::norm(error) / sigma_c2;
  p.scaled_noise2 = (2.0 * std::pow(s.std_amplitude(c, k - 1), 2) + 2.0 * model_error * model_error) / sigma_c2;
  return p;
}

std::vector<Pair> StandardisedPairs(const FitData& data, const std::vector<Eigen::MatrixXcd>& model,
                                    const MeasuredLevels& measured, double model_relative_error) {
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < data.steps.size(); ++i) {
    const int l = LevelIndex(data, data.steps[i].level);
    for (int c = 0; c < static_cast<int>(data.channels.size()); ++c)
      for (int k = 1; k <= data.num_fit_harmonics; ++k)
        pairs.push_back(StandardisedPair(data.steps[i], model[i], l, c, k, measured, model_relative_error));
  }
  return pairs;
}

// ---- Groupings ----

// Sums `value` over the pairs `selected` accepts into `group` and tests it;
// a group without pairs is not tested.
void AddGroup(const std::vector<Pair>& pairs, MisfitGroupTest group, const std::function<bool(const Pair&)>& selected,
              const std::function<double(const Pair&)>& value, int dof_per_pair, std::vector<MisfitGroupTest>* groups) {
  for (const Pair& p : pairs) {
    if (!selected(p)) continue;
    group.chi2 += value(p);
    group.dof += dof_per_pair;
  }
  if (group.dof == 0) return;
  group.p_value = ChiSquareUpperTail(group.chi2, group.dof);
  group.excess_chi2 = Excess(group.chi2, group.dof);
  groups->push_back(std::move(group));
}

double BothParts(const Pair& p) { return p.chi2; }

// The groups of channel c, harmonic k, in a fixed order: all levels and
// parts (with its growth over the levels); in_phase, quadrature; per level;
// per frequency band.
void AddChannelHarmonicGroups(const FitData& data, const std::vector<Pair>& pairs, const MeasuredLevels& measured,
                              int c, int k, std::vector<MisfitGroupTest>* groups) {
  const int num_levels = static_cast<int>(data.levels.size());
  const std::string& name = data.channels[c].channel;
  const auto in_group = [c, k](const Pair& p) { return p.channel == c && p.harmonic == k; };
  MisfitGroupTest group{.channel = name, .harmonic = k};
  if (num_levels >= 2)
    group.growth_exponent =
        GrowthExponent(pairs, measured.response2, measured.response_count, num_levels, in_group);
  AddGroup(pairs, group, in_group, BothParts, 2, groups);
  const auto with_parts = [&](const Pair& p) { return in_group(p) && p.has_parts; };
  AddGroup(pairs, {.channel = name, .harmonic = k, .part = ResidualPart::kInPhase}, with_parts,
           [](const Pair& p) { return p.in_phase; }, 1, groups);
  AddGroup(pairs, {.channel = name, .harmonic = k, .part = ResidualPart::kQuadrature}, with_parts,
           [](const Pair& p) { return p.quadrature; }, 1, groups);
  for (int l = 0; l < num_levels; ++l)
    AddGroup(pairs, {.channel = name, .harmonic = k, .level = data.levels[l]},
             [&](const Pair& p) { return in_group(p) && p.level == l; }, BothParts, 2, groups);
  for (bool near : {true, false})
    AddGroup(pairs, {.channel = name, .harmonic = k, .band = near ? FrequencyBand::kNearResonance : FrequencyBand::kAway},
             [&](const Pair& p) { return in_group(p) && p.near_resonance == near; }, BothParts, 2, groups);
}

std::vector<MisfitGroupTest> GroupTests(const FitData& data, const std::vector<Pair>& pairs,
                                        const MeasuredLevels& measured) {
  std::vector<MisfitGroupTest> groups;
  for (int c = 0; c < static_cast<int>(data.channels.size()); ++c)
    for (int k = 1; k <= data.num_fit_harmonics; ++k) AddChannelHarmonicGroups(data, pairs, measured, c, k, &groups);
  return groups;
}

// The overall test joins the groups' family: Holm over all, each group's
// adjusted p and the location's significance.
void TestFamily(const std::vector<Pair>& pairs, const MisfitLocationOptions& options, MisfitLocation* out) {
  for (const Pair& p : pairs) out->chi2 += p.chi2;
  out->dof = std::max(2 * static_cast<int>(pairs.size()) - options.num_fitted_parameters, 1);
  out->p_value = ChiSquareUpperTail(out->chi2, out->dof);
  std::vector<double> p_values{out->p_value};
  for (const auto& g : out->groups) p_values.push_back(g.p_value);
  const std::vector<double> adjusted = HolmAdjusted(p_values);
  out->num_groups_tested = static_cast<int>(p_values.size());
  out->significant = adjusted[0] < options.family_significance;
  for (std::size_t g = 0; g < out->groups.size(); ++g) {
    out->groups[g].adjusted_p_value = adjusted[g + 1];
    out->groups[g].significant = adjusted[g + 1] < options.family_significance;
    out->significant = out->significant || out->groups[g].significant;
  }
}

int ChannelIndex(const FitData& data, const std::string& channel) {
  return static_cast<int>(std::find_if(data.channels.begin(), data.channels.end(),
                                       [&](const FitChannel& f) { return f.channel == channel; }) -
                          data.channels.begin());
}

// Per-harmonic and per-channel excess, and the signature's shares (header).
void SignatureFeatures(const FitData& data, int fitted_harmonics, MisfitLocation* out) {
  const int k_max = data.num_fit_harmonics;
  out->harmonic_excess_chi2.assign(k_max, 0.0);
  out->channel_excess_chi2.assign(data.channels.size(), 0.0);
  double in_phase = 0.0, quadrature = 0.0, near = 0.0, away = 0.0;
  for (const auto& g : out->groups) {
    const bool by_harmonic = g.level.empty() && g.band == FrequencyBand::kAll;
    if (by_harmonic && g.part == ResidualPart::kBoth) {
      out->harmonic_excess_chi2[g.harmonic - 1] += g.excess_chi2;
      out->channel_excess_chi2[ChannelIndex(data, g.channel)] += g.excess_chi2;
    }
    if (by_harmonic && g.part == ResidualPart::kInPhase) in_phase += g.excess_chi2;
    if (by_harmonic && g.part == ResidualPart::kQuadrature) quadrature += g.excess_chi2;
    if (g.band == FrequencyBand::kNearResonance) near += g.excess_chi2;
    if (g.band == FrequencyBand::kAway) away += g.excess_chi2;
  }
  double total = 0.0, even = 0.0, beyond = 0.0;
  for (int k = 1; k <= k_max; ++k) {
    total += out->harmonic_excess_chi2[k - 1];
    if (k % 2 == 0) even += out->harmonic_excess_chi2[k - 1];
    if (k > fitted_harmonics) beyond += out->harmonic_excess_chi2[k - 1];
  }
  out->in_phase_fraction = Share(in_phase, in_phase + quadrature);
  out->near_resonance_fraction = Share(near, near + away);
  out->fundamental_fraction = Share(out->harmonic_excess_chi2[0], total);
  out->even_harmonic_fraction = Share(even, total);
  out->beyond_fitted_fraction = Share(beyond, total);
}

// Whether the recordings themselves carry even harmonics: their phasors of
// harmonics 2, 4, … against none, χ²(2 per pair). A misfit in the even
// harmonics says the support is asymmetric only if they do; otherwise it is
// the model's own even-order terms that the recordings lack.
void MeasuredEvenHarmonics(const std::vector<Pair>& pairs, double family_significance, MisfitLocation* out) {
  double chi2 = 0.0;
  int dof = 0;
  for (const Pair& p : pairs)
    if (p.harmonic % 2 == 0) chi2 += p.measured_chi2, dof += 2;
  if (dof == 0) return;
  out->measured_even_harmonics_p_value = ChiSquareUpperTail(chi2, dof);
  out->measured_even_harmonics = out->measured_even_harmonics_p_value < family_significance;
}

// The misfit's excess χ² summed over the harmonics (the findings' whole).
double TotalExcess(const MisfitLocation& location) {
  double total = 0.0;
  for (double e : location.harmonic_excess_chi2) total += e;
  return total;
}

// ---- Levels ----

// A_l and R_l of every level (MisfitLocation::level_growth_exponent).
void LevelAmplitudes(const std::vector<Pair>& pairs, const MeasuredLevels& measured, int num_levels,
                     MisfitLocation* out) {
  out->level_misfit_amplitude.assign(num_levels, 0.0);
  out->level_response_amplitude.assign(num_levels, 0.0);
  std::vector<double> excess(num_levels, 0.0);
  std::vector<int> count(num_levels, 0);
  for (const Pair& p : pairs) excess[p.level] += p.scaled_error2 - p.scaled_noise2, ++count[p.level];
  for (int l = 0; l < num_levels; ++l) {
    out->level_misfit_amplitude[l] = count[l] ? std::sqrt(std::max(excess[l], 0.0) / count[l]) : 0.0;
    out->level_response_amplitude[l] =
        measured.response_count[l] ? std::sqrt(measured.response2[l] / measured.response_count[l]) : 0.0;
  }
}

// Over the channel×harmonic groups that carry the misfit (all when none
// does): elsewhere noise would dilute the levels' misfit.
double LevelGrowthExponent(const FitData& data, const std::vector<Pair>& pairs, const MeasuredLevels& measured,
                           const std::vector<MisfitGroupTest>& groups) {
  const int num_levels = static_cast<int>(data.levels.size());
  std::vector<std::vector<bool>> carries(data.channels.size(), std::vector<bool>(data.num_fit_harmonics + 1, false));
  bool any = false;
  for (const auto& g : groups) {
    if (!g.significant || g.part != ResidualPart::kBoth || !g.level.empty() || g.band != FrequencyBand::kAll) continue;
    carries[ChannelIndex(data, g.channel)][g.harmonic] = any = true;
  }
  return GrowthExponent(pairs, measured.response2, measured.response_count, num_levels,
                        [&](const Pair& p) { return !any || carries[p.channel][p.harmonic]; });
}

// ---- Findings ----

// What the in-phase / quadrature split of g says, "" when it has none.
std::string PartPhrase(const MisfitGroupTest& g, const MisfitGroupTest* in, const MisfitGroupTest* quad) {
  if (!in || !quad || !(in->excess_chi2 + quad->excess_chi2 > 0.0)) return "";
  const double f = in->excess_chi2 / (in->excess_chi2 + quad->excess_chi2);
  if (g.harmonic == 1) {
    return f >= 0.7   ? "; stiffness-like (" + Percent(f) + " in phase with a stiffness change)"
           : f <= 0.3 ? "; dissipation-like (" + Percent(1.0 - f) + " in quadrature, as a damping change)"
                      : "; both stiffness- and dissipation-like (" + Percent(f) + " in phase)";
  }
  return f >= 0.7   ? "; its size is off (" + Percent(f) + " in phase with the model's harmonic)"
         : f <= 0.3 ? "; its phase is off (" + Percent(1.0 - f) + " in quadrature to the model's harmonic)"
                    : "; both its size and its phase are off";
}

std::string BandPhrase(const MisfitGroupTest* near, const MisfitGroupTest* away) {
  if (!near || !away || !(near->excess_chi2 + away->excess_chi2 > 0.0)) return "";
  const double f = near->excess_chi2 / (near->excess_chi2 + away->excess_chi2);
  return f >= 0.7   ? "; near resonance (" + Percent(f) + " within the half-power band)"
         : f <= 0.3 ? "; away from resonance (" + Percent(1.0 - f) + " outside the half-power band)"
                    : "; both near and away from resonance";
}

// How g's misfit changes with level: its growth exponent, else the one level flagged.
std::string LevelPhrase(const MisfitGroupTest& g, const std::vector<MisfitGroupTest>& groups, int num_levels) {
  std::vector<std::string> flagged;
  for (const auto& h : groups)
    if (h.channel == g.channel && h.harmonic == g.harmonic && !h.level.empty() && h.significant)
      flagged.push_back(h.level);
  if (!std::isnan(g.growth_exponent)) {
    const std::string exponent = Number(g.growth_exponent, "%.2f");
    return g.growth_exponent > 1.3
               ? "; grows with level faster than the response (exponent " + exponent +
                     ": a nonlinearity the model lacks)"
           : g.growth_exponent > 0.7 ? "; grows with level like the response (exponent " + exponent + ": a linear error)"
                                     : "; does not grow with level (exponent " + exponent + ")";
  }
  if (flagged.size() == 1 && num_levels >= 2) return "; only at level " + flagged[0];
  return "";
}

// One sentence on a significant channel×harmonic group g.
std::string GroupFinding(const MisfitGroupTest& g, const std::vector<MisfitGroupTest>& groups, double total,
                         int fitted_harmonics, int num_levels) {
  const auto find = [&](const std::function<bool(const MisfitGroupTest&)>& match) -> const MisfitGroupTest* {
    for (const auto& h : groups)
      if (h.channel == g.channel && h.harmonic == g.harmonic && match(h)) return &h;
    return nullptr;
  };
  std::string text = "Sensor " + g.channel + ", " + HarmonicName(g.harmonic) + ": " +
                     Percent(Share(g.excess_chi2, total)) + " of the misfit (chi-square " + Number(g.chi2, "%.1f") +
                     " for " + std::to_string(g.dof) + ", " + PValue(g.p_value) + ")";
  if (g.harmonic > fitted_harmonics)
    text += ", beyond the " + std::to_string(fitted_harmonics) + " harmonics the model fits";
  text += PartPhrase(g, find([](const auto& h) { return h.part == ResidualPart::kInPhase; }),
                     find([](const auto& h) { return h.part == ResidualPart::kQuadrature; }));
  text += BandPhrase(find([](const auto& h) { return h.band == FrequencyBand::kNearResonance; }),
                     find([](const auto& h) { return h.band == FrequencyBand::kAway; }));
  return text + LevelPhrase(g, groups, num_levels) + ".";
}

// The findings of the residual tests: the overall verdict, then the
// channel×harmonic groups carrying at least finding_min_share of the misfit,
// largest first, then harmonic truncation and asymmetry.
std::vector<std::string> ResidualFindings(const MisfitLocation& out, const FitData& data, int fitted_harmonics,
                                          const MisfitLocationOptions& options) {
  // Not the fit's χ²: these are the located harmonics, and each residual's
  // variance adds the model's own error where one is allowed.
  const std::string allowance = options.model_relative_error > 0.0
                                    ? " with the model's own error of " +
                                          Number(100.0 * options.model_relative_error, "%.2g") +
                                          " % of the fundamental allowed"
                                    : " against the phasors' stated uncertainty alone";
  const std::string overall = "chi-square " + Number(out.chi2, "%.1f") + " for " + std::to_string(out.dof) +
                              " degrees of freedom" + allowance + " (" + PValue(out.p_value) + ")";
  if (!out.significant)
    return {"No significant discrepancy: " + overall +
            "; no channel, harmonic, level or band of the residuals exceeds the noise at the " +
            Percent(options.family_significance) + " family-wise level."};
  std::vector<std::string> findings{"The model misses the recordings beyond their noise: " + overall + "."};
  const double total = TotalExcess(out);
  std::vector<const MisfitGroupTest*> main_groups;
  for (const auto& g : out.groups)
    if (g.significant && g.part == ResidualPart::kBoth && g.level.empty() && g.band == FrequencyBand::kAll &&
        g.excess_chi2 >= options.finding_min_share * total)
      main_groups.push_back(&g);
  std::sort(main_groups.begin(), main_groups.end(), [](auto* a, auto* b) { return a->excess_chi2 > b->excess_chi2; });
  for (const MisfitGroupTest* g : main_groups)
    findings.push_back(GroupFinding(*g, out.groups, total, fitted_harmonics, static_cast<int>(data.levels.size())));
  if (out.beyond_fitted_fraction >= options.finding_min_share && fitted_harmonics < data.num_fit_harmonics)
    findings.push_back(Percent(out.beyond_fitted_fraction) + " of the misfit is in harmonics above " +
                       std::to_string(fitted_harmonics) + ", which the model does not fit (harmonic truncation).");
  if (out.even_harmonic_fraction >= options.finding_min_share) {
    const std::string share = Percent(out.even_harmonic_fraction) + " of the misfit is in even harmonics (2, 4)";
    const std::string evidence = " (" + PValue(out.measured_even_harmonics_p_value) + " against none)";
    findings.push_back(out.measured_even_harmonics
                           ? share + ", which the recordings carry" + evidence + ": the support is not symmetric."
                           : share + " that the model makes and the recordings do not carry" + evidence +
                                 ": the model's even-order stiffness (k2) is spurious, not a sign of an asymmetric "
                                 "support.");
  }
  return findings;
}

// What the support's loops show, when enough steps reconstruct them.
std::optional<std::string> LoopFinding(const LoopEvidence& loops) {
  if (loops.num_steps_used < 2) return std::nullopt;
  std::string text = "Support loops (" + std::to_string(loops.num_steps_used) + " steps): ";
  if (loops.dissipation_not_viscous) {
    text += "the energy dissipated per cycle does not follow a viscous damper (equivalent damping " +
            Number(loops.damping_ratio_high_to_low, "%.2f") + "× larger at the largest rotation than at the smallest";
    if (!std::isnan(loops.area_exponent))
      text += ", loop area ∝ amplitude^" + Number(loops.area_exponent, "%.2f") + " against 2 for viscous";
    text += ")";
  } else {
    text += "the energy dissipated per cycle is that of a viscous damper (c = " +
            Number(loops.mean_equivalent_damping_Nms_rad) + " N·m·s/rad)";
  }
  if (loops.hysteretic_shape) text += "; the loops are not ellipses, with hysteretic harmonics: evidence of friction";
  else if (loops.non_elliptic) text += "; the loops are bent (an elastic nonlinearity), without hysteretic harmonics";
  if (loops.asymmetric) text += "; the rotation has even harmonics: the support is not symmetric";
  return text + ".";
}

}  // namespace

void MisfitLocationOptions::Validate() const {
  using namespace option_checks;
  if (!(family_significance > 0.0 && family_significance < 1.0))
    Refuse("MisfitLocationOptions.family_significance", FormatValue(family_significance), "in (0, 1)");
  RequireAtLeast("MisfitLocationOptions.num_fitted_parameters", num_fitted_parameters, 0);
  RequireNonNegative("MisfitLocationOptions.model_relative_error", model_relative_error);
  RequireInRange("MisfitLocationOptions.finding_min_share", finding_min_share, 0.0, 1.0);
  RequireNonNegative("MisfitLocationOptions.loop_relative_model_error", loop_relative_model_error);
}

MisfitLocation LocateMisfit(const FitData& data, const std::vector<Eigen::MatrixXcd>& model, int fitted_harmonics,
                            const hb::LinearBeamModel& reference_beam, const MisfitLocationOptions& options) {
  options.Validate();
  CheckSizes(data, model);
  const int num_levels = static_cast<int>(data.levels.size());
  const MeasuredLevels measured = MeasureLevels(data);
  const std::vector<Pair> pairs = StandardisedPairs(data, model, measured, options.model_relative_error);
  MisfitLocation out;
  out.groups = GroupTests(data, pairs, measured);
  TestFamily(pairs, options, &out);
  SignatureFeatures(data, fitted_harmonics, &out);
  MeasuredEvenHarmonics(pairs, options.family_significance, &out);
  LevelAmplitudes(pairs, measured, num_levels, &out);
  if (num_levels >= 2) out.level_growth_exponent = LevelGrowthExponent(data, pairs, measured, out.groups);
  if (options.analyse_loops)
    out.loops = AnalyseSupportLoops(data, reference_beam, options.family_significance, options.loop_relative_model_error);
  out.findings = ResidualFindings(out, data, fitted_harmonics, options);
  if (const auto loops = LoopFinding(out.loops)) out.findings.push_back(*loops);
  return out;
}

}  // namespace beamid::solver
