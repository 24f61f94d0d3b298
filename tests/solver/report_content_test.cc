// What a report page says is what its analysis concluded: each page embeds
// exactly one JSON data block (solver/report/report_outcome.h), which must
// equal the outcome the test built its input for (written out here from
// the input, not read from the page), and every headline, caption and
// verdict on the page must state that same outcome: the fit within the
// noise or not, the damping law the data accept, the measured damping
// trend with its z, the diagnosis's verdict, blame, ranking, selection and
// rest, the held-out errors, and on a measured-backbone page each level's
// flags and jumps and the trends. One case per verdict value.
#include <fmt/core.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "solver/estimation/damping_laws.h"
#include "solver/estimation/fit_verdict.h"
#include "solver/report/diagnosis_residual_map.h"
#include "solver/report/html_report.h"
#include "tests/support/sample_report.h"
#include "solver/report/measured_backbone_report.h"

namespace beamid::solver {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using json = nlohmann::json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The page's one data block, parsed; a failure when there is not exactly one.
json DataBlock(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"beamid-report-data\">";
  // One script element, the data block, and one end tag: no text inside closes
  // it.
  EXPECT_EQ(Count(page, "<script type="), 1u);
  EXPECT_EQ(Count(page, open), 1u);
  EXPECT_EQ(Count(page, "</script"), 1u);
  const std::size_t start = page.find(open);
  if (start == std::string::npos) {
    ADD_FAILURE() << "no data block";
    return nullptr;
  }
  const std::size_t begin = start + open.size(), end = page.find("</script>", begin);
  if (end == std::string::npos) {
    ADD_FAILURE() << "the data block is not closed";
    return nullptr;
  }
  return json::parse(page.substr(begin, end - begin));
}

// The content of the first element that opens with `open` up to `close`;
// "" (and a failure when `required`) when there is none.
std::string Element(const std::string& page, const std::string& open, const std::string& close, bool required = true) {
  const std::size_t start = page.find(open);
  if (start == std::string::npos) {
    if (required) ADD_FAILURE() << "no " << open;
    return "";
  }
  const std::size_t begin = start + open.size();
  return page.substr(begin, page.find(close, begin) - begin);
}

std::string Join(const json& names, const std::string& separator) {
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : separator) + n.get<std::string>();
  return text;
}

// ---- The identification page ----

ParameterEstimate Parameter(const std::string& name, double value, double std) {
  return {.name = name,
          .unit = "N*m/rad",
          .value = value,
          .std = std,
          .lower_95 = value - 1.96 * std,
          .upper_95 = value + 1.96 * std};
}

ReportInput Input(double chi_square, int dof) {
  ReportInput input;
  input.result_file = "out/result.json";
  input.campaign_folder = "campaign";
  input.result.model.law = "polynomial";
  input.result.model.fit_channels = {"acc1"};
  input.result.parameters = {{.name = "k1",
                              .unit = "N*m/rad",
                              .value = 150.2,
                              .std = 0.3,
                              .lower_95 = 150.2 - 1.96 * 0.3,
                              .upper_95 = 150.2 + 1.96 * 0.3}};
  input.result.fit.chi_square = chi_square;
  input.result.fit.degrees_of_freedom = dof;
  input.result.fit.reduced_chi_square = chi_square / dof;
  input.result.fit.verdict = JudgeFit(chi_square / dof);
  return input;
}

ReportCurves Curves(Trend trend, double z, bool damping = true) {
  return testing::MinimalReportCurves(trend, z, damping);
}

HeldOutChannel HeldOut(const std::string& channel, int steps, double worst_h1, int measurable_h1, double worst_h3,
                       int measurable_h3) {
  HeldOutChannel v{.channel = channel,
                   .worst_h1_relative_error = worst_h1,
                   .worst_h3_relative_error = worst_h3,
                   .measurable_steps_h1 = measurable_h1,
                   .measurable_steps_h3 = measurable_h3};
  v.steps.resize(static_cast<std::size_t>(steps));
  return v;
}

std::string HeldOutWords(const json& v, int harmonic) {
  const std::string key = fmt::format("_h{}", harmonic), ordinal = harmonic == 1 ? "1st" : "3rd";
  const int measurable = v["measurable_steps" + key].get<int>(), steps = v["steps"].get<int>();
  if (measurable == 0)
    return fmt::format("nothing measurable on the {} harmonic (none of the {} steps resolves", ordinal, steps);
  return fmt::format(
      "worst error {:.2f} % on the {} harmonic (over the {} of "
      "{} steps that resolve it)",
      100.0 * v["worst" + key + "_relative_error"].get<double>(), ordinal, measurable, steps);
}

