// The one escaping of every text the HTML report writes, in element content
// and in quoted attribute values alike: level labels, channel and campaign
// names and file paths are the user's, and unescaped they could end an
// attribute and add an event handler (`low" onmouseover="...`) or a script.
// & < > " ' become character references; nothing else changes.
#pragma once

#include <string>

namespace beamid::solver {

std::string HtmlEscape(const std::string& text);

}  // namespace beamid::solver
