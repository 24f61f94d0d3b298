// `beamid report` end to end on a campaign from the independent time-domain
// simulator: simulate, identify (fit acc1, acc2; hold out acc3), report. The
// page is self-contained and holds every plot as SVG with drawn paths; headless
// Chromium lays the plots out with visible size and drawn paths, and its
// screenshot (taken by the command with --screenshot) is not blank inside
// every plot. Skipped only when Chromium is absent (scripts/install-deps.sh
// installs it).
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solver/diagnosis/diagnosis_io.h"
#include "solver/estimation/result_io.h"
#include "solver/report/html_screenshot.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/png_image.h"
#include "tests/support/temp_path.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

// Two levels of eight steps around the first resonance (≈ 54 Hz), the
// paper's set-up and support law.
const std::string kScenario = beamid::testing::PaperScenarioJson(
    "report test: paper set-up, two levels",
    R"([{"label": "low", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 52, "stop": 57, "step": 0.7}},
        {"label": "high", "force_amplitude_N": 8.0, "frequencies_Hz": {"start": 52, "stop": 57, "step": 0.7}}])",
    3);

struct ProgramRun {
  int exit_code = -1;
  std::string output;
};

ProgramRun RunShell(const std::string& command, const fs::path& log) {
  const int status = std::system((command + " > " + log.string() + " 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class ReportCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new fs::path(beamid::testing::UniqueTempPath("beamid_report_test"));
    fs::remove_all(*folder_);
    fs::create_directories(*folder_);
    std::ofstream(*folder_ / "scenario.json") << kScenario;
    const std::string beamid = BEAMID_EXECUTABLE;
    const fs::path& f = *folder_;
    simulate_ = new ProgramRun(RunShell(beamid + " -q simulate " + (f / "scenario.json").string() + " -o " +
                                       (f / "campaign").string(), f / "simulate.log"));
    identify_ = new ProgramRun(RunShell(beamid + " -q identify " + (f / "campaign").string() +
                                       " --fit acc1,acc2 --validate acc3 -o " + (f / "result.json").string(),
                                   f / "identify.log"));
    const auto start = std::chrono::steady_clock::now();
    // From another working folder: the campaign is found through result.json.
    report_ = new ProgramRun(
        RunShell("cd / && " + beamid + " report " + (f / "result.json").string() + " -o " + (f / "report.html").string(),
                 f / "report.log"));
    report_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  static void TearDownTestSuite() {
    fs::remove_all(*folder_);
    delete folder_;
    delete simulate_;
    delete identify_;
    delete report_;
  }

  static fs::path* folder_;
  static ProgramRun *simulate_, *identify_, *report_;
  static double report_seconds_;
};

fs::path* ReportCommand::folder_ = nullptr;
ProgramRun* ReportCommand::simulate_ = nullptr;
ProgramRun* ReportCommand::identify_ = nullptr;
ProgramRun* ReportCommand::report_ = nullptr;
double ReportCommand::report_seconds_ = 0.0;

// 3 channels' response curves and their harmonics 2 and 3, backbone, damping,
// 2 levels' time histories, residual map.
constexpr int kPlots = 11;

TEST_F(ReportCommand, WritesOneSelfContainedPageWithEveryPlot) {
  ASSERT_EQ(simulate_->exit_code, 0) << simulate_->output;
  ASSERT_EQ(identify_->exit_code, 0) << identify_->output;
  ASSERT_EQ(report_->exit_code, 0) << report_->output;
  std::cout << "report: " << report_seconds_ << " s, "
            << fs::file_size(*folder_ / "report.html") / 1000 << " kB\n";
  const std::string html = ReadFile(*folder_ / "report.html");
  EXPECT_EQ(Count(html, "<svg"), static_cast<std::size_t>(kPlots));
  // Nothing to run: the one script element is the JSON data block.
  EXPECT_EQ(Count(html, "<script"), 1u);
  EXPECT_THAT(html, HasSubstr("<script type=\"application/json\" id=\"beamid-report-data\">"));
  EXPECT_THAT(html, Not(HasSubstr("<link")));
  EXPECT_THAT(html, Not(HasSubstr("src=\"http")));
  EXPECT_THAT(html, Not(HasSubstr("href=\"http")));
  for (const char* id : {"frc-acc1", "frc-acc2", "frc-acc3", "harmonics-acc1", "harmonics-acc2", "harmonics-acc3",
                         "backbone-plot", "damping-plot", "time-low", "time-high", "residual-map"})
    EXPECT_THAT(html, HasSubstr(std::string("id=\"") + id + "\"")) << id;
  // Model curves, unstable dashed branch at the high level, parameters.
  EXPECT_THAT(html, HasSubstr("model high"));
  EXPECT_THAT(html, HasSubstr("stroke-dasharray"));
  for (const char* parameter : {"k1", "k2", "k3", "c"}) EXPECT_THAT(html, HasSubstr(std::string("<td>") + parameter + "</td>"));
  // identify refitted the beam's damping laws: their envelope is a column.
  EXPECT_THAT(html, HasSubstr("<th>total 95 % (damping laws, harmonic truncation)</th>"));
  EXPECT_THAT(html, HasSubstr("Held-out acc3"));
}

// A diagnosis (the documented fields of `beamid diagnose`) pointing at the
// result gets its own section above the result's.
// The measured phase resonance of every level, from the model-free analysis,
// beside the identified model's backbone: the model was fitted to these
// recordings, so its backbone passes within the points' stated uncertainty.
TEST_F(ReportCommand, SetsEachLevelsMeasuredPhaseResonanceBesideTheModelsBackbone) {
  ASSERT_EQ(report_->exit_code, 0) << report_->output;
  const std::string html = ReadFile(*folder_ / "report.html");
  const std::size_t table = html.find("<table class=\"resonance\">");
  ASSERT_NE(table, std::string::npos);
  std::vector<double> z;
  for (std::size_t at = html.find("<td class=\"z\">", table); at != std::string::npos && at < html.find("</table>", table);
       at = html.find("<td class=\"z\">", at + 1))
    z.push_back(std::stod(html.substr(at + std::string("<td class=\"z\">").size())));
  ASSERT_EQ(z.size(), 2u) << "one row per level";
  std::printf("measured phase resonance − model backbone: %+.2f σ (low), %+.2f σ (high)\n", z[0], z[1]);
  for (double value : z) EXPECT_LT(std::abs(value), 3.0);
}

TEST_F(ReportCommand, RendersADiagnosisSummary) {
  ASSERT_EQ(identify_->exit_code, 0) << identify_->output;
  // A diagnosis written through the one writer of its format, with texts
  // that can be found in the page.
  using namespace beamid::solver;
  const ResultFile result = ReadResultFile(*folder_ / "result.json");
  DiagnosisFile file;
  file.campaign_name = result.campaign.name;
  file.campaign_folder = result.campaign.absolute_folder;
  file.campaign_sha256 = result.campaign.sha256;
  file.result_file = "result.json";
  DiagnosisResult& d = file.diagnosis;
  d.selected = {"support_friction"};
  d.verdict = DiagnosisVerdict::kCauseNamed;
  d.summary = "SUMMARY-TEXT";
  d.base.chi_square = 5000;
  MisfitLocation location;
  location.findings = {"FINDING-TEXT"};
  MisfitGroupTest beyond, within;
  beyond.channel = "acc2", beyond.harmonic = 1, beyond.level = "high", beyond.part = ResidualPart::kQuadrature;
  beyond.chi2 = 812.0, beyond.significant = true;
  within.channel = "acc1", within.harmonic = 3, within.level = "low", within.chi2 = 3.1;
  location.groups = {beyond, within};
  d.location = location;
  CandidateOutcome friction, clamp;
  friction.name = "support_friction", friction.signature_score = 0.9, friction.status = RefitStatus::kRefitted;
  friction.extra_parameters = {"jenkins_stiffness"};
  friction.fit.parameters = {{.name = "jenkins_stiffness", .unit = "N*m/rad", .value = 49.9, .std = 0.1}};
  friction.fit.chi_square = 120, friction.residual_drop = 41.7, friction.p_value = 0, friction.significant = true;
  clamp.name = "clamp_compliance", clamp.signature_score = 0.1, clamp.status = RefitStatus::kRefitted, clamp.fit.chi_square = 4900;
  d.candidates = {friction, clamp};
  WriteDiagnosisFile(*folder_ / "diagnosis.json", file);
  const ProgramRun run = RunShell(std::string(BEAMID_EXECUTABLE) + " -q report " +
                                      (*folder_ / "diagnosis.json").string() + " -o " +
                                      (*folder_ / "diagnosis.html").string(),
                                  *folder_ / "diagnosis.log");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string html = ReadFile(*folder_ / "diagnosis.html");
  EXPECT_THAT(html, HasSubstr("<section id=\"diagnosis\">"));
  EXPECT_THAT(html, HasSubstr("SUMMARY-TEXT"));
  EXPECT_THAT(html, HasSubstr("<li>FINDING-TEXT</li>"));
  EXPECT_THAT(html, HasSubstr("Residual groups beyond the noise (1 of 2)"));
  EXPECT_THAT(html, HasSubstr("<td>support_friction</td>"));
  EXPECT_THAT(html, HasSubstr("<td>clamp_compliance</td>"));
  EXPECT_THAT(html, HasSubstr("jenkins_stiffness = 49.9"));
  EXPECT_LT(html.find("id=\"diagnosis\""), html.find("id=\"parameters\""));
  EXPECT_EQ(Count(html, "<svg"), static_cast<std::size_t>(kPlots));

  // A diagnosis of another campaign beside this result is refused, not mixed
  // into one page.
  file.campaign_name = "another campaign";
  file.campaign_sha256 = std::string(64, 'a');
  WriteDiagnosisFile(*folder_ / "other_diagnosis.json", file);
  const ProgramRun mixed = RunShell(std::string(BEAMID_EXECUTABLE) + " -q report " +
                                        (*folder_ / "other_diagnosis.json").string() + " -o " +
                                        (*folder_ / "mixed.html").string(),
                                    *folder_ / "mixed.log");
  EXPECT_EQ(mixed.exit_code, 2) << mixed.output;
  EXPECT_THAT(mixed.output, HasSubstr("other_diagnosis.json: is of campaign 'another campaign' (content SHA-256 "
                                      "aaaaaaaaaaaa…), not of the campaign of "));
  EXPECT_THAT(mixed.output, HasSubstr("result.json ('report test"));
  EXPECT_FALSE(fs::exists(*folder_ / "mixed.html"));
}

TEST_F(ReportCommand, ChromiumShowsThePlots) {
  const auto chromium = beamid::solver::FindChromium();
  if (!chromium) GTEST_SKIP() << "Chromium is not installed (scripts/install-deps.sh installs it)";
  ASSERT_EQ(report_->exit_code, 0) << report_->output;
  const fs::path png = *folder_ / "report.png";
  const ProgramRun shot = RunShell(std::string(BEAMID_EXECUTABLE) + " report " + (*folder_ / "result.json").string() +
                                       " -o " + (*folder_ / "report.html").string() + " --screenshot " + png.string(),
                                   *folder_ / "shot.log");
  ASSERT_EQ(shot.exit_code, 0) << shot.output;
  EXPECT_THAT(shot.output, HasSubstr("screenshot: " + png.string()));

  // Lay the page out in Chromium with a probe that reports where each plot
  // is and how many of its paths have a length.
  std::string html = ReadFile(*folder_ / "report.html");
  const std::string probe = R"(<pre id="probe"></pre><script>
const lines = [];
for (const f of document.querySelectorAll('figure.plot')) {
  const r = f.querySelector('svg').getBoundingClientRect();
  let drawn = 0;
  for (const p of f.querySelectorAll('svg path')) { if (p.getTotalLength() > 1) drawn++; }
  lines.push([f.id, Math.round(r.left), Math.round(r.top + window.scrollY), Math.round(r.width), Math.round(r.height), drawn].join(' '));
}
document.getElementById('probe').textContent = lines.join(';');
</script>)";
  html.insert(html.rfind("</body>"), probe);
  std::ofstream(*folder_ / "probe.html") << html;
  // The screenshot's width; its height is the page's own (the probe's window
  // height does not change the layout).
  const beamid::solver::ScreenshotOptions window{.height_px = 2000};
  const ProgramRun dom = RunShell("'" + chromium->string() +
                                 "' --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=" +
                                 std::to_string(window.width_px) + "," + std::to_string(window.height_px) +
                                 " --dump-dom 'file://" + (*folder_ / "probe.html").string() + "' 2>/dev/null",
                             *folder_ / "dom.log");
  const std::size_t begin = dom.output.find("<pre id=\"probe\">");
  ASSERT_NE(begin, std::string::npos) << dom.output.substr(0, 2000);
  std::stringstream probe_text(
      dom.output.substr(begin + 16, dom.output.find("</pre>", begin) - begin - 16));

  const beamid::testing::PngImage image = beamid::testing::ReadPng(png.string());
  EXPECT_EQ(image.width, window.width_px);
  int plots = 0;
  std::string entry;
  while (std::getline(probe_text, entry, ';')) {
    std::stringstream fields(entry);
    std::string id;
    int x = 0, y = 0, w = 0, h = 0, drawn = 0;
    fields >> id >> x >> y >> w >> h >> drawn;
    ++plots;
    EXPECT_GT(w, 300) << id;
    EXPECT_GT(h, 200) << id;
    EXPECT_GT(drawn, 5) << id << ": too few drawn paths";
    // Inside the screenshot, and not blank there: dark pixels (axes, text,
    // curves) and several colours.
    ASSERT_LE(y + h, image.height) << id << " lies below the screenshot";
    ASSERT_LE(x + w, image.width) << id;
    int dark = 0;
    std::set<int> colours;
    for (int j = y; j < y + h; ++j)
      for (int i = x; i < x + w; ++i) {
        const auto& p = image.At(i, j);
        if (p[0] + p[1] + p[2] < 3 * 160) ++dark;
        colours.insert((p[0] >> 4) << 8 | (p[1] >> 4) << 4 | (p[2] >> 4));
      }
    EXPECT_GT(dark, w * h / 200) << id << ": blank plot region in the screenshot";
    EXPECT_GE(colours.size(), 4u) << id;
  }
  EXPECT_EQ(plots, kPlots);
}

}  // namespace
