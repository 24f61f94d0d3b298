// What beamid's data become in a gnuplot script: a text (a title, a legend
// key, a tic label holding a channel name or a level label from the user's
// files) as one quoted string that gnuplot shows exactly as written, and
// numbers as an inline datablock ("$name << EOD ... EOD"). Nothing else of
// the user's ever enters a script, so no label or path can become a gnuplot
// command (a shell escape, a "< command" pipe, `set output`).
#pragma once

#include <cstddef>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

namespace beamid::solver {

enum class GnuplotTextUse {
  kText,      // set title / xlabel / ylabel, plot ... title
  kTicLabel,  // set xtics ('label' position): gnuplot reads a % there as a number format
};

// A single-quoted gnuplot string showing `text` literally under enhanced
// text: a quote is doubled; a backslash and the markup characters _ ^ @ & ~
// { } are escaped with a backslash; a control character (< 0x20, 0x7F: a
// line break would end the command) becomes '?'; in a tic label, % becomes %%.
std::string GnuplotText(std::string_view text, GnuplotTextUse use = GnuplotTextUse::kText);

// A gnuplot datablock: "$name << EOD\n<rows>EOD\n" from rows of numbers; an
// empty row ends a line segment (gnuplot breaks lines at blank lines). The
// name is beamid's own: letters, digits and '_' (std::logic_error otherwise).
std::string Datablock(const std::string& name, const std::vector<std::vector<double>>& rows);

// The colour of the i-th series (a level, a channel) in every plot of a
// report, so that one level keeps its colour from figure to figure.
inline const char* SeriesColour(std::size_t i) {
  constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  return kColours[i % std::size(kColours)];
}

}  // namespace beamid::solver
