#include "solver/report/html_page.h"

#include "solver/report/html_escape.h"

namespace beamid::solver {
namespace {

constexpr const char* kStyle = R"(
body { font-family: Helvetica, Arial, sans-serif; margin: 2em auto; max-width: 1600px; color: #222; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; padding-bottom: 0.2em; margin-top: 1.6em; }
table { border-collapse: collapse; margin: 0.8em 0; } td, th { border: 1px solid #ccc; padding: 0.3em 0.7em; text-align: right; }
th { background: #f3f3f3; } td:first-child { text-align: left; }
figure.plot { display: inline-block; margin: 0.5em; vertical-align: top; }
figure.plot svg { display: block; }
figcaption { font-size: 0.9em; color: #555; max-width: 760px; }
dl { display: grid; grid-template-columns: max-content auto; gap: 0.2em 1em; } dt { font-weight: bold; }
.flag, .warning { color: #a50f15; }
)";

}  // namespace

std::string HtmlPageHead(const std::string& title) {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + HtmlEscape(title) +
         "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n<h1>" + HtmlEscape(title) + "</h1>\n";
}

}  // namespace beamid::solver
