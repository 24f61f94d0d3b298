#include "solver/report/gnuplot_script.h"

#include <stdexcept>

#include <fmt/core.h>

namespace beamid::solver {

std::string GnuplotText(std::string_view text, GnuplotTextUse use) {
  std::string out = "'";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7F) {
      out += '?';
    } else if (c == '\'') {
      out += "''";  // the only escape inside gnuplot's single quotes
    } else if (c == '\\' || c == '_' || c == '^' || c == '@' || c == '&' || c == '~' || c == '{' || c == '}') {
      // Enhanced text reads "\x" as a literal x (one backslash: single quotes
      // keep it as written).
      out += '\\';
      out += c;
    } else if (c == '%' && use == GnuplotTextUse::kTicLabel) {
      out += "%%";
    } else {
      out += c;
    }
  }
  return out + "'";
}

std::string Datablock(const std::string& name, const std::vector<std::vector<double>>& rows) {
  if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") !=
                          std::string::npos)
    throw std::logic_error("datablock name '" + name + "' is not a gnuplot identifier");
  std::string out = "$" + name + " << EOD\n";
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) out += fmt::format("{}{:.9g}", i ? " " : "", row[i]);
    out += '\n';
  }
  // A datablock without a single point makes gnuplot fail: give one that
  // plots nothing.
  if (rows.empty()) out += "NaN NaN\n";
  return out + "EOD\n";
}

}  // namespace beamid::solver
