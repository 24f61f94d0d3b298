#include "signal/recording.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cctype>
#include <fstream>
#include <optional>
#include <utility>

#include "hb/text_file.h"
#include "signal/array_recording.h"
#include "signal/input_error.h"
#include "signal/internal/channel_defects.h"
#include "signal/internal/text.h"
#include "signal/quality_finding.h"
#include "signal/table_reader.h"
#include "signal/uff_recording.h"

namespace beamid::signal {
namespace {

using internal::ChannelDefects;
using internal::Excerpt;
using internal::IsValidUtf8;

constexpr int kTimeColumn = -1;
constexpr int kIgnoredColumn = -2;
constexpr double kLargestPlausibleValue = 1e15;
// Unused columns named in a message: the first few say what they are.
constexpr std::size_t kMaxColumnsNamed = 8;

std::string LowerCase(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// What the header says of each CSV column.
struct HeaderMap {
  std::vector<int> columns;          // channel index, kTimeColumn or kIgnoredColumn per cell
  std::vector<std::string> names;    // per cell, for messages: the channel (or the time column's header)
  int time_cell = -1;
  double time_to_s = 1.0;            // 1e-3 for a time column in ms
  std::vector<std::string> ignored;  // header cells no channel uses (printable excerpts)
};

// A header cell naming the time: "time_s", "t_ms", "time [ms]", "Time (s)";
// the time unit's factor to s, 0 when the cell is not a time column. A time
// column without a unit is an error.
double TimeUnitFactor(const HeaderCell& cell, const std::string& source) {
  const std::string text = LowerCase(cell.text), name = LowerCase(cell.name);
  // A units row's unit stands for the whole cell ("time_s" over "s").
  const bool from_units_row = cell.unit_line > 0;
  std::string unit = from_units_row ? "" : cell.unit;
  if (unit.empty()) {
    for (const std::string_view word : {"time", "t"}) {
      if (text == word && cell.unit.empty())
        throw InputError(source, cell.text, "the time column has no unit",
                         "name it time_s (seconds) or time_ms, or write the unit: time [s], time [ms]");
      if (text == word) unit = cell.unit;
      if (const auto suffix = SplitUnitSuffix(text, word)) {
        if (from_units_row && NormaliseUnit(*suffix) != NormaliseUnit(cell.unit))
          throw InputError(source, Excerpt(cell.text),
                           "the time column's header says '" + *suffix + "' but the units row (line " +
                               std::to_string(cell.unit_line) + ") gives '" + Excerpt(cell.unit) + "'",
                           "give the time's unit once, in the header or in the units row, or make them agree");
        unit = *suffix;
      }
    }
    if (unit.empty()) return 0.0;
  } else if (name != "time" && name != "t") {
    return 0.0;
  }
  const auto normalised = NormaliseUnit(unit);
  if (normalised == "s") return 1.0;
  if (normalised == "ms") return 1e-3;
  throw InputError(source, Excerpt(cell.text), "the time column's unit '" + Excerpt(unit) + "' is not a time unit",
                   "give the time in s or ms: time_s, time [ms]");
}

// The channel a header cell names, and the unit it writes: the whole cell
// ("acc1_g" is the channel acc1_g when there is one), else its name before a
// bracketed unit ("acc1 [g]"), else a channel's name and a unit suffix
// ("acc1_g" for acc1). A name is matched whole, never as a prefix, so sensors
// acc1 and acc1_g are told apart in any order.
// A channel that campaign.json maps to a column ("column", "column_number")
// is not looked for by name.
bool IsMapped(const ChannelSpec& spec) { return !spec.column.empty() || spec.column_number > 0; }

std::optional<std::pair<std::size_t, std::string>> ChannelOfCell(const HeaderCell& cell,
                                                                 const std::vector<const ChannelSpec*>& channels) {
  const auto by_name = [&](std::size_t c) { return !IsMapped(*channels[c]); };
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (by_name(c) && cell.text == channels[c]->channel) return std::pair{c, cell.unit_line > 0 ? cell.unit : ""};
  if (!cell.unit.empty())
    for (std::size_t c = 0; c < channels.size(); ++c)
      if (by_name(c) && cell.name == channels[c]->channel) return std::pair{c, cell.unit};
  std::optional<std::pair<std::size_t, std::string>> suffixed;
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (const auto suffix = SplitUnitSuffix(cell.text, channels[c]->channel);
        by_name(c) && suffix &&
        (!suffixed || channels[c]->channel.size() > channels[suffixed->first]->channel.size()))
      suffixed = std::pair{c, *suffix};
  return suffixed;
}

// The unit a header writes for a channel, against campaign.json's: "" when
// they agree, else the problem.
std::string UnitProblem(const ChannelSpec& spec, const std::string& unit, int units_row_line) {
  const std::string gives =
      (units_row_line > 0 ? "the units row (line " + std::to_string(units_row_line) + ")" : std::string("the header")) +
      " gives the unit '" + Excerpt(unit) + "'";
  if (!IsValidUtf8(unit)) return gives + ", which is not UTF-8 text (campaign.json declares '" + spec.unit + "')";
  const auto normalised = NormaliseUnit(unit);
  if (!normalised || !UnitToSiFactor(spec.quantity, *normalised))
    return gives + ", which is not a unit of " + std::string(QuantityName(spec.quantity)) +
           " (campaign.json declares '" + spec.unit + "')";
  if (*normalised != spec.unit) return gives + " but campaign.json declares '" + spec.unit + "' for this channel";
  return "";
}

std::string ListColumns(const std::vector<std::string>& columns) {
  std::string list;
  for (std::size_t i = 0; i < columns.size() && i < kMaxColumnsNamed; ++i)
    list += (list.empty() ? "'" : ", '") + columns[i] + "'";
  if (columns.size() > kMaxColumnsNamed) list += " and " + std::to_string(columns.size() - kMaxColumnsNamed) + " more";
  return list;
}

// The header cells of the channels campaign.json maps to a column, by
// header text or number; the cells of no such channel hold npos. A mapping
// that finds no column (or two) is the channel's defect.
std::vector<std::size_t> MappedChannelOfCells(const TableReader& table, const std::vector<const ChannelSpec*>& channels,
                                              ChannelDefects& defects) {
  const std::vector<HeaderCell>& header = table.Header();
  std::vector<std::size_t> channel_of(header.size(), std::string::npos);
  const std::string header_line = "the header (line " + std::to_string(table.HeaderLine()) + ")";
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const ChannelSpec& spec = *channels[c];
    if (spec.column_number > 0) {
      const auto cell = static_cast<std::size_t>(spec.column_number - 1);
      if (cell >= header.size()) {
        defects.Report(c,
                       "campaign.json's \"column_number\": " + std::to_string(spec.column_number) +
                           " lies beyond the recording's columns: " + header_line + " has " +
                           std::to_string(header.size()) + " (" + table.Format().Describe() + ")",
                       "count the columns from 1 at the left, the time column included, or name the column by its "
                       "header text with \"column\"");
        continue;
      }
      channel_of[cell] = c;
      continue;
    }
    if (spec.column.empty()) continue;
    std::vector<std::size_t> found;
    for (std::size_t cell = 0; cell < header.size(); ++cell)
      if (header[cell].text == spec.column) found.push_back(cell);
    // Without its unit ("Laser (M - Filtered)" for "Laser (M - Filtered) [m/s]") when the whole text matches none.
    if (found.empty())
      for (std::size_t cell = 0; cell < header.size(); ++cell)
        if (!header[cell].unit.empty() && header[cell].name == spec.column) found.push_back(cell);
    if (found.size() == 1) {
      channel_of[found.front()] = c;
    } else if (found.empty()) {
      std::vector<std::string> texts;
      for (const HeaderCell& cell : header) texts.push_back(Excerpt(cell.text));
      defects.Report(c,
                     "campaign.json's \"column\": \"" + Excerpt(spec.column, 60) + "\" names no column of " +
                         header_line + " (columns: " + ListColumns(texts) + ")",
                     "copy the column's header text from the recording into \"column\" (letter case and blanks "
                     "count), or give its number with \"column_number\"");
    } else {
      defects.Report(c,
                     "campaign.json's \"column\": \"" + Excerpt(spec.column, 60) + "\" names " +
                         std::to_string(found.size()) + " columns of " + header_line + " (columns " +
                         std::to_string(found[0] + 1) + " and " + std::to_string(found[1] + 1) + ")",
                     "give the column's number with \"column_number\" instead");
    }
  }
  return channel_of;
}

HeaderMap MapHeader(const TableReader& table, const std::vector<const ChannelSpec*>& channels,
                    const std::string& source, ChannelDefects& defects) {
  HeaderMap map;
  std::vector<bool> seen(channels.size(), false);
  const std::vector<std::size_t> mapped = MappedChannelOfCells(table, channels, defects);
  for (std::size_t c = 0; c < channels.size(); ++c)
    seen[c] = IsMapped(*channels[c]) && std::find(mapped.begin(), mapped.end(), c) == mapped.end();
  for (const HeaderCell& cell : table.Header()) {
    int column = kIgnoredColumn;
    std::string name = Excerpt(cell.text);
    const std::size_t mapped_channel = mapped[map.columns.size()];
    const auto match = mapped_channel != std::string::npos
                           ? std::optional<std::pair<std::size_t, std::string>>({mapped_channel, cell.unit})
                           : ChannelOfCell(cell, channels);
    if (match) {
      const auto& [c, unit] = *match;
      const ChannelSpec& spec = *channels[c];
      name = spec.channel;
      if (seen[c]) {
        defects.Report(c, "the header names the channel twice", "keep one column per channel");
      } else if (const std::string problem = unit.empty() ? "" : UnitProblem(spec, unit, cell.unit_line);
                 !problem.empty()) {
        defects.Report(c, problem,
                       "make them agree: correct the channel's \"unit\" in campaign.json, or export the channel in " +
                           spec.unit + " (its header may say " + spec.channel + " [" + spec.unit + "] or nothing)");
      } else {
        column = static_cast<int>(c);
      }
      seen[c] = true;
    } else if (const double factor = TimeUnitFactor(cell, source); factor > 0.0) {
      if (map.time_cell >= 0)
        throw InputError(source, name,
                         "the header has two time columns ('" + map.names[static_cast<std::size_t>(map.time_cell)] +
                             "' and '" + name + "')",
                         "keep one time column");
      map.time_cell = static_cast<int>(map.columns.size());
      map.time_to_s = factor;
      column = kTimeColumn;
    } else if (!cell.text.empty()) {
      map.ignored.push_back(name);
      // Its name would reach the step's warnings, and from there JSON files.
      if (!IsValidUtf8(cell.text))
        defects.Note("column " + std::to_string(map.columns.size() + 1) + "'s header '" + name +
                         "' is not UTF-8 text; no channel uses the column, so it is ignored",
                     "save the file as UTF-8 if a channel should read this column");
    }
    map.columns.push_back(column);
    map.names.push_back(std::move(name));
  }
  for (std::size_t c = 0; c < channels.size(); ++c) {
    if (seen[c]) continue;
    // One header cell for several channels: the separator is none of ours.
    const std::string single = table.Header().size() == 1 && channels.size() > 1
                                   ? "; the header is a single column, so " + table.Format().Describe() +
                                         " but the header may use another separator"
                                   : "";
    defects.Report(c,
                   "the channel of campaign.json is missing from the header" +
                       (map.ignored.empty() ? std::string()
                                            : " (columns no channel uses: " + ListColumns(map.ignored) + single + ")"),
                   "export this channel into the recording, correct its name in campaign.json (a header may "
                   "add a unit: " + channels[c]->channel + " [" + channels[c]->unit + "]) or name its column there "
                   "with \"column\" or \"column_number\"" +
                       (table.HeaderLine() > 1 ? " (the header read is line " + std::to_string(table.HeaderLine()) +
                                                     "; a metadata block above it: \"recording_layout\")"
                                               : std::string()));
  }
  return map;
}

// Half a unit of the last printed digit of each time value [s], judged over
// the column: a printer that drops trailing zeros ("0.5" for 0.5000) is
// credited with the digits its other values show.
std::vector<double> TimeRounding(const std::vector<double>& time, const std::vector<PrintedPrecision>& precision,
                                 double to_s) {
  int max_decimals = -400, max_significant = 0;
  for (const auto& p : precision) {
    max_decimals = std::max(max_decimals, p.decimals);
    max_significant = std::max(max_significant, p.significant);
  }
  std::vector<double> rounding(time.size());
  for (std::size_t i = 0; i < time.size(); ++i) {
    const double own = 0.5 * std::pow(10.0, -precision[i].decimals);
    const double fixed = 0.5 * std::pow(10.0, -max_decimals);
    const double magnitude = std::abs(time[i]) > 0.0 ? std::floor(std::log10(std::abs(time[i]))) : 0.0;
    const double significant = 0.5 * std::pow(10.0, magnitude - max_significant + 1);
    rounding[i] = std::min(own, std::max(fixed, significant)) * to_s;
  }
  return rounding;
}

}  // namespace

int Recording::ChannelIndex(std::string_view channel) const {
  auto it = std::find(channels.begin(), channels.end(), channel);
  return it == channels.end() ? -1 : static_cast<int>(it - channels.begin());
}

Recording ParseRecording(std::string_view csv_text, const Campaign& campaign, const Step& step,
                         const std::string& source, const RecordingChecks& checks) {
  checks.Validate();
  const auto channels = campaign.Channels();
  TableReader table(csv_text, source, {.blank_lines_inside = false, .layout = campaign.recording_layout});
  if (!table.HasHeader()) throw InputError(source, "", "the file is empty", "export the recording again");
  ChannelDefects defects(campaign, channels, source);
  const HeaderMap map = MapHeader(table, channels, source, defects);
  const bool has_time = map.time_cell >= 0;
  if (!has_time && !campaign.sample_rate_hz)
    throw InputError(source, "",
                     "the recording has no time column and campaign.json gives no sample_rate_Hz, so the sample rate "
                     "is unknown",
                     "add a time column (time_s, or time [ms]) to the recording, or \"sample_rate_Hz\" to "
                     "campaign.json");
  const std::size_t num_cells = map.columns.size();

  // The rows counted before anything is reserved: a file of blank lines or
  // comments reserves nothing, and one without two rows stops here.
  const std::size_t max_rows = table.CountRows();
  if (max_rows < 2)
    throw InputError(source, has_time ? map.names[static_cast<std::size_t>(map.time_cell)] : "",
                     "fewer than two samples (" + std::to_string(max_rows) +
                         (max_rows == 1 ? " data row" : " data rows") + " after the header on line " +
                         std::to_string(table.HeaderLine()) + ")",
                     "record the whole step");
  Eigen::MatrixXd samples(static_cast<Eigen::Index>(max_rows), static_cast<Eigen::Index>(channels.size()));
  std::vector<double> time_s;
  std::vector<int> lines;
  std::vector<PrintedPrecision> time_precision;
  if (has_time) {
    time_s.reserve(max_rows);
    lines.reserve(max_rows);
    time_precision.reserve(max_rows);
  }
  Eigen::Index rows = 0;
  while (table.NextRow()) {
    const int line_number = table.Line();
    const auto& cells = table.Cells();
    if (cells.size() != num_cells) {
      const std::size_t at = std::min(cells.size(), num_cells - 1);
      throw InputError(source, map.names[at],
                       table.Format().Describe() + ": line " + std::to_string(line_number) +
                           " does not have one value per header column (" + std::to_string(num_cells) +
                           " columns, the line has " + std::to_string(cells.size()) + ")",
                       "give every row one value per header column");
    }
    for (std::size_t field = 0; field < num_cells; ++field) {
      const int column = map.columns[field];
      if (column == kIgnoredColumn || (column >= 0 && defects.Dropped(static_cast<std::size_t>(column)))) continue;
      // A time column's problem is the whole record's; a channel's is graded.
      const auto refuse = [&](const std::string& problem, const std::string& fix) {
        if (column == kTimeColumn) throw InputError(source, map.names[field], problem, fix);
        defects.Report(static_cast<std::size_t>(column), problem, fix);
      };
      const std::string& channel_name = map.names[field];
      double value = 0.0;
      PrintedPrecision precision;
      if (!table.Number(field, value, column == kTimeColumn ? &precision : nullptr)) {
        refuse(table.NotANumber(field, channel_name),
               table.Format().decimal_mark == ','
                   ? "write plain decimal numbers with ',' as the decimal mark throughout the file"
                   : "write plain decimal numbers with '.' as the decimal mark");
        continue;
      }
      if (!std::isfinite(value)) {
        refuse("NaN or infinite value at line " + std::to_string(line_number),
               "remove or repair the invalid samples (a NaN is no measurement)");
        continue;
      }
      // No acquisition system writes 1e15 in any unit; such a value is a
      // corrupted sample, and 1e308 would overflow every sum of squares.
      if (std::abs(value) > kLargestPlausibleValue) {
        refuse("value " + Excerpt(table.CellText(field)) + " at line " + std::to_string(line_number) +
                   " is beyond any measurement (|value| > 1e15)",
               "remove or repair the corrupted sample");
        continue;
      }
      if (column == kTimeColumn) {
        time_s.push_back(map.time_to_s == 1.0 ? value : value / 1000.0);
        lines.push_back(line_number);
        time_precision.push_back(precision);
      } else {
        samples(rows, column) = value;
      }
    }
    ++rows;
  }
  samples.conservativeResize(rows, Eigen::NoChange);

  Recording recording;
  recording.file = source;
  recording.ignored_columns = map.ignored;
  std::vector<Eigen::Index> kept;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    if (defects.Dropped(c)) continue;
    kept.push_back(static_cast<Eigen::Index>(c));
    recording.channels.push_back(channels[c]->channel);
    if (channels[c]->to_si_factor != 1.0) samples.col(static_cast<Eigen::Index>(c)) *= channels[c]->to_si_factor;
  }
  if (defects.Any()) samples = Eigen::MatrixXd(samples(Eigen::all, kept));
  if (has_time) {
    PrintedTime printed;
    printed.column = map.names[static_cast<std::size_t>(map.time_cell)];
    printed.first_line = lines.empty() ? table.HeaderLine() + 1 : lines.front();
    printed.lines = std::move(lines);
    printed.rounding_s = [&] { return TimeRounding(time_s, time_precision, map.time_to_s); };
    recording.sample_rate_hz =
        ValidateTimeColumn(time_s, campaign.sample_rate_hz.value_or(0.0), source, printed, checks);
    recording.start_time_s = time_s.front();
  } else {
    if (rows < 2) throw InputError(source, "", "fewer than two samples", "record the whole step");
    recording.sample_rate_hz = *campaign.sample_rate_hz;
    recording.start_time_s = 0.0;
  }
  defects.Finish(recording, std::move(samples), step, checks);
  return recording;
}

Recording ReadRecording(const Campaign& campaign, const Step& step, const RecordingChecks& checks) {
  checks.Validate();
  const std::filesystem::path path = campaign.StepPath(step);
  const std::string source = path.string();
  if (IsUniversalFile(path)) return RecordingFromUff58(ReadUff58(path), campaign, step, source, checks);
  if (IsArrayFile(path)) return RecordingFromArrays(*OpenArrayFile(path, source), campaign, step, checks);
  const std::string text =
      ReadTextFile(path, "recording", "check that the file named in campaign.json exists and is readable");
  return ParseRecording(text, campaign, step, source, checks);
}

}  // namespace beamid::signal