// Every headline, caption and verdict of the identification page against the
// block.
void ExpectPageStates(const std::string& page, const json& block) {
  const json& fit = block["fit"];
  const double reduced = fit["reduced_chi_square"].get<double>();
  EXPECT_THAT(page, HasSubstr(fmt::format("; model {} (", block["model"]["kind"].get<std::string>())));
  EXPECT_THAT(page, HasSubstr("; support law " + block["model"]["support_law"].get<std::string>() + ";"));
  EXPECT_THAT(page, HasSubstr(fmt::format("reduced χ² = {:.6g} (χ² {:.6g} over {} degrees of freedom)", reduced,
                                          fit["chi_square"].get<double>(), fit["degrees_of_freedom"].get<int>())));
  // The fit's verdict: "within the noise" iff the block says so, never both.
  const bool within = fit["within_noise"].get<bool>();
  const std::string verdict = Element(page, "<p class=\"fit-verdict\">", "</p>");
  EXPECT_THAT(verdict, HasSubstr(fmt::format("(reduced χ² {:.6g}, at most 2 allowed)", reduced)));
  EXPECT_EQ(verdict.find("<b>The model fits within the noise</b>") == 0, within) << verdict;
  EXPECT_EQ(verdict.find("<b>The model misfits beyond the noise</b>") == 0, !within) << verdict;
  EXPECT_EQ(page.find("misfits beyond the noise") != std::string::npos, !within);
  EXPECT_EQ(verdict.find("beamid diagnose") != std::string::npos, !within);

  // The damping law whose parameters are the answer.
  const json& law = block["damping_law"];
  const bool rejected = !law.is_null() && law["assumed_rejected"].get<bool>();
  EXPECT_EQ(page.find("reject the loss factor") != std::string::npos, rejected);
  if (rejected) {
    EXPECT_THAT(page, HasSubstr(fmt::format("accept the <b>{}</b> damping law (reduced χ² {:.6g} "
                                            "against {:.6g})",
                                            law["answer"].get<std::string>(),
                                            law["answer_reduced_chi_square"].get<double>(), reduced)));
  }

  // The measured damping trend: its words and z, and no other verdict's words.
  const json& trend = block["damping_trend"];
  const std::string caption =
      Element(page, "<figure class=\"plot\" id=\"damping-plot\">", "</figure>", !trend["verdict"].is_null());
  const std::string words = Element(caption, "<figcaption>", "</figcaption>", !trend["verdict"].is_null());
  for (const char* name :
       {"rises beyond a constant damper", "falls below a constant damper", "consistent with a constant damper"}) {
    const bool stated = !trend["verdict"].is_null() && trend["verdict"] == name;
    EXPECT_EQ(words.find(name) != std::string::npos, stated) << name << " in: " << words;
    if (stated) {
      EXPECT_THAT(words, HasSubstr(fmt::format("{} ({:+.1f} σ)", name, trend["z"].get<double>())));
    }
  }
  if (trend["verdict"].is_null()) {
    EXPECT_THAT(page, Not(HasSubstr("The damping rate ζω_n")));
  }

  // The diagnosis: verdict, blame, ranking, selection, the rest of the misfit.
  const json& d = block["diagnosis"];
  EXPECT_EQ(page.find("<section id=\"diagnosis\">") != std::string::npos, !d.is_null());
  if (!d.is_null()) {
    std::string headline = "<b>Verdict:</b> " + d["verdict"].get<std::string>();
    if (!d["blame"].is_null()) headline += " — to blame: <b>" + d["blame"].get<std::string>() + "</b>";
    if (!d["ranked_by"].is_null()) headline += " (ranked by " + d["ranked_by"].get<std::string>() + ")";
    EXPECT_EQ(Element(page, "<p class=\"diagnosis-verdict\">", "</p>"), headline);
    EXPECT_EQ(Element(page, "<p class=\"diagnosis-selected\">", "</p>"),
              "<b>Selected:</b> " + Join(d["selected"], ", "));
    const std::string rest = Element(page, "<p class=\"diagnosis-rest\">", "</p>");
    EXPECT_EQ(rest.find("lies within the noise") != std::string::npos, d["rest_within_noise"].get<bool>()) << rest;
    EXPECT_EQ(rest.find("remains beyond the noise") != std::string::npos, !d["rest_within_noise"].get<bool>()) << rest;
    const bool named = d["verdict"] == "cause named" || d["verdict"] == "combination named";
    EXPECT_EQ(page.find("<h2>The selected model: " + Join(d["selected"], " + ") + "</h2>") != std::string::npos, named);
    EXPECT_EQ(page.find("<h2>Identified parameters</h2>") != std::string::npos, !named);
  }

  // The held-out errors, one sentence per channel.
  EXPECT_EQ(Count(page, "<p class=\"held-out\">"), block["held_out"].size());
  for (const auto& v : block["held_out"]) {
    const std::string sentence =
        Element(page, "<p class=\"held-out\">Held-out " + v["channel"].get<std::string>() + ": ", "</p>");
    EXPECT_THAT(sentence, HasSubstr(HeldOutWords(v, 1)));
    EXPECT_THAT(sentence, HasSubstr(HeldOutWords(v, 3)));
  }
}

