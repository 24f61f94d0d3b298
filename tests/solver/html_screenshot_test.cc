// The page Chromium is given for a screenshot (FileUrl,
// solver/report/html_screenshot.h): every character of a path that a URL
// would read as something else is percent-encoded, so the URL names that
// very file.
#include "solver/report/html_screenshot.h"

#include <gtest/gtest.h>

namespace {

using beamid::solver::FileUrl;

TEST(FileUrl, PercentEncodesWhatAUrlWouldReadAsSyntax) {
  EXPECT_EQ(FileUrl("/tmp/report.html"), "file:///tmp/report.html");
  EXPECT_EQ(FileUrl("/tmp/a b/it's \"x\"#1?q=2%20&y;$(z)`w`.html"),
            "file:///tmp/a%20b/it%27s%20%22x%22%231%3Fq%3D2%2520%26y%3B%24%28z%29%60w%60.html");
  EXPECT_EQ(FileUrl("/tmp/é/x\ny.html"), "file:///tmp/%C3%A9/x%0Ay.html");
  EXPECT_EQ(FileUrl("/tmp/./a/../b_c-d~e.html"), "file:///tmp/b_c-d~e.html");
}

TEST(FileUrl, ARelativePathBecomesAbsolute) {
  const std::string url = FileUrl("report.html");
  ASSERT_EQ(url.rfind("file:///", 0), 0u) << url;
  EXPECT_EQ(url.substr(url.size() - 12), "/report.html");
}

}  // namespace
