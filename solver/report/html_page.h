// The opening of every HTML page beamid writes (the identification report
// and the measured-backbone report): doctype, title, one style sheet, the
// heading. One style, so the two reports look alike and a change reaches both.
#pragma once

#include <string>

namespace beamid::solver {

// Up to and including <body><h1>title</h1>; the title is escaped.
std::string HtmlPageHead(const std::string& title);

// One plot with its caption (HTML already): <figure class="plot CLASSES"
// id="ID">; the id, escaped here, also names the plot's files
// (solver/report/figure_files.h).
std::string PlotFigure(const std::string& id, const std::string& svg, const std::string& caption,
                       const std::string& more_classes = "");

// `html` with every <table> inside a <div class="table">, which scrolls
// sideways when the table cannot shrink to the page's width (the table
// itself keeps the automatic layout that wraps its long cells first).
std::string ScrollableTables(std::string html);

}  // namespace beamid::solver