json Fit(double chi_square, int dof, bool within_noise) {
  return {{"chi_square", chi_square},
          {"degrees_of_freedom", dof},
          {"reduced_chi_square", chi_square / dof},
          {"within_noise", within_noise}};
}

json Identification(const json& model, const json& fit, const json& law, const json& trend, const json& diagnosis,
                    const json& held_out) {
  return {{"format", "beamid-report-data/1"},
          {"page", "identification"},
          {"model", model},
          {"fit", fit},
          {"damping_law", law},
          {"damping_trend", trend},
          {"diagnosis", diagnosis},
          {"held_out", held_out}};
}

const json kHb = {{"kind", "hb"}, {"support_law", "polynomial"}};

// (a) As `beamid demo` ends: the fit within the noise, the loss factor
// accepted, damping rising with amplitude, a held-out channel whose 3rd
// harmonic no step resolves.
TEST(ReportContent, ADemoLikeIdentification) {
  ReportInput input = Input(193.2, 186);
  input.result.damping_laws.laws = {DampingLawFitOf("loss_factor", {Parameter("k1", 150.2, 0.3)}, 193.2, 186),
                                    DampingLawFitOf("rayleigh", {Parameter("k1", 150.3, 0.3)}, 192.9, 185)};
  JudgeDampingLaws(&input.result.damping_laws);
  input.result.validation = {HeldOut("acc3", 24, 0.0123, 22, kNaN, 0)};
  const std::string page = HtmlReport(input, Curves(Trend::kRises, 10.5));
  const json block = DataBlock(page);
  EXPECT_EQ(block, Identification(kHb, Fit(193.2, 186, true),
                                  {{"assumed", "loss_factor"},
                                   {"answer", "loss_factor"},
                                   {"answer_reduced_chi_square", 193.2 / 186},
                                   {"assumed_rejected", false}},
                                  {{"verdict", "rises beyond a constant damper"}, {"z", 10.5}}, nullptr,
                                  json::array({{{"channel", "acc3"},
                                                {"steps", 24},
                                                {"worst_h1_relative_error", 0.0123},
                                                {"measurable_steps_h1", 22},
                                                {"worst_h3_relative_error", nullptr},
                                                {"measurable_steps_h3", 0}}})))
      << block.dump(2);
  ExpectPageStates(page, block);
  EXPECT_THAT(page, HasSubstr("rises beyond a constant damper (+10.5 σ)"));
}

