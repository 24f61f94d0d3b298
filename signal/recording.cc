#include "signal/recording.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>

#include "hb/text_file.h"
#include "signal/input_error.h"
#include "signal/uff_recording.h"

namespace beamid::signal {
namespace {

constexpr int kTimeColumn = -1;
constexpr double kLargestPlausibleValue = 1e15;

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string_view Trim(std::string_view s) {
  while (!s.empty() && IsBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
  return s;
}

std::string_view NextLine(std::string_view& text) {
  const std::size_t end = text.find('\n');
  std::string_view line = text.substr(0, end);
  text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
  return line;
}

// Maps each CSV column to a Recording column (or kTimeColumn).
std::vector<int> MapHeader(std::string_view header, const std::vector<const ChannelSpec*>& channels,
                           const std::string& source) {
  if (header.size() >= 3 && std::memcmp(header.data(), "\xEF\xBB\xBF", 3) == 0) header.remove_prefix(3);
  std::vector<int> columns;
  std::vector<bool> seen(channels.size(), false);
  bool time_seen = false;
  while (true) {
    const std::size_t comma = header.find(',');
    const std::string name(Trim(header.substr(0, comma)));
    int column = -2;
    if (name == "time_s") {
      if (time_seen) throw InputError(source, "time_s", "the header names time_s twice", "keep one time column");
      time_seen = true;
      column = kTimeColumn;
    }
    for (std::size_t c = 0; c < channels.size(); ++c) {
      if (channels[c]->channel != name) continue;
      if (seen[c]) throw InputError(source, name, "the header names the channel twice", "keep one column per channel");
      seen[c] = true;
      column = static_cast<int>(c);
    }
    if (column == -2) {
      std::string known = "time_s";
      for (const auto* ch : channels) known += ", " + ch->channel;
      throw InputError(source, name, "unknown column in the header (campaign.json has no such channel)",
                       "name the columns " + known + ", or add the channel to campaign.json's sensors");
    }
    columns.push_back(column);
    if (comma == std::string_view::npos) break;
    header.remove_prefix(comma + 1);
  }
  if (!time_seen)
    throw InputError(source, "time_s", "the header has no time_s column", "add the sample times in seconds as time_s");
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (!seen[c])
      throw InputError(source, channels[c]->channel, "the channel of campaign.json is missing from the header",
                       "export this channel into the recording or correct its name in campaign.json");
  return columns;
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
  std::string_view text = csv_text;
  if (Trim(text).empty()) throw InputError(source, "", "the file is empty", "export the recording again");
  const std::vector<int> columns = MapHeader(NextLine(text), channels, source);

  const auto max_rows = static_cast<Eigen::Index>(std::count(text.begin(), text.end(), '\n') + 1);
  Eigen::MatrixXd samples(max_rows, static_cast<Eigen::Index>(channels.size()));
  std::vector<double> time_s(static_cast<std::size_t>(max_rows));
  Eigen::Index rows = 0;
  int line_number = 1;
  while (!text.empty()) {
    std::string_view line = NextLine(text);
    ++line_number;
    if (Trim(line).empty()) {
      if (Trim(text).empty()) break;  // trailing blank lines are harmless
      throw InputError(source, "", "line " + std::to_string(line_number) + " is empty", "remove the blank line");
    }
    const char* p = line.data();
    const char* const end = line.data() + line.size();
    for (std::size_t field = 0; field < columns.size(); ++field) {
      const std::string_view channel_name = columns[field] == kTimeColumn
                                                ? std::string_view("time_s")
                                                : std::string_view(channels[static_cast<std::size_t>(columns[field])]->channel);
      const char* field_end = std::find(p, end, ',');
      const bool last = field + 1 == columns.size();
      if ((field_end == end) != last)
        throw InputError(source, std::string(channel_name),
                         "line " + std::to_string(line_number) + " does not have one value per header column (" +
                             std::to_string(columns.size()) + " columns)",
                         "give every row one value per header column");
      std::string_view token = Trim(std::string_view(p, static_cast<std::size_t>(field_end - p)));
      if (!token.empty() && token.front() == '+') token.remove_prefix(1);
      double value = 0.0;
      const auto [parsed_end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
      if (token.empty() || error != std::errc() || parsed_end != token.data() + token.size())
        throw InputError(source, std::string(channel_name),
                         "cannot read '" + std::string(token) + "' at line " + std::to_string(line_number) +
                             " as a number",
                         "write plain decimal numbers with '.' as the decimal mark");
      if (!std::isfinite(value))
        throw InputError(source, std::string(channel_name),
                         "NaN or infinite value at line " + std::to_string(line_number),
                         "remove or repair the invalid samples (a NaN is no measurement)");
      // No acquisition system writes 1e15 in any unit; such a value is a
      // corrupted sample, and 1e308 would overflow every sum of squares.
      if (std::abs(value) > kLargestPlausibleValue)
        throw InputError(source, std::string(channel_name),
                         "value " + std::string(token) + " at line " + std::to_string(line_number) +
                             " is beyond any measurement (|value| > 1e15)",
                         "remove or repair the corrupted sample");
      if (columns[field] == kTimeColumn)
        time_s[static_cast<std::size_t>(rows)] = value;
      else
        samples(rows, columns[field]) = value;
      if (!last) p = field_end + 1;
    }
    ++rows;
  }
  time_s.resize(static_cast<std::size_t>(rows));
  samples.conservativeResize(rows, Eigen::NoChange);

  Recording recording;
  recording.file = source;
  for (const auto* channel : channels) recording.channels.push_back(channel->channel);
  recording.sample_rate_hz =
      ValidateTimeColumn(time_s, campaign.sample_rate_hz.value_or(0.0), source, /*first_line=*/2, checks);
  recording.start_time_s = time_s.front();
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (channels[c]->to_si_factor != 1.0) samples.col(static_cast<Eigen::Index>(c)) *= channels[c]->to_si_factor;
  ValidateChannels(samples, recording.channels, recording.sample_rate_hz, recording.start_time_s, step.frequency_hz,
                   source, checks);
  recording.samples = std::move(samples);
  return recording;
}

Recording ReadRecording(const Campaign& campaign, const Step& step, const RecordingChecks& checks) {
  checks.Validate();
  const std::filesystem::path path = campaign.StepPath(step);
  const std::string source = path.string();
  if (IsUniversalFile(path)) return RecordingFromUff58(ReadUff58(path), campaign, step, source, checks);
  const std::string text =
      ReadTextFile(path, "recording", "check that the file named in campaign.json exists and is readable");
  return ParseRecording(text, campaign, step, source, checks);
}

}  // namespace beamid::signal
