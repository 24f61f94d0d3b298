#include "signal/table_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstring>

#include "signal/input_error.h"
#include "signal/internal/text.h"

namespace beamid::signal {
namespace {

using internal::Excerpt;

// A header longer than this, or with more columns, is no acquisition
// system's: a file without line ends (one line of every value), a binary
// file or a damaged one. Refusing it before its cells are copied keeps the
// memory to the file's own.
constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;
constexpr std::size_t kMaxColumns = 10000;

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string_view Trim(std::string_view s) {
  while (!s.empty() && IsBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
  return s;
}

// Blanks, then one pair of surrounding quotes.
std::string_view Unquote(std::string_view s) {
  s = Trim(s);
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front())
    s = Trim(s.substr(1, s.size() - 2));
  return s;
}

// A line ends at LF, CRLF or a CR alone (the "CSV (Macintosh)" export of
// spreadsheets): a file of CR line ends is otherwise one line of every value.
std::string_view NextLine(std::string_view& text) {
  const std::size_t end = text.find_first_of("\r\n");
  if (end == std::string_view::npos) {
    const std::string_view line = text;
    text = {};
    return line;
  }
  const std::string_view line = text.substr(0, end);
  text.remove_prefix(end + (text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n' ? 2 : 1));
  return line;
}

bool IsComment(std::string_view trimmed) {
  return trimmed.starts_with('#') || trimmed.starts_with('%') || trimmed.starts_with("//");
}

// True when nothing but blank and comment lines is left.
bool OnlyBlankOrComments(std::string_view text) {
  while (!text.empty()) {
    const std::string_view line = Trim(NextLine(text));
    if (!line.empty() && !IsComment(line)) return false;
  }
  return true;
}

std::string SeparatorName(char c) { return c == '\t' ? "tab" : std::string("'") + c + "'"; }

}  // namespace

std::string TableFormat::Describe() const {
  return "the file uses " + SeparatorName(separator) + " as separator and '" + std::string(1, decimal_mark) +
         "' as decimal mark";
}

std::optional<std::string> NormaliseUnit(std::string_view spelling) {
  static const std::array<std::pair<std::string_view, std::string_view>, 44> kSpellings = {{
      {"hz", "Hz"},       {"1/s", "Hz"},       {"rad/s", "rad/s"},  {"rad_s", "rad/s"},  {"n", "N"},
      {"m/s^2", "m/s^2"}, {"m/s2", "m/s^2"},   {"m/s²", "m/s^2"},   {"m_s2", "m/s^2"},   {"m_s^2", "m/s^2"},
      {"ms-2", "m/s^2"},  {"m/s/s", "m/s^2"},  {"ms^-2", "m/s^2"},  {"m s^-2", "m/s^2"}, {"g", "g"},
      {"m/s", "m/s"},     {"m_s", "m/s"},      {"ms-1", "m/s"},     {"mm/s", "mm/s"},    {"mm_s", "mm/s"},
      {"m", "m"},         {"mm", "mm"},        {"rad", "rad"},      {"deg", "deg"},      {"degree", "deg"},
      {"degrees", "deg"}, {"°", "deg"},        {"radian", "rad"},   {"s", "s"},          {"sec", "s"},
      {"second", "s"},    {"seconds", "s"},    {"ms", "ms"},        {"msec", "ms"},      {"millisecond", "ms"},
      {"milliseconds", "ms"}, {"m/s^-2", "m/s^2"}, {"newton", "N"},
      {"v", "V"},         {"volt", "V"},       {"volts", "V"},      {"mv", "mV"},        {"millivolt", "mV"},
      {"millivolts", "mV"},
  }};
  const std::string key = internal::Lowercase(Unquote(spelling));
  for (const auto& [s, unit] : kSpellings)
    if (key == s) return std::string(unit);
  return std::nullopt;
}

std::optional<std::string> SplitUnitSuffix(std::string_view text, std::string_view name) {
  if (name.empty() || text.size() <= name.size() + 1 || !text.starts_with(name) || text[name.size()] != '_')
    return std::nullopt;
  const std::string_view suffix = text.substr(name.size() + 1);
  if (!NormaliseUnit(suffix)) return std::nullopt;
  return std::string(suffix);
}

TableReader::TableReader(std::string_view text, std::string source, Options options)
    : text_(text), source_(std::move(source)), options_(options) {
  if (text_.starts_with("\xFF\xFE") || text_.starts_with("\xFE\xFF"))
    throw InputError(source_, "", "the file is UTF-16 text (it begins with a UTF-16 byte order mark)",
                     "save or export it as UTF-8 (or ASCII) text");
  if (const void* nul = std::memchr(text_.data(), '\0', text_.size())) {
    const auto at = static_cast<std::size_t>(static_cast<const char*>(nul) - text_.data());
    const auto line = std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(at), '\n') + 1;
    throw InputError(source_, "",
                     "byte " + std::to_string(at + 1) + " (line " + std::to_string(line) +
                         ") is a NUL: the file is binary or UTF-16, not a text table",
                     "give the table as exported text, in UTF-8 or ASCII (a file of NUL bytes is an unfinished "
                     "copy or a damaged disk)");
  }
  if (text_.size() >= 3 && std::memcmp(text_.data(), "\xEF\xBB\xBF", 3) == 0) text_.remove_prefix(3);
  SkipLinesBeforeHeader();
  std::string_view header;
  while (!text_.empty()) {
    const std::string_view line = NextLine(text_);
    ++line_;
    const std::string_view trimmed = Trim(line);
    if (trimmed.empty() || IsComment(trimmed)) continue;
    header = line;
    has_header_ = true;
    break;
  }
  if (!has_header_) {
    if (options_.layout.lines_before_header > 0)
      throw InputError(source_, "",
                       "no header follows the " + std::to_string(options_.layout.lines_before_header) +
                           " lines skipped before it (the file has " + std::to_string(line_) + " lines)",
                       "give the recording with its header, or correct lines_before_header in " +
                           options_.layout.declared_in);
    return;
  }
  header_line_ = line_;
  if (header.size() > kMaxHeaderBytes)
    throw InputError(source_, "",
                     "the header (line " + std::to_string(line_) + ") is " + std::to_string(header.size()) +
                         " bytes long, beyond any table's header; it begins '" + Excerpt(header) + "'",
                     "give a table whose first line names the columns and whose lines end with LF, CRLF or CR");
  format_.separator = header.find(';') != std::string_view::npos    ? ';'
                      : header.find('\t') != std::string_view::npos ? '\t'
                                                                    : ',';
  if (const auto columns = static_cast<std::size_t>(std::count(header.begin(), header.end(), format_.separator)) + 1;
      columns > kMaxColumns)
    throw InputError(source_, "",
                     "the header (line " + std::to_string(line_) + ") has " + std::to_string(columns) +
                         " columns, more than the " + std::to_string(kMaxColumns) + " a table may have",
                     "give a table whose first line names the columns and whose lines end with LF, CRLF or CR");
  std::vector<std::string_view> cells;
  SplitCells(header, cells);
  for (const std::string_view cell : cells) {
    HeaderCell h;
    h.text = std::string(Unquote(cell));
    h.name = h.text;
    for (const auto& [open, close] : {std::pair{'[', ']'}, std::pair{'(', ')'}}) {
      const auto a = h.text.find(open), b = h.text.rfind(close);
      if (a != std::string::npos && b != std::string::npos && b > a) {
        h.name = std::string(Unquote(std::string_view(h.text).substr(0, a)));
        h.unit = std::string(Trim(std::string_view(h.text).substr(a + 1, b - a - 1)));
        break;
      }
    }
    header_.push_back(std::move(h));
  }
  if (options_.layout.units_row) ReadUnitsRow();
  DetectDecimalMark(text_);
}

void TableReader::SkipLinesBeforeHeader() {
  const int skip = options_.layout.lines_before_header;
  for (int skipped = 0; skipped < skip; ++skipped) {
    if (text_.empty())
      throw InputError(source_, "",
                       "the file has " + std::to_string(skipped) + " lines, fewer than the " + std::to_string(skip) +
                           " lines before the header that the layout skips",
                       "give the whole export, or correct lines_before_header in " + options_.layout.declared_in +
                           " (the number of lines above the header line)");
    NextLine(text_);
    ++line_;
  }
}

namespace {

// "[g]" and "(g)" as "g": some exports bracket the units of their units row.
std::string_view Unbracketed(std::string_view unit) {
  if (unit.size() >= 2 && ((unit.front() == '[' && unit.back() == ']') || (unit.front() == '(' && unit.back() == ')')))
    return Trim(unit.substr(1, unit.size() - 2));
  return unit;
}

}  // namespace

void TableReader::ReadUnitsRow() {
  const std::string where = "the units row (line " + std::to_string(line_ + 1) + ", under the header)";
  const std::string fix = "give each column's unit on the line directly under the header (a blank cell for a column "
                          "without one), or correct units_row in " + options_.layout.declared_in;
  if (text_.empty()) throw InputError(source_, "", where + " is missing: the file ends after the header", fix);
  const std::string_view line = NextLine(text_);
  ++line_;
  const std::string_view trimmed = Trim(line);
  if (trimmed.empty() || IsComment(trimmed))
    throw InputError(source_, "", where + " is " + (trimmed.empty() ? "blank" : "a comment"), fix);
  std::vector<std::string_view> cells;
  SplitCells(line, cells);
  if (cells.size() != header_.size())
    throw InputError(source_, "",
                     where + " has " + std::to_string(cells.size()) + " cells, the header " +
                         std::to_string(header_.size()) + " (" + format_.Describe() + ")",
                     fix);
  bool all_numbers = true;
  for (const std::string_view cell : cells) {
    double value = 0.0;
    const std::string_view unit = Unquote(cell);
    all_numbers = all_numbers && (unit.empty() || std::from_chars(unit.data(), unit.data() + unit.size(), value).ec ==
                                                      std::errc());
  }
  if (all_numbers)
    throw InputError(source_, "", where + " holds numbers ('" + Excerpt(trimmed) + "'): it is a row of data", fix);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::string unit(Unbracketed(Unquote(cells[i])));
    HeaderCell& cell = header_[i];
    if (unit.empty()) continue;
    if (!cell.unit.empty()) {
      const auto header_unit = NormaliseUnit(cell.unit), row_unit = NormaliseUnit(unit);
      if (!header_unit && row_unit) {
        // Parentheses that hold no unit belong to the name: "Laser (M - Filtered)" over "m/s".
        cell.name = cell.text;
        cell.unit = unit;
        cell.unit_line = line_;
        continue;
      }
      if (header_unit ? header_unit != row_unit : cell.unit != unit)
        throw InputError(source_, Excerpt(cell.text),
                         "the header gives the unit '" + Excerpt(cell.unit) + "' but " + where + " gives '" +
                             Excerpt(unit) + "'",
                         "give the unit once, in the header or in the units row, or make them agree");
      continue;
    }
    cell.unit = unit;
    cell.unit_line = line_;
  }
}

std::size_t TableReader::CountRows() const {
  std::size_t rows = 0;
  for (std::string_view rest = text_; !rest.empty();) {
    const std::string_view trimmed = Trim(NextLine(rest));
    if (!trimmed.empty() && !IsComment(trimmed)) ++rows;
  }
  return rows;
}

void TableReader::DetectDecimalMark(std::string_view rest) {
  if (format_.separator == ',') return;
  std::vector<std::string_view> cells;
  for (int lines = 0; lines < 1000 && !rest.empty(); ++lines) {
    const std::string_view line = NextLine(rest);
    const std::string_view trimmed = Trim(line);
    if (trimmed.empty() || IsComment(trimmed)) continue;
    SplitCells(line, cells);
    bool point = false;
    for (const std::string_view cell : cells) {
      if (cell.find(',') != std::string_view::npos) {
        format_.decimal_mark = ',';
        return;
      }
      point = point || cell.find('.') != std::string_view::npos;
    }
    if (point) return;
  }
}

void TableReader::SplitCells(std::string_view line, std::vector<std::string_view>& cells) const {
  cells.clear();
  while (true) {
    const std::size_t end = line.find(format_.separator);
    cells.push_back(line.substr(0, end));
    if (end == std::string_view::npos) break;
    line.remove_prefix(end + 1);
  }
}

bool TableReader::NextRow() {
  while (!text_.empty()) {
    const std::string_view line = NextLine(text_);
    ++line_;
    const std::string_view trimmed = Trim(line);
    if (!trimmed.empty() && IsComment(trimmed)) continue;
    if (trimmed.empty()) {
      if (options_.blank_lines_inside) continue;
      if (OnlyBlankOrComments(text_)) break;  // trailing blank lines are harmless
      throw InputError(source_, "", "line " + std::to_string(line_) + " is empty", "remove the blank line");
    }
    SplitCells(line, cells_);
    return true;
  }
  text_ = {};
  cells_.clear();
  return false;
}

std::string_view TableReader::CellText(std::size_t cell) const { return Unquote(cells_.at(cell)); }

namespace {

// The cell as a number: std::errc() when it is one, result_out_of_range when
// it is one beyond a double's range ("1e400"), invalid_argument else.
// `token` is left as parsed ('+' removed, a decimal comma made a point, in
// `buffer`).
std::errc ParseNumber(std::string_view& token, char decimal_mark, char (&buffer)[64], double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::errc::invalid_argument;
  if (decimal_mark == ',') {
    if (token.size() >= sizeof buffer || token.find('.') != std::string_view::npos) return std::errc::invalid_argument;
    std::memcpy(buffer, token.data(), token.size());
    std::replace(buffer, buffer + token.size(), ',', '.');
    token = std::string_view(buffer, token.size());
  }
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (end != token.data() + token.size()) return std::errc::invalid_argument;
  return error;
}

}  // namespace

bool TableReader::Number(std::size_t cell, double& value, PrintedPrecision* precision) const {
  std::string_view token = Unquote(cells_[cell]);
  char buffer[64];
  if (ParseNumber(token, format_.decimal_mark, buffer, value) != std::errc()) return false;
  if (precision != nullptr) {
    int after = 0, significant = 0, exponent = 0;
    bool in_fraction = false, leading = true;
    std::size_t i = 0;
    if (i < token.size() && token[i] == '-') ++i;
    for (; i < token.size(); ++i) {
      const char c = token[i];
      if (c == '.') {
        in_fraction = true;
      } else if (c >= '0' && c <= '9') {
        if (in_fraction) ++after;
        if (c != '0') leading = false;
        if (!leading) ++significant;
      } else {
        if (c == 'e' || c == 'E') std::from_chars(token.data() + i + 1 + (token[i + 1] == '+' ? 1 : 0),
                                                  token.data() + token.size(), exponent);
        break;
      }
    }
    *precision = {.decimals = after - exponent, .significant = significant};
  }
  return true;
}

std::string TableReader::NotANumber(std::size_t cell, std::string_view column) const {
  std::string_view token = CellText(cell);
  char buffer[64];
  double value = 0.0;
  const bool out_of_range =
      ParseNumber(token, format_.decimal_mark, buffer, value) == std::errc::result_out_of_range;
  return format_.Describe() + ": line " + std::to_string(line_) + ", column " + Excerpt(column, 60) + ": '" +
         Excerpt(CellText(cell)) + "' " +
         (out_of_range ? "is out of range (a number's magnitude must lie between 1e-308 and 1e308)"
                       : "is not a number");
}

}  // namespace beamid::signal
