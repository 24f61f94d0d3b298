#include "signal/array_recording.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include "signal/input_error.h"
#include "signal/internal/channel_defects.h"
#include "signal/internal/text.h"
#include "signal/quality_finding.h"
#include "signal/table_reader.h"

namespace beamid::signal {
namespace {

using internal::ChannelDefects;
using internal::Excerpt;
using internal::FormatNumber;

// No acquisition system writes 1e15 in any unit (as for CSV, signal/recording.cc).
constexpr double kLargestPlausibleArrayValue = 1e15;
// Arrays named in a message: the first few say what the file holds.
constexpr std::size_t kMaxArraysNamed = 8;

// "variable 'acc1'", "dataset 'data/acc1'".
std::string ArrayNameOf(const ArrayFile& file, const ArrayInfo& array) {
  return std::string(array.root_attribute ? "root attribute" : file.ArrayWord()) + " '" + Excerpt(array.name) + "'";
}

// Where the file gives an array's unit, for messages.
std::string UnitPlace(const ArrayFile& file, const ArrayInfo& array) {
  return file.ArrayWord() == "variable" ? "the variable " + Excerpt(array.name) + "_units"
                                        : std::string("its \"units\" attribute");
}

std::string ListArrays(const ArrayFile& file) {
  std::string list;
  std::size_t named = 0;
  for (const ArrayInfo& array : file.Arrays()) {
    if (named++ == kMaxArraysNamed) {
      list += " and " + std::to_string(file.Arrays().size() - kMaxArraysNamed) + " more";
      break;
    }
    list += (list.empty() ? "'" : ", '") + Excerpt(array.name) + "' (" + array.Shape() + " " + array.type + ")";
  }
  return list.empty() ? "nothing" : list;
}

// Why an array cannot be a channel's (or the time's) samples, with the fix;
// {"", ""} when it can.
std::pair<std::string, std::string> SamplesProblem(const ArrayFile& file, const ArrayInfo& array,
                                                   const std::string& unit) {
  const std::string name = ArrayNameOf(file, array);
  switch (array.kind) {
    case ArrayKind::kReal: break;
    case ArrayKind::kComplex:
      return {name + " holds " + array.type + " values; a time history is real",
              "save the real time series (complex values are spectra: give those as a first-harmonic table)"};
    case ArrayKind::kInteger:
      return {name + " holds " + array.type + " integers (raw converter counts?), not values in a unit",
              "save it in " + (unit.empty() ? std::string("its unit") : "'" + unit + "'") +
                  " as double or single precision numbers (counts times the channel's sensitivity)"};
    case ArrayKind::kElsewhere:
      return {name + " keeps its values in other files (HDF5 external storage or a virtual dataset), which beamid "
                     "does not follow",
              "store the values in the file itself (h5repack, or write the dataset anew)"};
    default:
      return {name + " is a " + array.type + " " + std::string(file.ArrayWord()) + ", not numbers",
              "save it as a vector of double or single precision numbers (no struct, cell, text or logical)"};
  }
  if (!array.IsVector() || array.dims.empty())
    return {name + " is a " + array.Shape() + " array, not a vector of samples",
            "save one vector (a column or a row) per channel"};
  return {"", ""};
}

// The time vector's factor to seconds from its name ("time_s", "t_ms") or,
// for "time" and "t", the unit the file gives; 0 when the array is no time.
double TimeVectorFactor(const ArrayFile& file, const ArrayInfo& array) {
  const std::string name = internal::Lowercase(array.name);
  std::string unit;
  bool is_time = false;
  for (const std::string_view word : {"time", "t"}) {
    if (name == word) is_time = true;
    if (const auto suffix = SplitUnitSuffix(name, word)) {
      const auto normalised = NormaliseUnit(*suffix);
      if (normalised && (*normalised == "s" || *normalised == "ms")) {
        is_time = true;
        unit = *normalised;
      }
    }
  }
  if (!is_time) return 0.0;
  if (!array.unit.empty()) {
    const auto given = NormaliseUnit(array.unit);
    if (!given || (*given != "s" && *given != "ms"))
      throw InputError(file.Source(), Excerpt(array.name),
                       "the time " + std::string(file.ArrayWord()) + " '" + Excerpt(array.name) + "' has the unit '" +
                           Excerpt(array.unit) + "' (" + UnitPlace(file, array) + "), which is not a time unit",
                       "give the time in s or ms");
    if (!unit.empty() && unit != *given)
      throw InputError(file.Source(), Excerpt(array.name),
                       "the time " + std::string(file.ArrayWord()) + "'s name says '" + unit + "' but " +
                           UnitPlace(file, array) + " says '" + Excerpt(array.unit) + "'",
                       "give the time's unit once, or make the two agree");
    unit = *given;
  }
  if (unit.empty())
    throw InputError(file.Source(), Excerpt(array.name),
                     "the time " + std::string(file.ArrayWord()) + " '" + Excerpt(array.name) + "' has no unit",
                     "name it time_s (seconds) or time_ms, or give its unit: " +
                         (file.ArrayWord() == "variable" ? "a char variable " + array.name + "_units = 's'"
                                                         : std::string("an attribute units = \"s\"")));
  return unit == "s" ? 1.0 : 1e-3;
}

bool IsSampleRateName(std::string_view name) { return name == "sample_rate_Hz" || name == "fs" || name == "Fs"; }

}  // namespace

Recording RecordingFromArrays(ArrayFile& file, const Campaign& campaign, const Step& step,
                              const RecordingChecks& checks) {
  checks.Validate();
  const std::string& source = file.Source();
  const std::string word(file.ArrayWord());
  const auto channels = campaign.Channels();
  ChannelDefects defects(campaign, channels, source);
  const auto is_channel_name = [&](const std::string& name) {
    return std::any_of(channels.begin(), channels.end(), [&](const ChannelSpec* c) { return c->channel == name; });
  };

  // Each channel's array: by "column", by name, or by name and a unit suffix.
  std::vector<const ArrayInfo*> matched(channels.size(), nullptr);
  std::vector<std::string> units(channels.size());  // the unit the file gives for it, as written
  std::set<const ArrayInfo*> used;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const ChannelSpec& spec = *channels[c];
    if (spec.column_number > 0) {
      defects.Report(c,
                     "campaign.json's \"column_number\": " + std::to_string(spec.column_number) +
                         " numbers a CSV column, but a " + file.FormatName() + " names its " + word + "s",
                     "name the channel's " + word + " with \"column\" instead");
      continue;
    }
    const std::string wanted = spec.column.empty() ? spec.channel : spec.column;
    const ArrayInfo* array = file.Find(wanted);
    if (array == nullptr && wanted.size() > 1 && wanted.front() == '/') array = file.Find(wanted.substr(1));
    std::string suffix_unit;
    if (array == nullptr && spec.column.empty()) {
      for (const ArrayInfo& candidate : file.Arrays()) {
        const auto suffix = SplitUnitSuffix(candidate.name, spec.channel);
        if (!suffix || candidate.root_attribute || is_channel_name(candidate.name)) continue;
        if (array != nullptr) {
          defects.Report(c,
                         "two " + word + "s hold the channel: '" + Excerpt(array->name) + "' and '" +
                             Excerpt(candidate.name) + "'",
                         "keep one " + word + " per channel");
          break;
        }
        array = &candidate;
        suffix_unit = *suffix;
      }
      if (defects.Dropped(c)) continue;
    }
    if (array == nullptr || array->root_attribute) {
      defects.Report(c,
                     "the " + file.FormatName() + " has no " + word + " named '" + Excerpt(wanted, 60) +
                         "' (it holds " + ListArrays(file) + ")",
                     "save the channel as a vector named " + wanted + " (a unit suffix may follow: " + wanted + "_" +
                         spec.unit + "), correct the channel's name in campaign.json, or name its " + word +
                         " there with \"column\"");
      continue;
    }
    used.insert(array);
    if (const auto [problem, fix] = SamplesProblem(file, *array, spec.unit); !problem.empty()) {
      defects.Report(c, problem, fix);
      continue;
    }
    if (!suffix_unit.empty() && !array->unit.empty() && NormaliseUnit(suffix_unit) != NormaliseUnit(array->unit)) {
      defects.Report(c,
                     ArrayNameOf(file, *array) + "'s name says '" + suffix_unit + "' but " + UnitPlace(file, *array) +
                         " says '" + Excerpt(array->unit) + "'",
                     "give the unit once, or make the two agree");
      continue;
    }
    matched[c] = array;
    units[c] = array->unit.empty() ? suffix_unit : array->unit;
    if (units[c].empty()) continue;  // campaign.json's unit applies
    // As a CSV header's: one of the two is wrong, and beamid will not guess which.
    const auto normalised = NormaliseUnit(units[c]);
    const std::string gives = ArrayNameOf(file, *array) + " gives the unit '" + Excerpt(units[c]) + "' (" +
                              (array->unit.empty() ? std::string("its name") : UnitPlace(file, *array)) + ")";
    if (!normalised || !UnitToSiFactor(spec.quantity, *normalised)) {
      defects.Report(c,
                     gives + ", which is not a unit of " + std::string(QuantityName(spec.quantity)) +
                         " (campaign.json declares '" + spec.unit + "')",
                     "give one of " + AcceptedUnits(spec.quantity) + ", the unit campaign.json declares");
      matched[c] = nullptr;
    } else if (*normalised != spec.unit) {
      defects.Report(c, gives + " but campaign.json declares '" + spec.unit + "' for this channel",
                     "make them agree: correct the channel's \"unit\" in campaign.json, or save the channel in " +
                         spec.unit);
      matched[c] = nullptr;
    }
  }

