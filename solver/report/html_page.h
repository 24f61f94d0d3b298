// The opening of every HTML page beamid writes (the identification report
// and the measured-backbone report): doctype, title, one style sheet, the
// heading. One style, so the two reports look alike and a change reaches both.
#pragma once

#include <string>

namespace beamid::solver {

// Up to and including <body><h1>title</h1>; the title is escaped.
std::string HtmlPageHead(const std::string& title);

// `html` with every <table> inside a <div class="table">, which scrolls
// sideways when the table cannot shrink to the page's width (the table
// itself keeps the automatic layout that wraps its long cells first).
std::string ScrollableTables(std::string html);

}  // namespace beamid::solver
