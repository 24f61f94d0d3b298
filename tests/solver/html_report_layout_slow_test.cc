// The report page as headless Chromium lays it out: at 900 and 1400 px it
// never scrolls sideways — wide tables (a diagnosis with every candidate),
// a long path in the header and every plot stay in the window — and the
// screenshot of `beamid report --screenshot` is as tall as the page, down to
// and including its last section (the residual map), which is drawn there.
// Chromium is run without a shell (solver/report/external_program.h), on
// the page with a layout probe of beamid's own (MeasurePage). Skipped only
// when Chromium is absent (scripts/install-deps.sh installs it).
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "solver/report/html_report.h"
#include "solver/report/html_screenshot.h"
#include "tests/support/png_image.h"
#include "tests/support/sample_report.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

namespace fs = std::filesystem;

class HtmlReportLayout : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new fs::path(beamid::testing::UniqueTempPath("beamid_report_layout"));
    fs::create_directories(*folder_);
    ReportInput input = beamid::testing::SampleReportInput();
    // A path with no place to break, as a deep campaign folder has.
    input.result_file = "/data/" + std::string(160, 'x') + "/result.json";
    DiagnosisResult d;
    d.verdict = DiagnosisVerdict::kNoSignificantDiscrepancy;
    d.selected = {"none"};
    d.base.chi_square = 26.9436;
    for (const char* name : {"sensor_position(acc2)", "modulus_error", "sensor_phase_delay(acc2)", "clamp_compliance",
                             "support_friction_with_a_rather_long_candidate_name"}) {
      CandidateOutcome c{.name = name,
                         .signature_score = 0.123456,
                         .status = RefitStatus::kRefitted,
                         .p_value = 0.355784,
                         .residual_drop = 1.03268};
      c.fit.chi_square = 26.0909;
      c.extra_parameters = {"extra_parameter_with_a_long_name"};
      c.fit.parameters = {
          {.name = "extra_parameter_with_a_long_name", .unit = "N*m*s/rad", .value = 0.0123456, .std = 0.00021}};
      d.candidates.push_back(c);
    }
    input.diagnosis = DiagnosisFile{.diagnosis = d};
    page_ = new fs::path(*folder_ / "report.html");
    std::ofstream(*page_) << HtmlReport(input, beamid::testing::SampleReportCurves());
  }
  static void TearDownTestSuite() {
    fs::remove_all(*folder_);
    delete folder_;
    delete page_;
  }
  void SetUp() override {
    if (!FindChromium()) GTEST_SKIP() << "Chromium is not installed (scripts/install-deps.sh installs it)";
  }

  static fs::path* folder_;
  static fs::path* page_;
};

fs::path* HtmlReportLayout::folder_ = nullptr;
fs::path* HtmlReportLayout::page_ = nullptr;

TEST_F(HtmlReportLayout, NeverScrollsSidewaysAt900Or1400Px) {
  for (const int width : {900, 1400}) {
    const PageLayout layout = MeasurePage(*page_, width);
    EXPECT_EQ(layout.client_width, width);
    EXPECT_LE(layout.scroll_width, layout.client_width) << "at " << width << " px the page scrolls sideways";
    EXPECT_GT(layout.scroll_height, 2000) << "the whole report laid out";
  }
}

TEST_F(HtmlReportLayout, TheScreenshotCoversThePageDownToItsLastSection) {
  const fs::path png = *folder_ / "report.png";
  ScreenshotHtml(*page_, png, {.width_px = 900});
  const PageLayout layout = MeasurePage(*page_, 900);
  const beamid::testing::PngImage image = beamid::testing::ReadPng(png.string());
  std::printf("page at 900 px: %d px tall, last section ends at %d px; screenshot %d x %d\n", layout.scroll_height,
              layout.last_section_bottom, image.width, image.height);
  EXPECT_EQ(image.width, 900);
  ASSERT_GT(layout.last_section_bottom, 0);
  EXPECT_GE(image.height, layout.last_section_bottom);
  EXPECT_LE(image.height, layout.scroll_height + 1) << "no more than the page";
  // The last section (the residual map) is drawn there: in its last 300 px
  // dark pixels (text, axes) and coloured ones (the map's cells).
  int dark = 0, coloured = 0;
  for (int y = layout.last_section_bottom - 300; y < layout.last_section_bottom; ++y)
    for (int x = 0; x < image.width; ++x) {
      const auto& p = image.At(x, y);
      if (p[0] + p[1] + p[2] < 3 * 120) ++dark;
      if (std::abs(p[0] - p[2]) > 60) ++coloured;
    }
  EXPECT_GT(dark, 500);
  EXPECT_GT(coloured, 500);
}

}  // namespace
}  // namespace beamid::solver