  // The excitation is always used: a problem of it has thrown above.
  const std::uint64_t num_samples = matched[0]->NumElements();
  for (std::size_t c = 1; c < channels.size(); ++c)
    if (matched[c] != nullptr && matched[c]->NumElements() != num_samples) {
      defects.Report(c,
                     ArrayNameOf(file, *matched[c]) + " holds " + std::to_string(matched[c]->NumElements()) +
                         " samples, but the excitation's " + ArrayNameOf(file, *matched[0]) + " holds " +
                         std::to_string(num_samples),
                     "save all channels of a step together, over one time span at one sample rate");
      matched[c] = nullptr;
    }

  // The time vector, the sample rate, and what else the file holds.
  const ArrayInfo* time = nullptr;
  double time_to_s = 1.0;
  std::optional<double> file_rate_hz;
  std::string file_rate_name;
  Recording recording;
  recording.file = source;
  for (const ArrayInfo& array : file.Arrays()) {
    if (used.count(&array)) continue;
    if (array.kind == ArrayKind::kText && array.name.size() > 6 &&
        array.name.compare(array.name.size() - 6, 6, "_units") == 0 &&
        file.Find(array.name.substr(0, array.name.size() - 6)) != nullptr)
      continue;  // a unit, read with its array
    if (IsSampleRateName(array.name)) {
      const std::string name = ArrayNameOf(file, array);
      if (array.kind != ArrayKind::kReal || array.NumElements() != 1)
        throw InputError(source, Excerpt(array.name),
                         name + " is a " + array.Shape() + " " + array.type + ", not one number (the rate in Hz)",
                         "save the sample rate as one double number in Hz");
      const double rate_hz = file.ReadReal(array).front();
      if (!std::isfinite(rate_hz) || rate_hz <= 0.0)
        throw InputError(source, Excerpt(array.name), name + " is " + FormatNumber(rate_hz) + ", not a sample rate",
                         "save the sample rate in Hz, a positive number");
      if (file_rate_hz && std::abs(rate_hz / *file_rate_hz - 1.0) > 1e-9)
        throw InputError(source, Excerpt(array.name),
                         name + " gives " + FormatNumber(rate_hz) + " Hz but " + file_rate_name + " gives " +
                             FormatNumber(*file_rate_hz) + " Hz",
                         "give the sample rate once");
      file_rate_hz = rate_hz;
      file_rate_name = name;
      continue;
    }
    if (array.root_attribute) continue;  // metadata
    if (const double factor = TimeVectorFactor(file, array); factor > 0.0) {
      if (time != nullptr)
        throw InputError(source, Excerpt(array.name),
                         "the file has two time " + word + "s ('" + Excerpt(time->name) + "' and '" +
                             Excerpt(array.name) + "')",
                         "keep one time " + word);
      time = &array;
      time_to_s = factor;
      continue;
    }
    recording.ignored_columns.push_back(Excerpt(array.name));
  }

