#include "solver/estimation/prediction_io.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string_view>

#include <nlohmann/json.hpp>

#include "hb/json_field.h"
#include "solver/estimation/model_family.h"
#include "hb/errors.h"
#include "hb/text_file.h"

namespace beamid::solver {
namespace {

// Insertion order is kept so that a file read and written again is the same text.
using Json = nlohmann::ordered_json;

constexpr const char* kFix = "give a prediction file written by 'beamid predict', or repair that field";
constexpr std::string_view kQuantities[] = {"displacement_m", "velocity_m_s", "acceleration_m_s2"};

// ---------------------------------------------------------------- writing

Json Number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }
Json Pair(double a, double b) { return Json::array({Number(a), Number(b)}); }
Json Phasor(std::complex<double> z) { return Pair(z.real(), z.imag()); }
Json Numbers(const std::vector<double>& values) {
  Json out = Json::array();
  for (double v : values) out.push_back(Number(v));
  return out;
}

Json StepToJson(const PredictionStep& s, const std::string& quantity) {
  Json harmonics = Json::array();
  for (const PredictionHarmonic& h : s.harmonics) {
    Json j = {{"k", h.k},
              {"displacement_m", Phasor(h.displacement_m)},
              {"displacement_std_m", Pair(h.displacement_std_real_m, h.displacement_std_imag_m)},
              {"acceleration_m_s2", Phasor(h.acceleration_m_s2)},
              {"acceleration_amplitude_m_s2", Number(h.acceleration_amplitude_m_s2)}};
    if (h.compared) {
      j["measured_" + quantity] = Phasor(h.measured);
      j["predicted_" + quantity] = Phasor(h.predicted);
      j["relative_error"] = Number(h.relative_error);
    }
    harmonics.push_back(j);
  }
  return {{"level", s.level},
          {"file", s.file},
          {"frequency_Hz", Number(s.frequency_hz)},
          {"converged", s.converged},
          {"harmonics", harmonics},
          {"time_s", Numbers(s.time_s)},
          {"acceleration_m_s2", Numbers(s.acceleration_m_s2)},
          {"acceleration_std_m_s2", Numbers(s.acceleration_std_m_s2)}};
}

// ---------------------------------------------------------------- reading

using Field = JsonField;


// The quantity of the harmonic's measured_<q> key, or "" when it has none.
std::string ComparedQuantity(const Field& h) {
  for (std::string_view q : kQuantities)
    if (h.Has("measured_" + std::string(q))) return std::string(q);
  return "";
}

PredictionStep StepFromJson(const Field& f, std::string& quantity) {
  f.OnlyKeys({"level", "file", "frequency_Hz", "converged", "harmonics", "time_s", "acceleration_m_s2",
              "acceleration_std_m_s2"});
  PredictionStep s;
  s.level = f.String("level");
  s.file = f.String("file");
  s.frequency_hz = f.Positive("frequency_Hz");
  s.converged = f.Boolean("converged");
  const Field harmonics = f.At("harmonics");
  for (std::size_t i = 0; i < harmonics.Size(); ++i) {
    const Field h = harmonics.At(i);
    PredictionHarmonic out;
    const std::string found = ComparedQuantity(h);
    if (!found.empty() && quantity.empty()) quantity = found;
    if (!found.empty() && found != quantity)
      h.Fail("compares " + found + ", not " + quantity + " as the rest of the file",
             "give a prediction file written by 'beamid predict' (one compared channel)");
    out.compared = !found.empty();
    if (out.compared) {
      h.OnlyKeys({"k", "displacement_m", "displacement_std_m", "acceleration_m_s2", "acceleration_amplitude_m_s2",
                  "measured_" + found, "predicted_" + found, "relative_error"});
      out.measured = h.At("measured_" + found).Phasor();
      out.predicted = h.At("predicted_" + found).Phasor();
      out.relative_error = h.Number("relative_error");
    } else {
      h.OnlyKeys({"k", "displacement_m", "displacement_std_m", "acceleration_m_s2", "acceleration_amplitude_m_s2"});
    }
    out.k = h.Count("k", 50);
    out.displacement_m = h.At("displacement_m").Phasor();
    const Field std = h.At("displacement_std_m");
    if (std.Size() != 2) std.Fail("must be [std of re, std of im]");
    out.displacement_std_real_m = std.At(0).NonNegative();
    out.displacement_std_imag_m = std.At(1).NonNegative();
    out.acceleration_m_s2 = h.At("acceleration_m_s2").Phasor();
    out.acceleration_amplitude_m_s2 = h.Number("acceleration_amplitude_m_s2");
    s.harmonics.push_back(out);
  }
  s.time_s = f.At("time_s").Numbers();
  s.acceleration_m_s2 = f.At("acceleration_m_s2").Numbers();
  s.acceleration_std_m_s2 = f.At("acceleration_std_m_s2").Numbers();
  return s;
}

}  // namespace