// The fit beyond the noise, the loss factor rejected for Rayleigh damping,
// damping falling; then consistent with a constant damper and no laws
// refitted; then no damping points (the trend not judged).
TEST(ReportContent, EachFitVerdictDampingLawAndTrend) {
  ReportInput misfit = Input(540.0, 100);
  misfit.result.damping_laws.laws = {DampingLawFitOf("loss_factor", {Parameter("k1", 150.2, 0.3)}, 160.0, 100),
                                     DampingLawFitOf("rayleigh", {Parameter("k1", 151.0, 0.3)}, 100.0, 99)};
  JudgeDampingLaws(&misfit.result.damping_laws);
  misfit.result.validation = {HeldOut("acc3", 12, 0.081, 12, 0.35, 5)};
  const std::string page = HtmlReport(misfit, Curves(Trend::kFalls, -11.6));
  json block = DataBlock(page);
  EXPECT_EQ(block, Identification(kHb, Fit(540.0, 100, false),
                                  {{"assumed", "loss_factor"},
                                   {"answer", "rayleigh"},
                                   {"answer_reduced_chi_square", 100.0 / 99},
                                   {"assumed_rejected", true}},
                                  {{"verdict", "falls below a constant damper"}, {"z", -11.6}}, nullptr,
                                  json::array({{{"channel", "acc3"},
                                                {"steps", 12},
                                                {"worst_h1_relative_error", 0.081},
                                                {"measurable_steps_h1", 12},
                                                {"worst_h3_relative_error", 0.35},
                                                {"measurable_steps_h3", 5}}})))
      << block.dump(2);
  ExpectPageStates(page, block);
  EXPECT_THAT(page, HasSubstr("falls below a constant damper (-11.6 σ)"));

  const std::string constant = HtmlReport(Input(187.0, 186), Curves(Trend::kNone, 0.4));
  block = DataBlock(constant);
  EXPECT_EQ(block,
            Identification(kHb, Fit(187.0, 186, true), nullptr,
                           {{"verdict", "consistent with a constant damper"}, {"z", 0.4}}, nullptr, json::array()))
      << block.dump(2);
  ExpectPageStates(constant, block);
  EXPECT_THAT(constant, HasSubstr("is consistent with a constant damper (+0.4 σ)"));

  const std::string unjudged = HtmlReport(Input(187.0, 186), Curves(Trend::kRises, 3.0, /*damping=*/false));
  block = DataBlock(unjudged);
  EXPECT_EQ(block, Identification(kHb, Fit(187.0, 186, true), nullptr, {{"verdict", nullptr}, {"z", nullptr}}, nullptr,
                                  json::array()))
      << block.dump(2);
  ExpectPageStates(unjudged, block);
}

// (c) A multiple-scales result: the model's family is stated and recorded.
TEST(ReportContent, AMultipleScalesResult) {
  ReportInput input = Input(95.0, 90);
  input.result.model.kind = ModelKind::kMultipleScales;
  input.result.model.law = "cubic";
  const std::string page = HtmlReport(input, Curves(Trend::kRises, 6.2));
  const json block = DataBlock(page);
  EXPECT_EQ(block, Identification({{"kind", "ms"}, {"support_law", "cubic"}}, Fit(95.0, 90, true), nullptr,
                                  {{"verdict", "rises beyond a constant damper"}, {"z", 6.2}}, nullptr, json::array()))
      << block.dump(2);
  ExpectPageStates(page, block);
  EXPECT_THAT(page, HasSubstr("model ms (multiple scales)"));
  EXPECT_THAT(page, Not(HasSubstr("harmonic balance)")));
}

