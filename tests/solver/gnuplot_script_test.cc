// The one way a text of the user's reaches a gnuplot script (GnuplotText,
// solver/report/gnuplot_script.h): quotes, backslashes, line breaks and
// enhanced-text markup come out as a single-quoted string that gnuplot shows
// exactly as written, and never as a command; checked on the string and on
// what gnuplot draws from it.
#include "solver/report/gnuplot_script.h"

#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solver/report/gnuplot_svg.h"
#include "tests/support/temp_path.h"

namespace {

namespace fs = std::filesystem;
using beamid::solver::Datablock;
using beamid::solver::GnuplotSvg;
using beamid::solver::GnuplotText;
using beamid::solver::GnuplotTextUse;
using ::testing::HasSubstr;

TEST(GnuplotText, DoublesQuotesAndEscapesBackslashesAndMarkup) {
  EXPECT_EQ(GnuplotText("acc1"), "'acc1'");
  EXPECT_EQ(GnuplotText("it's"), "'it''s'");
  EXPECT_EQ(GnuplotText("a\\b"), "'a\\\\b'");
  EXPECT_EQ(GnuplotText("acc_2 x^2 @ & ~ {/Symbol z}"), "'acc\\_2 x\\^2 \\@ \\& \\~ \\{/Symbol z\\}'");
  EXPECT_EQ(GnuplotText("\"$(x)`y`"), "'\"$(x)`y`'");
  EXPECT_EQ(GnuplotText(""), "''");
  EXPECT_EQ(GnuplotText("ζ é"), "'ζ é'");  // UTF-8 passes
}

TEST(GnuplotText, ControlCharactersCannotEndTheCommand) {
  EXPECT_EQ(GnuplotText("a\nb\rc\td"), "'a?b?c?d'");
  EXPECT_EQ(GnuplotText(std::string("a\0b", 3)), "'a?b'");
  EXPECT_EQ(GnuplotText("a\x7f" "b\x1b"), "'a?b?'");
}

TEST(GnuplotText, PercentIsLiteralInTicLabels) {
  EXPECT_EQ(GnuplotText("50 %"), "'50 %'");
  EXPECT_EQ(GnuplotText("50 %s", GnuplotTextUse::kTicLabel), "'50 %%s'");
}

TEST(GnuplotText, TheResultIsOneSingleQuotedStringToken) {
  // Every quote inside is doubled, so the first lone quote is the last
  // character: nothing after the string can be read as gnuplot.
  for (const std::string text : {"x'", "'", "''", "a'.system('touch x').'", "'\n!touch x\n'", "\\'"}) {
    const std::string quoted = GnuplotText(text);
    ASSERT_GE(quoted.size(), 2u);
    EXPECT_EQ(quoted.front(), '\'');
    EXPECT_EQ(quoted.back(), '\'');
    std::size_t i = 1;
    while (i + 1 < quoted.size()) {
      if (quoted[i] == '\'') {
        ASSERT_EQ(quoted[i + 1], '\'') << quoted;
        i += 2;
      } else {
        EXPECT_NE(quoted[i], '\n');
        ++i;
      }
    }
    EXPECT_EQ(i, quoted.size() - 1) << quoted;
  }
}

TEST(Datablock, HoldsNumbersOnlyUnderABeamidName) {
  EXPECT_EQ(Datablock("d0", {{1.5, 2}, {}, {3, -4e-9}}), "$d0 << EOD\n1.5 2\n\n3 -4e-09\nEOD\n");
  EXPECT_EQ(Datablock("empty", {}), "$empty << EOD\nNaN NaN\nEOD\n");
  EXPECT_THROW(Datablock("a b", {}), std::logic_error);
  EXPECT_THROW(Datablock("x\nsystem", {}), std::logic_error);
  EXPECT_THROW(Datablock("", {}), std::logic_error);
}

// What gnuplot draws: the texts as written (in the SVG, as XML text), and no
// command run.
TEST(GnuplotText, GnuplotShowsTheTextAsWrittenAndRunsNothing) {
  const fs::path folder = beamid::testing::UniqueTempPath("beamid_gnuplot_text");
  fs::remove_all(folder);
  fs::create_directories(folder);
  const fs::path sentinel = folder / "SENTINEL";
  const std::string touch = "touch " + sentinel.string();
  const std::string title = "T acc_2^3 @x &{y} ~z {/Symbol a} back\\slash it's \"$(" + touch + ")\" `" + touch + "`";
  const std::string key = "low'.system('" + touch + "').'";
  const std::string tic = "r%s%d 100%";
  const std::string broken = "x'\n!" + touch + "\nset title 'y";
  const std::string svg = GnuplotSvg("set title " + GnuplotText(title) + "\nset xlabel " + GnuplotText(broken) +
                                     "\nset ytics (" + GnuplotText(tic, GnuplotTextUse::kTicLabel) + " 1)\n" +
                                     Datablock("d", {{0, 0}, {1, 2}}) + "plot $d title " + GnuplotText(key) + "\n");
  EXPECT_FALSE(fs::exists(sentinel));
  // Each text is drawn in one piece (markup would split it into tspans),
  // as XML text: gnuplot's SVG escapes & and <.
  const auto drawn = [](std::string text) {
    for (std::size_t at = 0; (at = text.find('&', at)) != std::string::npos; at += 5) text.replace(at, 1, "&amp;");
    return ">" + text + "</tspan></text>";
  };
  for (const std::string& text : {title, key, tic}) EXPECT_THAT(svg, HasSubstr(drawn(text))) << text;
  EXPECT_THAT(svg, HasSubstr(">x'?!" + touch + "?set title 'y</tspan></text>"));
  fs::remove_all(folder);
}

}  // namespace
