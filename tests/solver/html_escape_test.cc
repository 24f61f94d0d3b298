// Hostile labels, channel and campaign names stay text in the report.
#include "solver/report/html_escape.h"

#include <gtest/gtest.h>

namespace beamid::solver {
namespace {

TEST(HtmlEscape, HostileTextCannotLeaveAnAttributeOrOpenAnElement) {
  for (const std::string hostile : {"low\" onmouseover=\"alert(1)", "low' onmouseover='alert(1)",
                                    "</figure><script>alert(1)</script>", "acc&1 <b>"}) {
    const std::string escaped = HtmlEscape(hostile);
    EXPECT_EQ(escaped.find('"'), std::string::npos) << escaped;
    EXPECT_EQ(escaped.find('\''), std::string::npos) << escaped;
    EXPECT_EQ(escaped.find('<'), std::string::npos) << escaped;
    EXPECT_EQ(escaped.find('>'), std::string::npos) << escaped;
  }
  EXPECT_EQ(HtmlEscape("low\" x='1' & <b>"), "low&quot; x=&#39;1&#39; &amp; &lt;b&gt;");
  EXPECT_EQ(HtmlEscape("acc1 (m/s²), level high_2"), "acc1 (m/s²), level high_2");
}

}  // namespace
}  // namespace beamid::solver