// (b) A diagnosis, once per verdict: a concealed friction named (the model
// to blame, ranked by the held-out channel), a fault of the recording, a
// pair, two causes the data cannot tell apart, nothing to explain, and a
// misfit nothing explains.
TEST(ReportContent, EachDiagnosisVerdict) {
  struct Case {
    DiagnosisVerdict verdict;
    Blame blame;
    RankedBy ranked_by;
    std::vector<std::string> selected;
    bool rest_within_noise;
    json expected;
  };
  const Case cases[] = {
      {DiagnosisVerdict::kCauseNamed,
       Blame::kModel,
       RankedBy::kHeldOutChannels,
       {"support_friction"},
       true,
       {{"verdict", "cause named"},
        {"blame", "the model"},
        {"ranked_by", "held-out channels"},
        {"selected", {"support_friction"}},
        {"rest_within_noise", true}}},
      {DiagnosisVerdict::kCauseNamed,
       Blame::kRecording,
       RankedBy::kInSampleBic,
       {"force_drift"},
       false,
       {{"verdict", "cause named"},
        {"blame", "the recording"},
        {"ranked_by", "in-sample BIC"},
        {"selected", {"force_drift"}},
        {"rest_within_noise", false}}},
      {DiagnosisVerdict::kCombinationNamed,
       Blame::kModel,
       RankedBy::kLevelsLeftOut,
       {"support_friction", "added_mass"},
       true,
       {{"verdict", "combination named"},
        {"blame", "the model"},
        {"ranked_by", "levels left out in turn"},
        {"selected", {"support_friction", "added_mass"}},
        {"rest_within_noise", true}}},
      {DiagnosisVerdict::kCausesIndistinguishable,
       Blame::kNone,
       RankedBy::kNone,
       {"support_friction", "clamp_compliance"},
       false,
       {{"verdict", "causes indistinguishable"},
        {"blame", nullptr},
        {"ranked_by", nullptr},
        {"selected", {"support_friction", "clamp_compliance"}},
        {"rest_within_noise", false}}},
      {DiagnosisVerdict::kNoSignificantDiscrepancy,
       Blame::kNone,
       RankedBy::kNone,
       {"none"},
       true,
       {{"verdict", "no significant discrepancy"},
        {"blame", nullptr},
        {"ranked_by", nullptr},
        {"selected", {"none"}},
        {"rest_within_noise", true}}},
      {DiagnosisVerdict::kUnexplained,
       Blame::kNone,
       RankedBy::kNone,
       {"none"},
       false,
       {{"verdict", "unexplained"},
        {"blame", nullptr},
        {"ranked_by", nullptr},
        {"selected", {"none"}},
        {"rest_within_noise", false}}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.expected.dump());
    ReportInput input = Input(4.5e5, 186);
    DiagnosisResult d;
    d.verdict = c.verdict;
    d.blame = c.blame;
    d.ranked_by = c.ranked_by;
    d.selected = c.selected;
    d.rest_within_noise = c.rest_within_noise;
    d.base.parameters = {Parameter("k1", 150.2, 0.3)};
    d.final_fit.parameters = {Parameter("k1", 149.8, 0.2)};
    for (double f : {54.5, 55.0, 55.5})
      d.response.push_back({.level = "high",
                            .frequency_hz = f,
                            .channel = "acc1",
                            .measured = {6.2, 0.0},
                            .base_model = {3.5, 0.0},
                            .final_model = {6.1, 0.0}});
    input.diagnosis = DiagnosisFile{.diagnosis = d};
    const std::string page = HtmlReport(input, Curves(Trend::kRises, 10.5));
    const json block = DataBlock(page);
    EXPECT_EQ(block,
              Identification(kHb, Fit(4.5e5, 186, false), nullptr,
                             {{"verdict", "rises beyond a constant damper"}, {"z", 10.5}}, c.expected, json::array()))
        << block.dump(2);
    ExpectPageStates(page, block);
  }
}

// A text of the record cannot close the data block or open a comment in it.
TEST(ReportContent, NoTextOfTheRecordClosesTheBlock) {
  ReportInput input = Input(187.0, 186);
  input.result.model.law = "</script><script>alert(1)</script><!--";
  const std::string page = HtmlReport(input, Curves(Trend::kNone, 0.4));
  const json block = DataBlock(page);
  EXPECT_EQ(block["model"]["support_law"], "</script><script>alert(1)</script><!--");
  EXPECT_THAT(page, Not(HasSubstr("<!--")));
}

// ---- (d) The measured-backbone page ----

Estimate Est(double value, double std) { return {.value = value, .std = std, .valid = true}; }

LevelResonance Level(const std::string& label, double amplitude_m) {
  LevelResonance l;
  l.label = label;
  l.quadrature_frequency_hz = Est(54.0 + 100 * amplitude_m, 2e-4);
  l.quadrature_amplitude_m = Est(amplitude_m, 2e-8);
  l.damping_ratio = Est(0.0057, 4e-5);
  return l;
}

SweepJump Jump(int from_step) {
  return {.from_step = from_step,
          .to_step = from_step + 1,
          .from_frequency_hz = 53.1,
          .to_frequency_hz = 53.0,
          .up_sweep = false,
          .receptance_ratio = 2.5,
          .phase_change_rad = 1.0};
}

