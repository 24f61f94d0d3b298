#include "solver/backbone/measured_backbone_io.h"

#include <numbers>
#include <string_view>
#include <type_traits>

#include "hb/text_file.h"
#include "signal/free_decay_schema.h"

namespace beamid::solver {
namespace {

using schema::kOptional;
using schema::Presence;
using schema::TextRule;

constexpr schema::Format kMeasuredBackboneSchema{kMeasuredBackboneFormat, "measured backbone",
                                                 "give a .json written by 'beamid backbone --measured'"};

// Descriptions for a reader of the file; they are the same in every file, so
// the struct does not carry them (and an earlier file's wording reads).
constexpr const char* kAmplitudeDescription = "first-harmonic displacement amplitude at the sensor [m]";
constexpr const char* kModelDescription =
    "A(a)*F/X_d = wn^2(a) - w^2 + 2i*w*(zeta*wn)(a), s = a/a_ref; wn^2, zeta*wn: polynomials in s or power laws "
    "c0 + c1*s^exponent (Iwan-like); A = A0r + i*A0i (+ A2*s^2); chosen by AICc; X_d/F = A/D + R, a = |X_d - R*F|";
constexpr const char* kParameterOrder = "Re A0, Im A0, [A2], wn^2 terms, zeta*wn terms";

// Bounds on what a file can make the reader hold: a campaign's levels and
// steps, the fit's candidates and curve stay far below them.
constexpr std::size_t kMaxInputs = 1'000;
constexpr std::size_t kMaxLevels = 10'000;
constexpr std::size_t kMaxStepsPerLevel = 1'000'000;
constexpr std::size_t kMaxFlagsPerLevel = 1'000;
constexpr std::size_t kMaxParameters = 64;
constexpr std::size_t kMaxCandidates = 100'000;
constexpr std::size_t kMaxCurvePoints = 1'000'000;
constexpr std::size_t kMaxWarnings = 10'000;
constexpr int kMaxDegree = 100;

const schema::Name<LevelControl> kControls[] = {
    {LevelControl::kForce, LevelControlName(LevelControl::kForce)},
    {LevelControl::kResponse, LevelControlName(LevelControl::kResponse)},
    {LevelControl::kNeither, LevelControlName(LevelControl::kNeither)}};
const schema::Name<LevelFlagKind> kFlagKinds[] = {
    {LevelFlagKind::kDampingNotPositive, LevelFlagName(LevelFlagKind::kDampingNotPositive)},
    {LevelFlagKind::kPeakOutsideBand, LevelFlagName(LevelFlagKind::kPeakOutsideBand)},
    {LevelFlagKind::kRegenerationBeyondNoise, LevelFlagName(LevelFlagKind::kRegenerationBeyondNoise)},
    {LevelFlagKind::kJump, LevelFlagName(LevelFlagKind::kJump)},
    {LevelFlagKind::kPhaseConvention, LevelFlagName(LevelFlagKind::kPhaseConvention)},
    {LevelFlagKind::kCoarseSteps, LevelFlagName(LevelFlagKind::kCoarseSteps)},
    {LevelFlagKind::kOffBackbone, LevelFlagName(LevelFlagKind::kOffBackbone)},
    {LevelFlagKind::kNonlinearCurve, LevelFlagName(LevelFlagKind::kNonlinearCurve)}};
// SweepJump::up_sweep.
constexpr schema::Name<bool> kDirections[] = {{true, "up"}, {false, "down"}};
// What drives the levels (MeasuredBackbone::excitation_quantity).
const schema::Name<std::string> kExcitations[] = {
    {"force", "force"}, {"voltage", "voltage"}, {"base_acceleration", "base_acceleration"}};

// An estimate: {value, std}, or null when it could not be made.
auto EstimateOf(std::string_view unit, schema::Limits value) {
  return [unit, value](auto& io, auto& e) {
    io.Number("value", e.value, unit, value.OrNull());
    io.Number("std", e.std, unit, schema::NonNegative().OrNull());
  };
}
void EstimateField(auto& io, std::string_view key, auto& e, std::string_view unit, schema::Limits value,
                   Presence presence = Presence::kRequired) {
  io.ObjectOrNull(key, e, &Estimate::valid, presence, EstimateOf(unit, value));
}

// The labels of a known excitation; none while the declaration only lists
// its fields (an empty name).
ExcitationLabels LabelsOrNone(const std::string& quantity) {
  return quantity.empty() ? ExcitationLabels{} : LabelsOf(quantity);
}

}  // namespace

// The declaration of the file (hb/json_schema.h): its writer, reader and
// documentation. Fields that earlier files lack are optional (the struct's
// defaults: no jumps, no flags, in the fit, 0, a force).

void Describe(auto& io, schema::Like<SweepJump> auto& j) {
  io.Integer("from_step", j.from_step, 0, kMaxStepsPerLevel);
  io.Integer("to_step", j.to_step, 0, kMaxStepsPerLevel);
  io.Number("from_frequency_Hz", j.from_frequency_hz, "Hz", schema::Positive());
  io.Number("to_frequency_Hz", j.to_frequency_hz, "Hz", schema::Positive());
  io.Choice("direction", j.up_sweep, kDirections);
  io.Number("receptance_ratio", j.receptance_ratio, "1", schema::NonNegative().OrNull());
  io.Number("phase_change_rad", j.phase_change_rad, "rad",
            schema::Between(-std::numbers::pi, std::numbers::pi).OrNull());
  io.Number("miss_over_predicted", j.miss_over_predicted, "1", schema::Any().OrNull());
}

void Describe(auto& io, schema::Like<LevelFrfPoint> auto& p) {
  io.Number("frequency_Hz", p.frequency_hz, "Hz", schema::Positive());
  io.Number("receptance_m_N", p.receptance_m_N, "m/N", schema::NonNegative().OrNull());
  io.Number("phase_rad", p.phase_rad, "rad", schema::Between(-std::numbers::pi, std::numbers::pi).OrNull());
}

void Describe(auto& io, schema::Like<LevelFlag> auto& flag) {
  io.Choice("kind", flag.kind, kFlagKinds);
  io.Text("quantity", flag.quantity, TextRule::kNotEmpty);
  io.Text("message", flag.message);
}

void Describe(auto& io, schema::Like<LevelResonance> auto& l) {
  io.Text("label", l.label);
  io.Choice("control", l.control, kControls);
  io.Integer("num_points", l.num_points, 0, kMaxStepsPerLevel);
  io.Integer("num_fit_points", l.num_fit_points, 0, kMaxStepsPerLevel);
  // Response amplitudes and forces are in the level's response quantity and
  // excitation (SI), receptances per the excitation's unit.
  io.Object("phase_resonance", l, Presence::kRequired, [](auto& p_io, auto& r) {
    EstimateField(p_io, "frequency_Hz", r.quadrature_frequency_hz, "Hz", schema::Positive());
    EstimateField(p_io, "displacement_amplitude_m", r.quadrature_amplitude_m, "m", schema::NonNegative());
    EstimateField(p_io, "response_amplitude", r.quadrature_response_amplitude, "SI", schema::NonNegative());
    EstimateField(p_io, "force_N", r.quadrature_force_N, "N", schema::NonNegative());
    EstimateField(p_io, "damping_ratio", r.quadrature_damping_ratio, "1", schema::Any());
    p_io.Boolean("after_jump", r.quadrature_after_jump);
    p_io.Text("note", r.quadrature_note);
  });
  io.Object("peak", l, Presence::kRequired, [](auto& p_io, auto& r) {
    EstimateField(p_io, "frequency_Hz", r.peak_frequency_hz, "Hz", schema::Positive());
    EstimateField(p_io, "receptance_m_N", r.peak_receptance_m_N, "m/N", schema::NonNegative());
    EstimateField(p_io, "displacement_amplitude_m", r.peak_amplitude_m, "m", schema::NonNegative());
  });
  io.Object("half_power", l, Presence::kRequired, [](auto& h_io, auto& r) {
    EstimateField(h_io, "damping_ratio", r.half_power_damping_ratio, "1", schema::Any());
    EstimateField(h_io, "lower_frequency_Hz", r.half_power_lower_frequency_hz, "Hz", schema::Positive(), kOptional);
    EstimateField(h_io, "upper_frequency_Hz", r.half_power_upper_frequency_hz, "Hz", schema::Positive(), kOptional);
    EstimateField(h_io, "natural_frequency_Hz", r.half_power_natural_frequency_hz, "Hz", schema::Positive(),
                  kOptional);
    h_io.Text("note", r.half_power_note);
  });
  io.OptionalObject("free_decay", l.free_decay_damping_ratio.valid, l, [](auto& d_io, auto& r) {
    EstimateField(d_io, "damping_ratio", r.free_decay_damping_ratio, "1", schema::Any());
    d_io.Number("step_frequency_Hz", r.free_decay_step_frequency_hz, "Hz", schema::NonNegative());
    d_io.List("points", r.free_decay, signal::kMaxDecayPoints);
  });
  io.Number("noise_from_sweep_relative_rms", l.noise_from_sweep_relative_rms, "1", schema::NonNegative(), kOptional);
  EstimateField(io, "damping_ratio", l.damping_ratio, "1", schema::Any(), kOptional);
  io.Text("damping_ratio_note", l.damping_ratio_note, TextRule::kAny, kOptional);
  io.Object("local_fit", l, Presence::kRequired, [](auto& f_io, auto& r) {
    EstimateField(f_io, "natural_frequency_Hz", r.local_natural_frequency_hz, "Hz", schema::Positive());
    EstimateField(f_io, "damping_ratio", r.local_damping_ratio, "1", schema::Any());
    f_io.Number("reduced_chi_square", r.local_reduced_chi_square, "1", schema::NonNegative().OrNull());
  });
  io.Object("regeneration", l, Presence::kRequired, [](auto& g_io, auto& r) {
    g_io.Number("relative_rms", r.regeneration_relative_rms, "1", schema::NonNegative().OrNull());
    g_io.Number("max_relative", r.regeneration_max_relative, "1", schema::NonNegative().OrNull());
    g_io.Number("reduced_chi_square", r.regeneration_reduced_chi_square, "1", schema::NonNegative().OrNull());
    g_io.Number("noise_relative_rms", r.regeneration_noise_relative_rms, "1", schema::NonNegative().OrNull(),
                kOptional);
    g_io.Number("own_curve_relative_rms", r.own_curve_relative_rms, "1", schema::NonNegative().OrNull(), kOptional);
  });
  io.List("jumps", l.jumps, kMaxStepsPerLevel, kOptional);
  // What the page draws; files written before them have neither.
  io.List("measured_frf", l.measured_frf, kMaxStepsPerLevel, kOptional);
  io.List("fit_frf", l.fit_frf, kMaxCurvePoints, kOptional);
  io.List("flags", l.flags, kMaxFlagsPerLevel, kOptional);
  io.Boolean("in_global_fit", l.in_global_fit, kOptional);
}

void Describe(auto& io, schema::Like<BackboneModelCandidate> auto& c) {
  io.Text("form", c.form);
  io.Integer("frequency_degree", c.frequency_degree, 0, kMaxDegree);
  io.Integer("damping_degree", c.damping_degree, 0, kMaxDegree);
  io.Number("frequency_exponent", c.frequency_exponent, "1", schema::NonNegative());
  io.Number("damping_exponent", c.damping_exponent, "1", schema::NonNegative());
  io.Boolean("amplitude_dependent_modal_constant", c.amplitude_dependent_modal_constant);
  io.Number("aicc", c.aicc, "1", schema::Any().OrNull());
  io.Number("reduced_chi_square", c.reduced_chi_square, "1", schema::NonNegative().OrNull());
}

void Describe(auto& io, schema::Like<MeasuredBackboneCurvePoint> auto& p) {
  io.Number("amplitude_m", p.amplitude_m, "m", schema::NonNegative());
  io.Number("frequency_Hz", p.frequency_hz, "Hz", schema::Positive().OrNull());
  io.Number("frequency_std_Hz", p.frequency_std_hz, "Hz", schema::NonNegative().OrNull());
  io.Number("damping_ratio", p.damping_ratio, "1", schema::Any().OrNull());
  io.Number("damping_ratio_std", p.damping_ratio_std, "1", schema::NonNegative().OrNull());
}

void Describe(auto& io, schema::Like<MeasuredBackboneFit> auto& fit) {
  io.Derived("model", kModelDescription);
  io.Text("form", fit.form);
  io.Integer("frequency_degree", fit.frequency_degree, 0, kMaxDegree);
  io.Integer("damping_degree", fit.damping_degree, 0, kMaxDegree);
  io.Number("frequency_exponent", fit.frequency_exponent, "1", schema::NonNegative());
  io.Number("damping_exponent", fit.damping_exponent, "1", schema::NonNegative());
  io.Boolean("amplitude_dependent_modal_constant", fit.amplitude_dependent_modal_constant);
  io.Number("residual_receptance_m_N", fit.residual_receptance_m_N, "m/N");
  io.Derived("parameter_order", kParameterOrder);
  io.Number("reference_amplitude_m", fit.reference_amplitude_m, "m", schema::Positive());
  // In the units parameter_order implies (rad²/s², rad/s per the powers of s).
  io.Numbers("parameters", fit.parameters, "", schema::Any().OrNull(), kMaxParameters);
  io.Number("reduced_chi_square", fit.reduced_chi_square, "1", schema::NonNegative().OrNull());
  io.List("candidates", fit.candidates, kMaxCandidates);
  io.List("curve", fit.curve, kMaxCurvePoints);
}

// The damping-rate verdict's words, then (read only) those of files written
// before the damping rate, whose one verdict was on ζ (see the reader).
constexpr schema::Name<Trend> kVerdictNamesOfAnyVersion[] = {
    kDampingRateTrendNames[0],  kDampingRateTrendNames[1],  kDampingRateTrendNames[2],  kDampingRateTrendNames[3],
    kDampingRatioTrendNames[0], kDampingRatioTrendNames[1], kDampingRatioTrendNames[2]};

void Describe(auto& io, schema::Like<DampingTrend> auto& t) {
  io.Number("amplitude_m", t.amplitude_m, "m", schema::NonNegative());
  io.Number("slope_per_m", t.slope_per_m, "1/m", schema::Any().OrNull());
  io.Number("slope_std_per_m", t.slope_std_per_m, "1/m", schema::NonNegative().OrNull());
  io.Number("z", t.z, "1", schema::Any().OrNull());
  // Files written before the damping rate judged ζ alone (see the reader).
  io.Number("damping_rate_slope_per_s_m", t.damping_rate_slope_per_s_m, "1/(s m)", schema::Any().OrNull(), kOptional);
  io.Number("damping_rate_slope_std_per_s_m", t.damping_rate_slope_std_per_s_m, "1/(s m)",
            schema::NonNegative().OrNull(), kOptional);
  io.Number("damping_rate_z", t.damping_rate_z, "1", schema::Any().OrNull(), kOptional);
  io.Choice("verdict", t.verdict, kVerdictNamesOfAnyVersion);
  io.Choice("damping_ratio_verdict", t.damping_ratio_verdict, kDampingRatioTrendNames, kOptional);
  io.Text("note", t.note, TextRule::kAny, kOptional);
}

void Describe(auto& io, schema::Like<MeasuredBackboneModelPoint> auto& p) {
  io.Number("amplitude_m", p.amplitude_m, "m", schema::NonNegative());
  io.Number("frequency_Hz", p.frequency_hz, "Hz", schema::Positive().OrNull());
}

void Describe(auto& io, schema::Like<MeasuredBackboneFile> auto& f) {
  io.Constant("format", kMeasuredBackboneFormat);
  // A file older than the key reads with version "", not this program's.
  if constexpr (std::remove_reference_t<decltype(io)>::kReading) f.beamid_version.clear();
  io.Text("beamid_version", f.beamid_version, TextRule::kAny, kOptional);
  io.Texts("inputs", f.inputs, kMaxInputs, TextRule::kNotEmpty);
  io.Text("channel", f.channel, TextRule::kNotEmpty);
  io.Text("response_quantity", f.response_quantity, TextRule::kNotEmpty);
  io.Object("excitation", f.excitation_quantity, kOptional, [](auto& e_io, auto& quantity) {
    e_io.Choice("quantity", quantity, kExcitations);
    const ExcitationLabels labels = LabelsOrNone(quantity);
    e_io.Derived("unit", labels.unit);
    e_io.Derived("frf", labels.frf);
  });
  io.Derived("amplitude", kAmplitudeDescription);
  io.List("levels", f.levels, kMaxLevels);
  io.Object("single_mode_fit", f.single_mode_fit);
  io.Object("damping_trend", f.damping_trend);
  io.List("model_backbone", f.model_backbone, kMaxCurvePoints);
  io.Texts("warnings", f.warnings, kMaxWarnings);
}

std::vector<schema::FieldDoc> MeasuredBackboneFileFields() { return schema::Fields<MeasuredBackboneFile>(); }

std::string MeasuredBackboneFileToJson(const MeasuredBackboneFile& file) { return schema::ToJson(file); }

MeasuredBackboneFile MeasuredBackboneFileFromJson(const std::string& text, const std::string& source) {
  MeasuredBackboneFile file = schema::FromJson<MeasuredBackboneFile>(text, source, kMeasuredBackboneSchema);
  // Files written before the damping rate have one verdict, on ζ; the
  // writer always writes both or neither.
  DampingTrend& t = file.damping_trend;
  if (t.damping_ratio_verdict == Trend::kNotJudged && t.verdict != Trend::kNotJudged) {
    t.damping_ratio_verdict = t.verdict;
    t.verdict = Trend::kNotJudged;
  }
  return file;
}

void WriteMeasuredBackboneFile(const std::filesystem::path& path, const MeasuredBackboneFile& file) {
  WriteTextFileAtomically(path, MeasuredBackboneFileToJson(file));
}

MeasuredBackboneFile ReadMeasuredBackboneFile(const std::filesystem::path& path) {
  return MeasuredBackboneFileFromJson(
      ReadTextFile(path, "measured backbone file", "give the .json of 'beamid backbone --measured', or check the path"),
      path.string());
}

}  // namespace beamid::solver
