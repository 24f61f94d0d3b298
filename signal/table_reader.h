// The one reader of delimited text tables that beamid takes from acquisition
// systems: a step's recording (signal/recording.h) and a first-harmonic
// phasor table (signal/phasor_table.h) both go through it. It settles how the
// file is written and leaves what the columns mean to its callers:
//  - separator ',', ';' or tab, from the header line; decimal mark '.' or,
//    with ';' or tab, ',' (from the first data line that holds either);
//  - a UTF-8 BOM, LF, CRLF or CR line ends, comment lines (starting with
//    '#', '%' or '//'), blank lines at the end (inside the table only when
//    the caller allows them);
//  - header cells unquoted ("acc2") and split into a name and a bracketed
//    unit ("acc2 [g]", "acc2 (m/s²)"); a unit suffix ("acc2_g") needs the
//    caller's names and is split with SplitUnitSuffix;
//  - when the caller says so (TableLayout): a block of lines before the
//    header skipped whatever they hold (an export's metadata without '#'),
//    and a units row directly under the header ("s, N, g, g", "[s];[N]").
// Numbers are read with std::from_chars (an optional leading '+'); a cell
// that is none is reported with the convention detected, e.g. "the file uses
// ';' as separator and ',' as decimal mark: line 12, column acc2: 'abc' is not
// a number" (or "'1e400' is out of range"), quoting at most a short printable
// excerpt of the cell.
// What is no text table is refused at once, before anything is copied: a
// NUL byte (a binary or UTF-16 file, a file of zeros), a UTF-16 byte order
// mark, a header beyond 1 MiB or 10000 columns. The reader keeps views into
// the caller's text; its memory is the header's and one row's.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace beamid::signal {

struct TableFormat {
  char separator = ',';
  char decimal_mark = '.';
  // "the file uses ';' as separator and ',' as decimal mark"
  std::string Describe() const;
};

struct HeaderCell {
  std::string text;  // as written, without quotes and surrounding blanks
  std::string name;  // text without its bracketed unit
  std::string unit;  // the bracketed unit (or the units row's) as written, "" when none
  int unit_line = 0;  // the units row's line when the unit is the units row's, else 0
};

// How an export lays out what precedes its data, which the text alone cannot
// tell: a metadata block may hold separators and numbers, and a units row
// looks like a row of words.
struct TableLayout {
  int lines_before_header = 0;  // skipped whatever they hold
  bool units_row = false;       // the line under the header gives each column's unit
  // Where the layout was declared, for the fix of a file that breaks it
  // ("recording_layout in campaign.json").
  std::string declared_in;
};

// The unit spellings the readers accept, normalised to the campaign format's
// words (signal/quantity.h: N, V, mV, m/s^2, g, m/s, mm/s, m, mm) plus Hz,
// rad/s, rad, deg, s and ms; case is ignored ("m/s²", "M_S2", "ms-2" give
// "m/s^2"; "MV" is read as millivolts, no acquisition system drives megavolts).
// nullopt when unknown.
std::optional<std::string> NormaliseUnit(std::string_view spelling);

// "acc2_g" with name "acc2" gives "g" (the suffix as written) when the text is
// the name, an underscore and a known unit (NormaliseUnit); else nullopt.
std::optional<std::string> SplitUnitSuffix(std::string_view text, std::string_view name);

// How a number was printed: "0.0002" has 4 decimals and 1 significant
// digit, "1.50e-3" 5 decimals and 3 significant digits. Half a unit of its
// last digit is 0.5·10^-decimals.
struct PrintedPrecision {
  int decimals = 0;      // digits after the decimal mark minus the exponent
  int significant = 0;   // digits from the first non-zero one
};

class TableReader {
 public:
  struct Options {
    bool blank_lines_inside = false;  // else a blank line inside the table is an error
    TableLayout layout;
  };

  // Finds the header (the first line that is neither blank nor a comment) and
  // detects the format. `source` names the file in messages. Throws
  // InputError for what is no text table (see above), and for a file that
  // breaks its layout: fewer lines than the block before the header, a units
  // row missing, of another column count, or contradicting a unit in the header.
  TableReader(std::string_view text, std::string source, Options options);

  bool HasHeader() const { return has_header_; }
  const TableFormat& Format() const { return format_; }
  const std::vector<HeaderCell>& Header() const { return header_; }
  int HeaderLine() const { return header_line_; }
  const std::string& Source() const { return source_; }

  // The number of data rows left at most (lines that are neither blank nor
  // comments), counted without storing anything: what a caller may reserve.
  std::size_t CountRows() const;

  // Moves to the next data row; false at the end of the table. Throws
  // InputError for a blank line inside the table unless allowed.
  bool NextRow();
  int Line() const { return line_; }  // file line of the current row (1-based)
  const std::vector<std::string_view>& Cells() const { return cells_; }

  // Cell `cell` of the current row as a number in the file's convention;
  // false when it is none. precision, when given, receives how it was printed.
  bool Number(std::size_t cell, double& value, PrintedPrecision* precision = nullptr) const;
  // The cell as written (blanks and quotes removed), for messages.
  std::string_view CellText(std::size_t cell) const;
  // "<format>: line 12, column acc2: 'abc' is not a number", or "... '1e400'
  // is out of range ..." for a number beyond a double's range.
  std::string NotANumber(std::size_t cell, std::string_view column) const;

 private:
  void SplitCells(std::string_view line, std::vector<std::string_view>& cells) const;
  void DetectDecimalMark(std::string_view rest);
  void SkipLinesBeforeHeader();
  void ReadUnitsRow();
  bool NextContentLine(std::string_view& line, bool& blank);

  std::string_view text_;
  std::string source_;
  Options options_;
  TableFormat format_;
  std::vector<HeaderCell> header_;
  bool has_header_ = false;
  int header_line_ = 0;
  int line_ = 0;
  std::vector<std::string_view> cells_;
};

}  // namespace beamid::signal