MeasuredBackboneFile BackboneFile(Trend rate, double rate_z, Trend ratio, double ratio_z) {
  MeasuredBackboneFile file;
  file.inputs = {"campaign"};
  file.channel = "acc2";
  file.response_quantity = "acceleration";
  LevelResonance low = Level("low", 2.9e-4);
  LevelResonance mid = Level("mid", 9.0e-4);
  mid.flags = {{.kind = LevelFlagKind::kRegenerationBeyondNoise,
                .quantity = "regeneration_relative_rms",
                .message = "the fit regenerates the level to 4 %, beyond its noise"}};
  LevelResonance high = Level("high", 2.6e-3);
  high.jumps = {Jump(30), Jump(52)};
  high.flags = {{.kind = LevelFlagKind::kJump, .quantity = "sweep", .message = "the response jumps down"},
                {.kind = LevelFlagKind::kJump, .quantity = "sweep", .message = "the response jumps up"},
                {.kind = LevelFlagKind::kDampingNotPositive,
                 .quantity = "half_power_damping_ratio",
                 .message = "the half-power damping ratio is -0.1 %"}};
  high.in_global_fit = false;
  file.levels = {low, mid, high};
  file.single_mode_fit.form = "wn^2: polynomial 2, zeta*wn: polynomial 1, A constant";
  file.single_mode_fit.reduced_chi_square = 1.37;
  file.damping_trend = {.z = ratio_z, .damping_rate_z = rate_z, .verdict = rate, .damping_ratio_verdict = ratio};
  return file;
}

void ExpectBackbonePageStates(const std::string& page, const json& block) {
  const json& levels = block["levels"];
  EXPECT_THAT(page,
              HasSubstr(fmt::format("<p>{} levels, {} flagged, {} left out of the cross-level fit.</p>", levels.size(),
                                    block["flagged_levels"].get<int>(), block["left_out_levels"].get<int>())));
  for (const auto& l : levels) {
    const std::string label = l["label"].get<std::string>();
    SCOPED_TRACE(label);
    const std::string row = Element(page, "<tr><td>" + label + "</td>", "</tr>");
    const std::string in_fit = l["in_global_fit"].get<bool>() ? "yes" : "<span class=\"flag\">no</span>";
    EXPECT_THAT(row,
                ::testing::EndsWith("<td>" + in_fit + "</td><td class=\"flag\">" + Join(l["flags"], ", ") + "</td>"));
    // The notes under the table: one item per jump.
    const std::string notes = Element(page, "<h3>" + label + "</h3>", "</ul>", /*required=*/false);
    EXPECT_EQ(Count(notes, "<li>jump ("), l["jumps"].get<std::size_t>());
  }
  EXPECT_THAT(page, HasSubstr(fmt::format("<p>Form: {}; reduced χ² {:.3g}.</p>",
                                          block["single_mode_fit"]["form"].get<std::string>(),
                                          block["single_mode_fit"]["reduced_chi_square"].get<double>())));
  const std::string trend = Element(page, "<p class=\"damping-trend\">", "</p>");
  const json& rate = block["damping_rate_trend"];
  const json& ratio = block["damping_ratio_trend"];
  EXPECT_THAT(
      trend, HasSubstr("<strong>" + (rate["verdict"].is_null() ? "not available" : rate["verdict"].get<std::string>()) +
                       "</strong>"));
  if (!rate["verdict"].is_null()) {
    EXPECT_THAT(trend, HasSubstr(fmt::format("/(s·m), {:+.1f} σ); ζ alone", rate["z"].get<double>())));
  }
  if (!ratio["verdict"].is_null()) {
    EXPECT_THAT(trend, HasSubstr(fmt::format("ζ alone {} (slope", ratio["verdict"].get<std::string>())));
    EXPECT_THAT(trend, HasSubstr(fmt::format("per m, {:+.1f} σ)", ratio["z"].get<double>())));
  }
}

json BackboneBlock(const json& rate, const json& ratio) {
  return {{"format", "beamid-report-data/1"},
          {"page", "measured-backbone"},
          {"levels",
           {{{"label", "low"}, {"flags", json::array()}, {"jumps", 0}, {"in_global_fit", true}},
            {{"label", "mid"}, {"flags", {"regeneration_beyond_noise"}}, {"jumps", 0}, {"in_global_fit", true}},
            {{"label", "high"}, {"flags", {"jump", "damping_not_positive"}}, {"jumps", 2}, {"in_global_fit", false}}}},
          {"flagged_levels", 2},
          {"left_out_levels", 1},
          {"single_mode_fit",
           {{"form", "wn^2: polynomial 2, zeta*wn: polynomial 1, A constant"}, {"reduced_chi_square", 1.37}}},
          {"damping_rate_trend", rate},
          {"damping_ratio_trend", ratio}};
}

