#include "signal/uff58.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>

#include "hb/text_file.h"
#include "signal/input_error.h"
#include "signal/internal/text.h"

namespace beamid::signal {
namespace {

using internal::Excerpt;
using internal::FormatNumber;

using uff58::kComplexDouble;
using uff58::kComplexSingle;
using uff58::kRealDouble;
using uff58::kRealSingle;
constexpr int kNumHeaderRecords = 11;  // ID lines 1..5 and records 6..11
// The header records are 80 columns wide; a line far longer is no record
// (a file without line ends, a binary file) and is not copied.
constexpr std::size_t kMaxHeaderLineBytes = 4096;

std::string_view TrimView(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// Columns [first, first + width) of a fixed-format record (1-based first
// column as in the format statements), empty when the line is shorter.
std::string_view Columns(std::string_view line, std::size_t first, std::size_t width) {
  if (line.size() < first) return {};
  return line.substr(first - 1, width);
}

// A real number of a record: std::errc() when it is one, result_out_of_range
// when it is one beyond a double's range ("1e400"), invalid_argument else.
std::errc ParseReal(std::string_view token, double& value) {
  token = TrimView(token);
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  // No number is this long; a longer token is not copied.
  char text[80];
  if (token.empty() || token.size() > sizeof text) return std::errc::invalid_argument;
  std::memcpy(text, token.data(), token.size());
  // Fortran writers may use D as the exponent letter.
  std::replace(text, text + token.size(), 'D', 'E');
  std::replace(text, text + token.size(), 'd', 'e');
  const auto [end, error] = std::from_chars(text, text + token.size(), value);
  if (end != text + token.size()) return std::errc::invalid_argument;
  return error;
}

std::optional<double> ParseReal(std::string_view token) {
  double value = 0.0;
  if (ParseReal(token, value) != std::errc()) return std::nullopt;
  return value;
}

// "cannot read 'abc' as a number", "'1e400' is out of range ...".
std::string RealProblem(std::string_view token) {
  double value = 0.0;
  if (ParseReal(token, value) == std::errc::result_out_of_range)
    return "'" + Excerpt(TrimView(token)) + "' is out of range (a number's magnitude must lie between 1e-308 and "
           "1e308)";
  return "cannot read '" + Excerpt(TrimView(token)) + "' as a number";
}

std::optional<long long> ParseInteger(std::string_view token) {
  token = TrimView(token);
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  long long value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

// The next blank-separated token of `line` (consumed), empty at its end:
// the values of a line are read one by one, never all held.
std::string_view NextToken(std::string_view& line) {
  std::size_t i = 0;
  while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
  const std::size_t start = i;
  while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
  const std::string_view token = line.substr(start, i - start);
  line.remove_prefix(i);
  return token;
}

// The first `max` tokens of a header line.
std::vector<std::string_view> Tokens(std::string_view line, std::size_t max = 16) {
  std::vector<std::string_view> tokens;
  for (std::string_view token = NextToken(line); !token.empty() && tokens.size() < max; token = NextToken(line))
    tokens.push_back(token);
  return tokens;
}

std::string FunctionTypeName(int type) {
  switch (type) {
    case 0: return "general or unknown";
    case 1: return "time response";
    case 2: return "auto spectrum";
    case 3: return "cross spectrum";
    case 4: return "frequency response function";
    case 5: return "transmissibility";
    case 6: return "coherence";
    case 9: return "power spectral density";
    case 12: return "spectrum";
    default: return "type " + std::to_string(type);
  }
}

// Reads the file line by line and, for 58b, block by block, keeping the
// position for messages.
class Cursor {
 public:
  Cursor(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}

  bool AtEnd() const { return position_ >= bytes_.size(); }
  std::size_t Remaining() const { return bytes_.size() - position_; }
  int line_number() const { return line_number_; }

  // The next line without its end of line (\n or \r\n); nullopt at the end.
  std::optional<std::string_view> Line() {
    if (AtEnd()) return std::nullopt;
    const std::size_t end = bytes_.find('\n', position_);
    std::string_view line = bytes_.substr(position_, end == std::string_view::npos ? std::string_view::npos : end - position_);
    position_ = end == std::string_view::npos ? bytes_.size() : end + 1;
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }

  std::optional<std::string_view> Bytes(std::size_t count) {
    if (bytes_.size() - position_ < count) return std::nullopt;
    std::string_view block = bytes_.substr(position_, count);
    position_ += count;
    line_number_ += static_cast<int>(std::count(block.begin(), block.end(), '\n'));
    return block;
  }

  // Skips the end of line that some writers put after the binary block.
  void SkipLineEnd() {
    if (!AtEnd() && bytes_[position_] == '\r') ++position_;
    if (!AtEnd() && bytes_[position_] == '\n') {
      ++position_;
      ++line_number_;
    }
  }

  [[noreturn]] void Fail(const std::string& problem, const std::string& fix) const {
    throw InputError(source_, "", problem, fix);
  }

 private:
  std::string_view bytes_;
  const std::string& source_;
  std::size_t position_ = 0;
  int line_number_ = 0;
};

bool IsDelimiter(std::string_view line) { return TrimView(line) == "-1"; }

class DatasetReader {
 public:
  DatasetReader(Cursor& cursor, Uff58Dataset& dataset, Uff58Functions functions)
      : cursor_(cursor), dataset_(dataset), functions_(functions) {}

  [[noreturn]] void Fail(const std::string& problem, const std::string& fix) const {
    cursor_.Fail(dataset_.Describe() + ": " + problem + " (line " + std::to_string(cursor_.line_number()) + ")", fix);
  }

  std::string_view HeaderLine(const char* what) {
    auto line = cursor_.Line();
    if (!line || IsDelimiter(*line))
      Fail(std::string("the file ends inside the header, before ") + what,
           "export the dataset again: the file is truncated");
    if (line->size() > kMaxHeaderLineBytes)
      Fail("the line of " + std::string(what) + " is " + std::to_string(line->size()) +
               " bytes long, not a record of 80 columns; it begins '" + Excerpt(*line) + "'",
           "write the header records in the dataset 58 format (docs/uff58.md)");
    return *line;
  }

  int Integer(std::string_view field, const char* what) const {
    auto value = ParseInteger(field);
    if (!value) Fail(std::string("cannot read ") + what + " from '" + Excerpt(field) + "'",
                     "write the record in the dataset 58 format (docs/uff58.md)");
    if (*value < std::numeric_limits<int>::min() || *value > std::numeric_limits<int>::max())
      Fail(std::string(what) + " " + std::to_string(*value) + " is out of range",
           "write the record in the dataset 58 format (docs/uff58.md)");
    return static_cast<int>(*value);
  }

  void ReadHeader() {
    for (std::size_t i = 0; i < dataset_.id_lines.size(); ++i) {
      std::string_view line = HeaderLine("the five ID lines end");
      while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.remove_suffix(1);
      dataset_.id_lines[i] = std::string(line);
    }
    // Record 6: Format(2(I5,I10),2(1X,A10,I10,I4)).
    const std::string_view record6 = HeaderLine("record 6");
    dataset_.function_type = Integer(Columns(record6, 1, 5), "the function type (record 6, columns 1-5)");
    dataset_.response_entity = std::string(TrimView(Columns(record6, 32, 10)));
    const std::string_view node = TrimView(Columns(record6, 42, 10));
    const std::string_view direction = TrimView(Columns(record6, 52, 4));
    dataset_.response_node = node.empty() ? 0 : Integer(node, "the response node (record 6, columns 42-51)");
    dataset_.response_direction =
        direction.empty() ? 0 : Integer(direction, "the response direction (record 6, columns 52-55)");
    dataset_.reference_entity = std::string(TrimView(Columns(record6, 57, 10)));
    const std::string_view reference_node = TrimView(Columns(record6, 67, 10));
    const std::string_view reference_direction = TrimView(Columns(record6, 77, 4));
    dataset_.reference_node =
        reference_node.empty() ? 0 : Integer(reference_node, "the reference node (record 6, columns 67-76)");
    dataset_.reference_direction = reference_direction.empty()
                                       ? 0
                                       : Integer(reference_direction, "the reference direction (record 6, columns 77-80)");
    // Record 7: Format(3I10,3E13.5); read by fields so that wider numbers
    // (some writers give Δx with 12 digits) keep their precision.
    const std::string_view record7 = HeaderLine("record 7");
    const auto fields = Tokens(record7);
    if (fields.size() < 5)
      Fail("record 7 has " + std::to_string(fields.size()) + " fields, not the 6 of Format(3I10,3E13.5)",
           "write record 7 as: ordinate type, number of values, spacing, x_min, dx, z");
    dataset_.ordinate_type = Integer(fields[0], "the ordinate data type (record 7 field 1)");
    num_values_ = Integer(fields[1], "the number of values (record 7 field 2)");
    const int spacing = Integer(fields[2], "the abscissa spacing (record 7 field 3)");
    const auto start = ParseReal(fields[3]);
    const auto step = ParseReal(fields[4]);
    if (!start || !step)
      Fail("cannot read x_min and dx from record 7: " + RealProblem(start ? fields[4] : fields[3]),
           "write them as real numbers (E13.5)");
    dataset_.abscissa_start = *start;
    dataset_.abscissa_step = *step;
    dataset_.abscissa = Axis(HeaderLine("record 8"));
    dataset_.ordinate = Axis(HeaderLine("record 9"));
    dataset_.denominator = Axis(HeaderLine("record 10"));
    HeaderLine("record 11");
    dataset_.num_points = num_values_;
    dataset_.uneven = spacing == 0;
    if (functions_ == Uff58Functions::kFrequencyFunctions) {
      CheckFrequencyFunctionHeader(spacing);
      return;
    }

    if (dataset_.function_type != 0 && dataset_.function_type != 1)
      Fail("function type " + std::to_string(dataset_.function_type) + " (" +
               FunctionTypeName(dataset_.function_type) + ") is not a time history",
           "export the time histories (function type 1) of the recording");
    if (dataset_.ordinate_type != kRealSingle && dataset_.ordinate_type != kRealDouble)
      Fail("ordinate data type " + std::to_string(dataset_.ordinate_type) +
               (dataset_.ordinate_type == 5 || dataset_.ordinate_type == 6 ? " (complex)" : "") +
               " is not accepted",
           "export real values, in single (2) or double (4) precision");
    if (spacing != 1)
      Fail("the abscissa is unevenly spaced (record 7 field 3 = " + std::to_string(spacing) + ")",
           "export the recording at one uniform sample rate (even spacing, 1)");
    if (num_values_ < 2) Fail("the dataset holds " + std::to_string(num_values_) + " values", "record the whole step");
    if (!(dataset_.abscissa_step > 0.0) || !std::isfinite(dataset_.abscissa_step) ||
        !std::isfinite(dataset_.abscissa_start))
      Fail("the abscissa increment dx = " + FormatNumber(dataset_.abscissa_step) + " is not a positive time step",
           "write the sample interval in seconds in record 7 field 5");
  }

  // A spectrum or frequency response: real or complex ordinates, at even or
  // uneven frequencies (a stepped sine's steps need not be evenly spaced).
  void CheckFrequencyFunctionHeader(int spacing) {
    const int type = dataset_.ordinate_type;
    if (type != kRealSingle && type != kRealDouble && type != kComplexSingle && type != kComplexDouble)
      Fail("ordinate data type " + std::to_string(type) + " is not accepted",
           "export real (2, 4) or complex (5, 6) values in single or double precision");
    if (spacing != 0 && spacing != 1)
      Fail("the abscissa spacing (record 7 field 3) is " + std::to_string(spacing) + ", neither 1 (even) nor 0 (uneven)",
           "write record 7 in the dataset 58 format (docs/uff58.md)");
    if (num_values_ < 1) Fail("the dataset holds no value", "export the frequency steps");
    if (spacing == 1 && (!(dataset_.abscissa_step > 0.0) || !std::isfinite(dataset_.abscissa_step) ||
                         !std::isfinite(dataset_.abscissa_start)))
      Fail("the abscissa increment dx = " + FormatNumber(dataset_.abscissa_step) + " is not a positive frequency step",
           "write the frequency increment in record 7 field 5, or export the steps unevenly spaced (0)");
  }

  // The numbers record 12 holds: per point its abscissa when uneven, and one
  // real or two (real, imaginary) ordinate numbers.
  std::size_t NumbersToRead() const {
    return static_cast<std::size_t>(num_values_) * ((dataset_.Complex() ? 2 : 1) + (dataset_.uneven ? 1 : 0));
  }

  // ASCII values: any number per line, separated by blanks, up to the "-1"
  // that closes the dataset.
  void ReadAsciiValues() {
    const std::size_t numbers = NumbersToRead();
    // A damaged record 7 must not reserve gigabytes: the vector grows anyway,
    // and a value takes at least two bytes of the file (a digit and a blank).
    dataset_.values.reserve(std::min({numbers, cursor_.Remaining() / 2,
                                      std::size_t{1} << 22}));
    while (true) {
      auto line = cursor_.Line();
      if (!line || IsDelimiter(*line)) {
        if (dataset_.values.size() == numbers && line) return;
        Fail("truncated: " + std::to_string(dataset_.values.size()) + " of the " + std::to_string(numbers) +
                 " numbers record 7 announces before " + (line ? "the closing -1" : "the end of the file"),
             "export the dataset again, whole");
      }
      std::string_view rest = *line;
      for (std::string_view token = NextToken(rest); !token.empty(); token = NextToken(rest)) {
        auto value = ParseReal(token);
        if (!value) Fail(RealProblem(token), "write the values as real numbers (E13.5)");
        if (dataset_.values.size() == numbers)
          Fail("more values than the " + std::to_string(numbers) + " record 7 announces",
               "correct the number of values in record 7 field 2");
        dataset_.values.push_back(*value);
      }
    }
  }

  // 58b: the byte count of the header line, values in the stated byte order.
  void ReadBinaryValues(std::size_t num_bytes, bool little_endian) {
    const std::size_t width =
        dataset_.ordinate_type == kRealSingle || dataset_.ordinate_type == kComplexSingle ? 4 : 8;
    const std::size_t numbers = NumbersToRead();
    const std::size_t needed = width * numbers;
    if (num_bytes < needed)
      Fail("the 58b header announces " + std::to_string(num_bytes) + " bytes but record 7 needs " +
               std::to_string(needed) + " (" + std::to_string(numbers) + " values of " + std::to_string(width) +
               " bytes)",
           "export the dataset again: header and record 7 disagree");
    auto block = cursor_.Bytes(num_bytes);
    if (!block)
      Fail("truncated: the file ends inside the " + std::to_string(num_bytes) + " bytes of binary values",
           "export the dataset again, whole");
    const bool swap = little_endian != (std::endian::native == std::endian::little);
    dataset_.values.resize(numbers);
    for (std::size_t i = 0; i < dataset_.values.size(); ++i) {
      unsigned char raw[8];
      std::memcpy(raw, block->data() + i * width, width);
      if (swap) std::reverse(raw, raw + width);
      if (width == 4) {
        float value;
        std::memcpy(&value, raw, 4);
        dataset_.values[i] = value;
      } else {
        std::memcpy(&dataset_.values[i], raw, 8);
      }
    }
    cursor_.SkipLineEnd();
    auto line = cursor_.Line();
    while (line && TrimView(*line).empty()) line = cursor_.Line();
    if (!line || !IsDelimiter(*line))
      Fail("no closing -1 after the binary values", "export the dataset again: the file is truncated or damaged");
  }

 private:
  // Records 8..11: Format(I10,3I5,2(1X,A20)).
  Uff58Axis Axis(std::string_view record) const {
    Uff58Axis axis;
    const std::string_view type = TrimView(Columns(record, 1, 10));
    axis.data_type = type.empty() ? 0 : Integer(type, "the specific data type (columns 1-10)");
    axis.label = std::string(TrimView(Columns(record, 27, 20)));
    axis.unit = std::string(TrimView(Columns(record, 48, 20)));
    return axis;
  }

  Cursor& cursor_;
  Uff58Dataset& dataset_;
  Uff58Functions functions_;
  int num_values_ = 0;
};

void SkipDataset(Cursor& cursor) {
  while (auto line = cursor.Line())
    if (IsDelimiter(*line)) return;
}

}  // namespace

std::string Uff58Dataset::Describe() const {
  return "dataset 58 number " + std::to_string(number) +
         (id_lines[0].empty() ? std::string() : " ('" + Excerpt(TrimView(id_lines[0])) + "')");
}

std::string Uff58Dataset::NodeDirection() const {
  static constexpr const char* kAxes[] = {"X", "Y", "Z", "RX", "RY", "RZ"};
  const int d = std::abs(response_direction);
  std::string direction = d >= 1 && d <= 6 ? std::string(response_direction < 0 ? "-" : "+") + kAxes[d - 1]
                                           : std::to_string(response_direction);
  return std::to_string(response_node) + ":" + direction;
}

std::optional<Quantity> Uff58Quantity(int data_type) {
  switch (data_type) {
    case uff58::kDisplacementType: return Quantity::kDisplacement;
    case uff58::kVelocityType: return Quantity::kVelocity;
    case uff58::kAccelerationType: return Quantity::kAcceleration;
    case uff58::kReactionForceType:
    case uff58::kExcitationForceType: return Quantity::kForce;
    default: return std::nullopt;
  }
}

std::string Uff58Unit(const std::string& unit) {
  std::string compact;
  for (char c : unit)
    if (c != ' ') compact += c;
  // "m/s\xB2": the ² of a writer in Latin-1 (Windows-1252), the encoding of
  // many universal files.
  if (compact == "m/s2" || compact == "m/s**2" || compact == "m/s\xC2\xB2" || compact == "m/s\xB2" ||
      compact == "ms^-2" || compact == "m/s/s" || compact == "m/sec^2" || compact == "m/sec2")
    return "m/s^2";
  if (compact == "G") return "g";
  if (compact == "mm/sec") return "mm/s";
  if (compact == "m/sec") return "m/s";
  return compact;
}

bool Uff58Dataset::Complex() const { return ordinate_type == kComplexSingle || ordinate_type == kComplexDouble; }

double Uff58Dataset::Abscissa(int i) const {
  if (!uneven) return abscissa_start + abscissa_step * i;
  return values[static_cast<std::size_t>(i) * (Complex() ? 3 : 2)];
}

std::complex<double> Uff58Dataset::Ordinate(int i) const {
  const std::size_t per_point = (Complex() ? 2 : 1) + (uneven ? 1 : 0);
  const std::size_t at = static_cast<std::size_t>(i) * per_point + (uneven ? 1 : 0);
  return {values[at], Complex() ? values[at + 1] : 0.0};
}

std::vector<Uff58Dataset> ParseUff58(std::string_view bytes, const std::string& source, Uff58Functions functions) {
  Cursor cursor(bytes, source);
  std::vector<Uff58Dataset> datasets;
  bool any_dataset = false;
  while (true) {
    auto line = cursor.Line();
    while (line && TrimView(*line).empty()) line = cursor.Line();
    if (!line) break;
    if (!IsDelimiter(*line))
      cursor.Fail("line " + std::to_string(cursor.line_number()) + " should open a dataset with -1 but reads '" +
                      Excerpt(TrimView(*line)) + "'",
                  any_dataset ? "export the file again: a dataset is damaged"
                              : "give a universal file (.uff/.unv) whose datasets open and close with -1");
    auto header = cursor.Line();
    if (!header) cursor.Fail("the file ends after an opening -1", "export the file again: it is truncated");
    const auto tokens = Tokens(*header);
    const std::string_view kind = tokens.empty() ? std::string_view() : tokens[0];
    any_dataset = true;
    if (kind != "58" && kind != "58b") {
      SkipDataset(cursor);
      continue;
    }
    Uff58Dataset& dataset = datasets.emplace_back();
    dataset.number = static_cast<int>(datasets.size());
    dataset.binary = kind == "58b";
    DatasetReader reader(cursor, dataset, functions);
    bool little_endian = true;
    std::size_t num_bytes = 0;
    if (dataset.binary) {
      // "    58b     1     2          11        8000     0 ...": byte order
      // (1 little, 2 big endian), float format (2 IEEE 754), ASCII lines, bytes.
      if (tokens.size() < 5) reader.Fail("the 58b header line has fewer than 4 fields", "export the file again");
      const int byte_order = reader.Integer(tokens[1], "the byte order of the 58b header");
      const int float_format = reader.Integer(tokens[2], "the floating-point format of the 58b header");
      const int ascii_lines = reader.Integer(tokens[3], "the number of ASCII lines of the 58b header");
      const long long count = reader.Integer(tokens[4], "the byte count of the 58b header");
      if (byte_order != 1 && byte_order != 2)
        reader.Fail("byte order " + std::to_string(byte_order) + " is neither 1 (little) nor 2 (big endian)",
                    "export the file again");
      if (float_format != 2)
        reader.Fail("floating-point format " + std::to_string(float_format) + " is not IEEE 754 (2)",
                    "export with IEEE floating point");
      if (ascii_lines != kNumHeaderRecords)
        reader.Fail("the 58b header announces " + std::to_string(ascii_lines) + " ASCII lines, not 11",
                    "export the file again");
      if (count < 0) reader.Fail("negative byte count in the 58b header", "export the file again");
      little_endian = byte_order == 1;
      num_bytes = static_cast<std::size_t>(count);
    }
    reader.ReadHeader();
    if (dataset.binary)
      reader.ReadBinaryValues(num_bytes, little_endian);
    else
      reader.ReadAsciiValues();
  }
  if (!any_dataset)
    cursor.Fail("the file holds no dataset", "give a universal file (.uff/.unv) with datasets 58 of the recording");
  if (datasets.empty())
    cursor.Fail("the file holds no dataset 58 (function at nodal DOF)",
                "export the time histories as datasets 58 or 58b");
  return datasets;
}

std::vector<Uff58Dataset> ReadUff58(const std::filesystem::path& file, Uff58Functions functions) {
  const std::string source = file.string();
  return ParseUff58(ReadTextFile(file, "universal file", "check that it exists and is readable"), source, functions);
}

bool IsUniversalFile(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".uff" || extension == ".unv";
}

}  // namespace beamid::signal