  std::vector<double> time_s;
  if (time != nullptr) {
    if (const auto [problem, fix] = SamplesProblem(file, *time, "s"); !problem.empty())
      throw InputError(source, Excerpt(time->name), problem, fix);
    if (time->NumElements() != num_samples)
      throw InputError(source, Excerpt(time->name),
                       ArrayNameOf(file, *time) + " holds " + std::to_string(time->NumElements()) +
                           " times, but the excitation's " + ArrayNameOf(file, *matched[0]) + " holds " +
                           std::to_string(num_samples) + " samples",
                       "save the time vector with the channels, one time per sample");
    time_s = file.ReadReal(*time);
    for (std::size_t n = 0; n < time_s.size(); ++n) {
      if (!std::isfinite(time_s[n]))
        throw InputError(source, Excerpt(time->name),
                         ArrayNameOf(file, *time) + " holds NaN or an infinite value at sample " + std::to_string(n),
                         "save the time of every sample, or leave the time out and give the sample rate");
      time_s[n] *= time_to_s;
    }
    PrintedTime printed;
    printed.column = Excerpt(time->name);
    printed.first_line = 0;
    printed.place = "sample";
    recording.sample_rate_hz =
        ValidateTimeColumn(time_s, campaign.sample_rate_hz.value_or(0.0), source, printed, checks);
    recording.start_time_s = time_s.front();
    if (file_rate_hz && std::abs(recording.sample_rate_hz / *file_rate_hz - 1.0) > checks.sample_rate_tolerance_rel)
      throw InputError(source, Excerpt(time->name),
                       ArrayNameOf(file, *time) + " implies " + FormatNumber(recording.sample_rate_hz) + " Hz but " +
                           file_rate_name + " gives " + FormatNumber(*file_rate_hz) + " Hz",
                       "save the time vector and the sample rate of the same recording, or only one of them");
  } else if (file_rate_hz) {
    if (campaign.sample_rate_hz &&
        std::abs(*file_rate_hz / *campaign.sample_rate_hz - 1.0) > checks.sample_rate_tolerance_rel)
      throw InputError(source, "",
                       file_rate_name + " gives " + FormatNumber(*file_rate_hz) +
                           " Hz, but campaign.json says sample_rate_Hz = " + FormatNumber(*campaign.sample_rate_hz),
                       "correct sample_rate_Hz in campaign.json or the file's sample rate");
    recording.sample_rate_hz = *file_rate_hz;
  } else if (campaign.sample_rate_hz) {
    recording.sample_rate_hz = *campaign.sample_rate_hz;
  } else {
    throw InputError(source, "",
                     "the " + file.FormatName() + " has no time " + word + " and no sample rate, and campaign.json "
                     "gives no sample_rate_Hz, so the sample rate is unknown (the file holds " + ListArrays(file) + ")",
                     "save a time vector time_s (or time_ms) or the scalar sample_rate_Hz with the channels, or "
                     "add \"sample_rate_Hz\" to campaign.json");
  }
  if (num_samples < 2) throw InputError(source, "", "fewer than two samples", "record the whole step");