TEST(ReportContent, AMeasuredBackbonePageForEachTrend) {
  struct Case {
    Trend rate;
    double rate_z;
    Trend ratio;
    double ratio_z;
    json expected_rate, expected_ratio;
  };
  const Case cases[] = {
      {Trend::kRises,
       4.2,
       Trend::kNone,
       0.3,
       {{"verdict", "rises beyond a constant damper"}, {"z", 4.2}},
       {{"verdict", "no significant trend"}, {"z", 0.3}}},
      {Trend::kFalls,
       -3.1,
       Trend::kFalls,
       -5.5,
       {{"verdict", "falls below a constant damper"}, {"z", -3.1}},
       {{"verdict", "falls"}, {"z", -5.5}}},
      {Trend::kNone,
       0.7,
       Trend::kRises,
       2.9,
       {{"verdict", "consistent with a constant damper"}, {"z", 0.7}},
       {{"verdict", "rises"}, {"z", 2.9}}},
      {Trend::kNotJudged,
       0.0,
       Trend::kNotJudged,
       0.0,
       {{"verdict", nullptr}, {"z", nullptr}},
       {{"verdict", nullptr}, {"z", nullptr}}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.expected_rate.dump());
    const std::string page =
        MeasuredBackboneHtmlReport(BackboneFile(c.rate, c.rate_z, c.ratio, c.ratio_z), "out/measured.json");
    const json block = DataBlock(page);
    EXPECT_EQ(block, BackboneBlock(c.expected_rate, c.expected_ratio)) << block.dump(2);
    ExpectBackbonePageStates(page, block);
  }
}


// ---- A diagnosis that names physics: its model beside the base ----

// Three steps of acc1 (fitted, harmonics 1..3) and one of the held-out acc3;
// the base misfits large in h1, the selected model's within the noise.
DiagnosisResult NamedFriction() {
  DiagnosisResult d;
  d.verdict = DiagnosisVerdict::kCauseNamed;
  d.blame = Blame::kModel;
  d.ranked_by = RankedBy::kHeldOutChannels;
  d.selected = {"support_friction"};
  d.base.parameters = {Parameter("k1", 150.2, 0.3)};
  d.final_fit.parameters = {Parameter("k1", 149.8, 0.2)};
  const std::vector<std::vector<double>> base = {{30.0, 4.0, 0.5}, {41.0, 2.0, 0.25}, {12.0, 3.0, 0.125}},
                                         final = {{0.5, 1.5, 0.25}, {1.25, 0.75, 0.5}, {0.5, 1.0, 0.25}};
  const double frequencies[] = {54.5, 55.0, 55.5};
  for (std::size_t i = 0; i < 3; ++i) {
    d.response.push_back({.level = "high", .frequency_hz = frequencies[i], .channel = "acc1",
                          .measured = {6.2, 0.0}, .base_model = {3.5, 0.0}, .final_model = {6.1, 0.0},
                          .base_misfit_sigma = base[i], .final_misfit_sigma = final[i]});
    for (std::size_t k = 0; k < 3; ++k) {
      d.base.chi_square += base[i][k] * base[i][k];
      d.final_fit.chi_square += final[i][k] * final[i][k];
    }
  }
  // Held out: not on the map, and its misfits not in the fits' χ².
  d.response.push_back({.level = "high", .frequency_hz = 55.0, .channel = "acc3", .held_out = true,
                        .measured = {1.0, 0.0}, .base_model = {0.5, 0.0}, .final_model = {0.9, 0.0},
                        .base_misfit_sigma = {99.0}, .final_misfit_sigma = {7.0}});
  d.final_backbone = {.channel = "acc1", .position_m = 0.1};
  for (double f : {54.2, 54.6, 55.1}) d.final_backbone.points.push_back({.amplitude_m = 1e-4 * (f - 54.0), .frequency_hz = f});
  return d;
}

