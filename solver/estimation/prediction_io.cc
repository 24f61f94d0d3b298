#include "solver/estimation/prediction_io.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <string_view>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/json_field.h"
#include "hb/option_checks.h"
#include "hb/text_file.h"
#include "solver/estimation/model_family.h"

namespace beamid::solver {
namespace {

using schema::kOmittedWhenEmpty;
using schema::kOptional;
using schema::Presence;
using schema::TextRule;

constexpr schema::Format kPredictionSchema{kPredictionFormat, "prediction",
                                           "give a prediction file written by 'beamid predict', or repair that field"};
constexpr std::string_view kQuantities[] = {"displacement_m", "velocity_m_s", "acceleration_m_s2"};

// Bounds on what a file can make the reader hold: predict writes one step
// per fitted step and one period of a few hundred samples.
constexpr std::size_t kMaxPredictedSteps = 1'000'000;
constexpr std::size_t kMaxSamples = 1'000'000;

template <typename Io>
constexpr bool kWriting = std::is_same_v<std::remove_const_t<Io>, schema::Writer>;

// A value JSON cannot hold (1e400 is refused): on reading, what an absent
// optional phasor leaves behind.
constexpr double kAbsent = -std::numeric_limits<double>::infinity();

bool KnownQuantity(const std::string& q) {
  return q.empty() || std::find(std::begin(kQuantities), std::end(kQuantities), q) != std::end(kQuantities);
}

// The quantity of the first "measured_<q>" key of a harmonic, or "": files of
// the earlier writer name it only there.
std::string QuantityOfTheKeys(const nlohmann::ordered_json& root) {
  const auto steps = root.find("steps");
  if (steps == root.end() || !steps->is_array()) return "";
  for (const auto& step : *steps) {
    if (!step.is_object() || !step.contains("harmonics") || !step["harmonics"].is_array()) continue;
    for (const auto& h : step["harmonics"]) {
      if (!h.is_object()) continue;
      for (std::string_view q : kQuantities)
        if (h.contains("measured_" + std::string(q))) return std::string(q);
    }
  }
  return "";
}

// A harmonic; its comparison keys name the file's compared quantity.
void DescribeHarmonic(auto& io, schema::Like<PredictionHarmonic> auto& h, const std::string& quantity) {
  using Io = std::remove_reference_t<decltype(io)>;
  io.Integer("k", h.k, 1, option_checks::kMaxHarmonics);
  io.Phasor("displacement_m", h.displacement_m, "m", schema::Any().OrNull());
  std::vector<double> std = {h.displacement_std_real_m, h.displacement_std_imag_m};
  io.Numbers("displacement_std_m", std, "m", schema::NonNegative().OrNull(),
             schema::Count::Exactly(2, "2 (std of re, std of im)"));
  io.Phasor("acceleration_m_s2", h.acceleration_m_s2, "m/s²", schema::Any().OrNull());
  io.Number("acceleration_amplitude_m_s2", h.acceleration_amplitude_m_s2, "m/s²", schema::NonNegative().OrNull());
  if constexpr (Io::kReading) {
    h.displacement_std_real_m = std[0];
    h.displacement_std_imag_m = std[1];
    h.measured = h.predicted = {kAbsent, kAbsent};
    h.relative_error = kAbsent;
  }
  // The comparison with the channel, in its quantity q, where it measured
  // the harmonic; written only there.
  const std::string& q = quantity;
  if (!q.empty() && (!kWriting<Io> || h.compared)) {
    io.Phasor("measured_" + q, h.measured, "of <q>", schema::Any().OrNull(), kOptional);
    io.Phasor("predicted_" + q, h.predicted, "of <q>", schema::Any().OrNull(), kOptional);
    io.Number("relative_error", h.relative_error, "1", schema::NonNegative().OrNull(), kOptional);
  }
  bool together = true;
  if constexpr (Io::kReading) {
    const bool measured = h.measured.real() != kAbsent, predicted = h.predicted.real() != kAbsent,
               error = h.relative_error != kAbsent;
    together = measured == predicted && predicted == error;
    h.compared = measured;
    if (!measured) h.measured = {};
    if (!predicted) h.predicted = {};
    if (!error) h.relative_error = 0.0;
  }
  io.Check(together, "measured_<q>, predicted_<q> and relative_error are there together or not at all");
}

}  // namespace

// The declaration of the prediction file (hb/json_schema.h): its writer,
// reader and documentation.
void Describe(auto& io, schema::Like<PredictionFile> auto& f) {
  io.Constant("format", kPredictionFormat, kOptional);  // the earlier writer had only "command"
  io.Constant("command", "predict");
  io.Text("beamid_version", f.beamid_version, TextRule::kAny, kOptional);
  io.Text("result", f.result_file);
  io.Choice("model", f.model_kind, kModelKindNames);
  io.Number("position_m", f.position_m, "m", schema::NonNegative());
  io.Text("compared_channel", f.compared_channel);
  // Files of the earlier writer lack it: the reader takes it from the keys.
  io.Text("compared_quantity", f.compared_quantity, TextRule::kAny, kOptional);
  io.Check(KnownQuantity(f.compared_quantity),
           "compared_quantity is displacement_m, velocity_m_s, acceleration_m_s2 or \"\"", "compared_quantity");
  // The documentation names the compared quantity <q>.
  const std::string quantity =
      schema::kDocumenting<std::remove_reference_t<decltype(io)>> ? "<q>" : f.compared_quantity;
  io.List("steps", f.steps, kMaxPredictedSteps, Presence::kRequired, [&](auto& step_io, auto& s) {
    step_io.Text("level", s.level);
    step_io.Text("file", s.file);
    step_io.Number("frequency_Hz", s.frequency_hz, "Hz", schema::Positive().OrNull());
    step_io.Boolean("converged", s.converged);
    step_io.List("harmonics", s.harmonics, option_checks::kMaxHarmonics, Presence::kRequired,
                 [&](auto& h_io, auto& h) { DescribeHarmonic(h_io, h, quantity); });
    step_io.Numbers("time_s", s.time_s, "s", schema::Any().OrNull(), kMaxSamples);
    step_io.Numbers("acceleration_m_s2", s.acceleration_m_s2, "m/s²", schema::Any().OrNull(), kMaxSamples);
    step_io.Numbers("acceleration_std_m_s2", s.acceleration_std_m_s2, "m/s²", schema::NonNegative().OrNull(),
                    kMaxSamples);
  });
  io.Text("campaign_sha256", f.campaign_sha256, TextRule::kAny, kOmittedWhenEmpty);
}

std::vector<schema::FieldDoc> PredictionFileFields() { return schema::Fields<PredictionFile>(); }

std::string PredictionFileToJson(const PredictionFile& file) { return schema::ToJson(file); }

PredictionFile PredictionFileFromJson(const std::string& text, const std::string& source) {
  nlohmann::ordered_json json = ParseJsonObject(text, source, kPredictionSchema.what, kPredictionSchema.fix);
  if (!json.contains("compared_quantity")) json["compared_quantity"] = QuantityOfTheKeys(json);
  PredictionFile file;
  schema::Reader::ReadInto(JsonField(json, "", source, kPredictionSchema.tag, kPredictionSchema.fix), file);
  return file;
}

void WritePredictionFile(const std::filesystem::path& path, const PredictionFile& file) {
  WriteTextFileAtomically(path, PredictionFileToJson(file));
}

PredictionFile ReadPredictionFile(const std::filesystem::path& path) {
  return PredictionFileFromJson(
      ReadTextFile(path, "prediction file", "give the file of 'beamid predict', or check the path"), path.string());
}

}  // namespace beamid::solver
