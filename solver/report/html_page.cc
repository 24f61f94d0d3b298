#include "solver/report/html_page.h"

#include <fmt/core.h>

#include "solver/report/html_escape.h"

namespace beamid::solver {
namespace {

// Readable from a 900 px window up: the text column is at most 1000 px wide,
// a plot scales down to the column (its SVG keeps its aspect), a table wider
// than the column scrolls inside its own box, and a long path or name in the
// text wraps instead of widening the page.
constexpr const char* kStyle = R"(
*, *::before, *::after { box-sizing: border-box; }
body { font-family: Helvetica, Arial, sans-serif; margin: 1em auto; padding: 0 1em; max-width: 1000px; color: #222; line-height: 1.35; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; padding-bottom: 0.2em; margin-top: 1.6em; }
p, li, dd, dt, figcaption, h1, h2, h3, code { overflow-wrap: anywhere; }
div.table { max-width: 100%; overflow-x: auto; margin: 0.8em 0; }
table { border-collapse: collapse; }
td, th { border: 1px solid #ccc; padding: 0.3em 0.6em; text-align: right; vertical-align: top; }
th { background: #f3f3f3; } td:first-child { text-align: left; }
figure.plot { display: block; margin: 1em 0; max-width: 100%; }
figure.plot svg { display: block; width: 100%; max-width: 900px; height: auto; }
figcaption { font-size: 0.9em; color: #555; max-width: 900px; }
dl { display: grid; grid-template-columns: max-content auto; gap: 0.2em 1em; } dt { font-weight: bold; }
.flag, .warning { color: #a50f15; }
)";

}  // namespace

std::string ScrollableTables(std::string html) {
  for (std::size_t at = 0; (at = html.find("<table", at)) != std::string::npos; at += 24)
    html.insert(at, "<div class=\"table\">");
  for (std::size_t at = 0; (at = html.find("</table>", at)) != std::string::npos; at += 14)
    html.insert(at + 8, "</div>");
  return html;
}

std::string HtmlPageHead(const std::string& title) {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + HtmlEscape(title) +
         "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n<h1>" + HtmlEscape(title) + "</h1>\n";
}

std::string PlotFigure(const std::string& id, const std::string& svg, const std::string& caption,
                       const std::string& more_classes) {
  return fmt::format("<figure class=\"plot{}\" id=\"{}\">\n{}\n<figcaption>{}</figcaption>\n</figure>\n",
                     more_classes.empty() ? "" : " " + more_classes, HtmlEscape(id), svg, caption);
}

}  // namespace beamid::solver