  // The samples, each channel judged before it is kept.
  std::vector<std::vector<double>> values(channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c) {
    if (matched[c] == nullptr || defects.Dropped(c)) continue;
    values[c] = file.ReadReal(*matched[c]);
    for (std::size_t n = 0; n < values[c].size(); ++n) {
      const double value = values[c][n];
      if (std::isfinite(value) && std::abs(value) <= kLargestPlausibleArrayValue) continue;
      const std::string at = " at sample " + std::to_string(n) + " (t = " +
                             FormatNumber(time_s.empty() ? static_cast<double>(n) / recording.sample_rate_hz
                                                         : time_s[n]) + " s)";
      if (!std::isfinite(value))
        defects.Report(c, ArrayNameOf(file, *matched[c]) + " holds NaN or an infinite value" + at,
                       "remove or repair the invalid samples (a NaN is no measurement)");
      else
        defects.Report(c, ArrayNameOf(file, *matched[c]) + " holds the value " + FormatNumber(value) + at +
                              ", beyond any measurement (|value| > 1e15)",
                       "remove or repair the corrupted sample");
      values[c].clear();
      break;
    }
  }
  std::vector<std::size_t> kept;
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (!values[c].empty() && !defects.Dropped(c)) kept.push_back(c);
  Eigen::MatrixXd samples(static_cast<Eigen::Index>(num_samples), static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const ChannelSpec& spec = *channels[kept[k]];
    recording.channels.push_back(spec.channel);
    samples.col(static_cast<Eigen::Index>(k)) =
        spec.to_si_factor *
        Eigen::Map<const Eigen::VectorXd>(values[kept[k]].data(), static_cast<Eigen::Index>(num_samples));
    std::vector<double>().swap(values[kept[k]]);
  }
  defects.Finish(recording, std::move(samples), step, checks);
  return recording;
}

}  // namespace beamid::signal