std::string PredictionFileToJson(const PredictionFile& file) {
  Json steps = Json::array();
  for (const PredictionStep& s : file.steps) steps.push_back(StepToJson(s, file.compared_quantity));
  Json root = {{"format", std::string(kPredictionFormat)},
                     {"command", "predict"},
                     {"beamid_version", file.beamid_version},
                     {"result", file.result_file},
                     {"model", file.model_kind},
                     {"position_m", Number(file.position_m)},
                     {"compared_channel", file.compared_channel},
                     {"compared_quantity", file.compared_quantity},
                     {"steps", steps}};
  if (!file.campaign_sha256.empty()) root["campaign_sha256"] = file.campaign_sha256;
  return root.dump(1) + "\n";
}

PredictionFile PredictionFileFromJson(const std::string& text, const std::string& source) {
  const Json json = ParseJsonObject(text, source, "prediction", "give a prediction file written by 'beamid predict'");
  const Field root(json, "", source, kPredictionFormat, kFix);
  // The earlier writer had no "format", only "command".
  if (root.Has("format")) {
    const std::string format = root.String("format");
    if (format != kPredictionFormat)
      throw InputError(source + ": field \"format\" is \"" + format + "\", not \"" + std::string(kPredictionFormat) +
                       "\". Fix: give a prediction file written by 'beamid predict'");
  }
  const std::string command = root.String("command");
  if (command != "predict")
    throw InputError(source + ": field \"command\" is \"" + command +
                     "\", not \"predict\". Fix: give a prediction file written by 'beamid predict'");
  root.OnlyKeys({"format", "command", "beamid_version", "result", "model", "position_m", "compared_channel",
                 "compared_quantity", "steps", "campaign_sha256"});
  PredictionFile file;
  file.beamid_version = root.Has("beamid_version") ? root.String("beamid_version") : "";
  file.result_file = root.String("result");
  if (root.Has("campaign_sha256")) file.campaign_sha256 = root.String("campaign_sha256");
  file.model_kind = root.String("model");
  try {
    FindModelFamily(file.model_kind);
  } catch (const InputError&) {
    root.At("model").Fail("is \"" + file.model_kind + "\"", "give one of " + ModelFamilyNames());
  }
  file.position_m = root.Number("position_m");
  file.compared_channel = root.String("compared_channel");
  if (root.Has("compared_quantity")) {
    const Field q = root.At("compared_quantity");
    file.compared_quantity = q.String();
    if (!file.compared_quantity.empty() &&
        std::find(std::begin(kQuantities), std::end(kQuantities), file.compared_quantity) == std::end(kQuantities))
      q.Fail("is \"" + file.compared_quantity + "\"", "give displacement_m, velocity_m_s, acceleration_m_s2 or \"\"");
  }
  const Field steps = root.At("steps");
  for (std::size_t i = 0; i < steps.Size(); ++i) file.steps.push_back(StepFromJson(steps.At(i), file.compared_quantity));
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