TEST(ReportContent, TheDiagnosisMapsAreTheBaseAndTheSelectedModelsCellByCell) {
  const DiagnosisResult d = NamedFriction();
  for (const DiagnosedModel model : {DiagnosedModel::kBase, DiagnosedModel::kSelected}) {
    const ResidualMap map = DiagnosisResidualMap(d.response, model);
    EXPECT_EQ(map.rows, (std::vector<std::string>{"acc1 h1", "acc1 h2", "acc1 h3"}));
    EXPECT_EQ(map.step_frequency_hz, (std::vector<double>{54.5, 55.0, 55.5}));
    ASSERT_EQ(map.whitened_norm.cols(), 3);
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t k = 0; k < 3; ++k) {
        const ResponsePoint& p = d.response[i];
        EXPECT_EQ(map.whitened_norm(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)),
                  (model == DiagnosedModel::kBase ? p.base_misfit_sigma : p.final_misfit_sigma)[k]);
      }
    EXPECT_EQ(SumOfSquares(map), model == DiagnosedModel::kBase ? d.base.chi_square : d.final_fit.chi_square);
  }
}

TEST(ReportContent, ADiagnosisDrawsTheSelectedModelsBackboneAndItsResidualMapAfterTheCause) {
  ReportInput input = Input(4.5e5, 186);
  input.diagnosis = DiagnosisFile{.diagnosis = NamedFriction()};
  const DiagnosisResult& d = input.diagnosis->diagnosis;
  const std::string page = HtmlReport(input, Curves(Trend::kRises, 10.5));
  ExpectPageStates(page, DataBlock(page));
  // Before and after, each captioned with its own χ², the map's equal to the fit's.
  const std::string before = Element(page, "<figure class=\"plot\" id=\"residual-map\">", "</figure>");
  const std::string after = Element(page, "<figure class=\"plot\" id=\"residual-map-selected\">", "</figure>");
  EXPECT_THAT(before, HasSubstr(fmt::format("χ² {:.6g} on the map; {:.6g} in its fit", d.base.chi_square,
                                            d.base.chi_square)));
  EXPECT_THAT(after, HasSubstr(fmt::format("χ² {:.6g} on the map; {:.6g} in its fit", d.final_fit.chi_square,
                                           d.final_fit.chi_square)));
  EXPECT_THAT(after, HasSubstr("the selected model (support_friction)"));
  // One colour scale: the selected model's cells (at most 1.5 σ) are drawn on
  // the base's scale, which reaches 100 σ.
  EXPECT_THAT(before, HasSubstr("100 (misfit)"));
  EXPECT_THAT(after, HasSubstr("100 (misfit)"));
  // The backbone figure: the base's and the selected model's, each in the legend.
  const std::string backbone = Element(page, "<figure class=\"plot\" id=\"backbone-plot\">", "</figure>");
  EXPECT_THAT(backbone, HasSubstr("base model's backbone"));
  EXPECT_THAT(backbone, HasSubstr("backbone of the selected model"));
  EXPECT_THAT(backbone, HasSubstr("Blue: the backbone of the model the diagnosis selected (support_friction)"));
}

TEST(ReportContent, ABackboneTracedElsewhereOrNotAtAllIsSaidNotDrawn) {
  for (const auto& [channel, error, said] :
       {std::tuple<std::string, std::string, std::string>{"acc2", "", "traced at acc2, not at this sensor"},
        {"acc1", "no quadrature point", "could not be traced: no quadrature point"}}) {
    ReportInput input = Input(4.5e5, 186);
    DiagnosisResult d = NamedFriction();
    d.final_backbone.channel = channel;
    d.final_backbone.error = error;
    if (!error.empty()) d.final_backbone.points.clear();
    input.diagnosis = DiagnosisFile{.diagnosis = d};
    const std::string page = HtmlReport(input, Curves(Trend::kRises, 10.5));
    const std::string backbone = Element(page, "<figure class=\"plot\" id=\"backbone-plot\">", "</figure>");
    EXPECT_THAT(backbone, HasSubstr(said));
    EXPECT_THAT(backbone, Not(HasSubstr("backbone of the selected model")));
  }
}

TEST(ReportContent, ADiagnosisWithoutMisfitsKeepsTheIdentifiedMap) {
  ReportInput input = Input(4.5e5, 186);
  DiagnosisResult d = NamedFriction();
  for (auto& p : d.response) p.base_misfit_sigma.clear(), p.final_misfit_sigma.clear();
  input.diagnosis = DiagnosisFile{.diagnosis = d};
  const std::string page = HtmlReport(input, Curves(Trend::kRises, 10.5));
  EXPECT_EQ(Count(page, "id=\"residual-map\""), 1u);
  EXPECT_EQ(Count(page, "id=\"residual-map-selected\""), 0u);
}

}  // namespace
}  // namespace beamid::solver
