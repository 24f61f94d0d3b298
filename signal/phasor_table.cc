#include "signal/phasor_table.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "hb/text_file.h"
#include "signal/array_file.h"
#include "signal/first_harmonic_level.h"
#include "signal/input_error.h"
#include "signal/internal/text.h"
#include "signal/table_reader.h"

namespace beamid::signal {
namespace {

enum class ColumnRole { kFrequency, kForce, kResponse, kPhase };

struct Column {
  std::string header;  // as written, for messages
  ColumnRole role = ColumnRole::kFrequency;
  bool is_std = false;
  std::string unit;                       // normalised, "" when not given
  std::optional<Quantity> quantity;       // a response or excitation column that names it
  int index = 0;
};

std::string TrimBlanksAndQuotes(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\"'");
  if (first == std::string_view::npos) return "";
  const auto last = text.find_last_not_of(" \t\r\"'");
  return std::string(text.substr(first, last - first + 1));
}

// The unit spellings of signal/table_reader.h, without the time units (no
// column of a phasor table is a time). Its own name: the unity build puts
// this file beside others that call signal::NormaliseUnit unqualified.
std::optional<std::string> PhasorTableUnit(const std::string& raw) {
  auto unit = signal::NormaliseUnit(raw);
  if (unit == "s" || unit == "ms") return std::nullopt;
  return unit;
}

// Splits "force [N]", "phase (deg)", "frequency_Hz", "acc_m_s2" into a
// normalised name and a unit (raw when bracketed and unknown, so that the
// error can name it).
std::pair<std::string, std::string> SplitNameAndUnit(const std::string& header) {
  std::string name = header, unit;
  for (const auto& [open, close] : {std::pair{'[', ']'}, std::pair{'(', ')'}}) {
    const auto a = header.find(open), b = header.rfind(close);
    if (a != std::string::npos && b != std::string::npos && b > a) {
      name = header.substr(0, a);
      unit = TrimBlanksAndQuotes(header.substr(a + 1, b - a - 1));
      break;
    }
  }
  name = internal::Lowercase(TrimBlanksAndQuotes(name));
  std::replace_if(name.begin(), name.end(), [](char c) { return c == ' ' || c == '-' || c == '.'; }, '_');
  while (!name.empty() && name.back() == '_') name.pop_back();
  if (unit.empty()) {
    // The longest suffix after an underscore that is a unit.
    for (std::size_t pos = name.find('_'); pos != std::string::npos; pos = name.find('_', pos + 1)) {
      if (PhasorTableUnit(name.substr(pos + 1))) {
        unit = name.substr(pos + 1);
        name = name.substr(0, pos);
        break;
      }
    }
  }
  return {name, unit};
}

bool StripAffix(std::string& name, std::string_view prefix, std::string_view suffix) {
  if (!prefix.empty() && name.starts_with(prefix)) {
    name = name.substr(prefix.size());
    return true;
  }
  if (!suffix.empty() && name.ends_with(suffix)) {
    name = name.substr(0, name.size() - suffix.size());
    return true;
  }
  return false;
}

// A column by its name; `cell.unit` when the units row gave it.
std::optional<Column> Classify(const HeaderCell& cell, int index) {
  const std::string& header = cell.text;
  auto [name, unit] = SplitNameAndUnit(header);
  if (cell.unit_line > 0) unit = cell.unit;
  Column column{.header = header, .unit = unit, .index = index};
  column.is_std = StripAffix(name, "std_", "_std") || StripAffix(name, "sigma_", "_sigma") ||
                  StripAffix(name, "u_", "_u");
  bool amplitude = false;
  for (std::string_view amp : {"_amplitude", "_amp", "_magnitude", "_mag"})
    if ((amplitude = StripAffix(name, "", amp))) break;
  // "F_amp", "F [N]": the force, not the frequency.
  if (name == "f" && (amplitude || PhasorTableUnit(unit) == std::optional<std::string>("N"))) name = "force";
  // An excitation that says what it is: the default is a force.
  static const std::array<std::pair<std::string_view, Quantity>, 6> kExcitations = {{
      {"force", Quantity::kForce},
      {"voltage", Quantity::kVoltage},
      {"drive_voltage", Quantity::kVoltage},
      {"base_acceleration", Quantity::kBaseAcceleration},
      {"base_accel", Quantity::kBaseAcceleration},
      {"base_acc", Quantity::kBaseAcceleration},
  }};
  for (const auto& [word, quantity] : kExcitations)
    if (name == word) {
      column.role = ColumnRole::kForce;
      column.quantity = quantity;
      return column;
    }
  static const std::array<std::pair<std::string_view, ColumnRole>, 10> kGeneric = {{
      {"frequency", ColumnRole::kFrequency}, {"freq", ColumnRole::kFrequency},   {"f", ColumnRole::kFrequency},
      {"force", ColumnRole::kForce},         {"excitation", ColumnRole::kForce}, {"input", ColumnRole::kForce},
      {"response", ColumnRole::kResponse},   {"output", ColumnRole::kResponse},  {"phase", ColumnRole::kPhase},
      {"response_phase", ColumnRole::kPhase},
  }};
  static const std::array<std::pair<std::string_view, Quantity>, 8> kResponses = {{
      {"acceleration", Quantity::kAcceleration}, {"accel", Quantity::kAcceleration},
      {"acc", Quantity::kAcceleration},          {"velocity", Quantity::kVelocity},
      {"vel", Quantity::kVelocity},              {"displacement", Quantity::kDisplacement},
      {"disp", Quantity::kDisplacement},         {"amplitude", Quantity::kDisplacement},
  }};
  for (const auto& [word, role] : kGeneric)
    if (name == word) {
      column.role = role;
      return column;
    }
  for (const auto& [word, quantity] : kResponses)
    if (name == word) {
      column.role = ColumnRole::kResponse;
      // A bare "amplitude" says nothing of the quantity: its unit must.
      if (word != "amplitude") column.quantity = quantity;
      return column;
    }
  return std::nullopt;  // some other column (coherence, THD...): ignored
}

std::string_view RoleName(ColumnRole role) {
  switch (role) {
    case ColumnRole::kFrequency: return "frequency";
    case ColumnRole::kForce: return "force amplitude";
    case ColumnRole::kResponse: return "response amplitude";
    case ColumnRole::kPhase: return "phase";
  }
  return "";
}

// A few of the header's cells, printable: a table's header may be anything.
std::string HeaderExcerpt(const std::vector<HeaderCell>& cells) {
  std::string found;
  for (std::size_t i = 0; i < cells.size() && i < 12; ++i)
    found += (found.empty() ? "'" : ", '") + internal::Excerpt(cells[i].text) + "'";
  if (cells.size() > 12) found += " and " + std::to_string(cells.size() - 12) + " more";
  return found;
}

// The cell a mapping names: a 1-based column number, else the header text
// (with or without its unit, case ignored); −1 when none.
int FindMappedCell(const std::vector<HeaderCell>& cells, const std::string& wanted) {
  const std::string key = internal::Lowercase(TrimBlanksAndQuotes(wanted));
  if (!key.empty() && std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    const int number = key.size() > 6 ? 0 : std::stoi(key);
    return number >= 1 && number <= static_cast<int>(cells.size()) ? number - 1 : -1;
  }
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (internal::Lowercase(TrimBlanksAndQuotes(cells[i].text)) == key ||
        internal::Lowercase(TrimBlanksAndQuotes(cells[i].name)) == key)
      return static_cast<int>(i);
  return -1;
}

class TableParser {
 public:
  TableParser(const std::string& source, const std::string& label, const PhasorTableOptions& options)
      : source_(source), label_(label), options_(options) {}

  FirstHarmonicLevel Parse(std::string_view text) {
    TableReader table(text, source_, {.blank_lines_inside = true, .layout = options_.layout});
    if (!table.HasHeader()) Fail("", "the table is empty", "write a header line and one row per frequency step");
    ReadHeader(table.Header());
    std::vector<std::array<double, 8>> rows;
    while (table.NextRow()) rows.push_back(ReadRow(table));
    if (rows.size() < 3)
      Fail("", "only " + std::to_string(rows.size()) + " data rows", "a level needs at least 3 frequency steps");
    return MakeLevel(rows);
  }

  // The table as a .mat or HDF5 file (signal/array_file.h): one vector per
  // column, named as a CSV header names it ("frequency_Hz", "phase_deg"); a
  // unit the file gives (an HDF5 "units" attribute, a .mat <name>_units) is
  // the column's unit, as a units row's is. Element i of every vector is step i.
  FirstHarmonicLevel ParseArrays(ArrayFile& file) {
    std::vector<HeaderCell> cells;
    std::vector<const ArrayInfo*> arrays;
    for (const ArrayInfo& array : file.Arrays()) {
      if (array.root_attribute || array.kind == ArrayKind::kText) continue;  // metadata, <name>_units
      cells.push_back({.text = array.name, .name = array.name, .unit = array.unit,
                       .unit_line = array.unit.empty() ? 0 : 1});
      arrays.push_back(&array);
    }
    if (cells.empty())
      Fail("", "the " + file.FormatName() + " holds no numeric " + std::string(file.ArrayWord()),
           "save one vector per column: frequency_Hz, force_N, acceleration_m_s2 (or another response), phase_deg");
    ReadHeader(cells);
    std::vector<std::vector<double>> values;
    for (const Column& c : columns_) {
      const ArrayInfo& array = *arrays[static_cast<std::size_t>(c.index)];
      if (array.kind != ArrayKind::kReal)
        Fail(c.header, "holds " + array.type + " values, not real numbers",
             "save the column as a vector of double or single precision numbers (amplitude and phase, not complex)");
      if (!array.IsVector() || array.dims.empty())
        Fail(c.header, "is a " + array.Shape() + " array, not a vector", "save one vector per column, a value a step");
      if (!values.empty() && array.NumElements() != values.front().size())
        Fail(c.header,
             "holds " + std::to_string(array.NumElements()) + " values but '" + columns_.front().header + "' holds " +
                 std::to_string(values.front().size()),
             "give every column one value per frequency step");
      values.push_back(file.ReadReal(array));
    }
    const std::size_t num_steps = values.front().size();
    if (num_steps < 3)
      Fail("", "only " + std::to_string(num_steps) + " steps", "a level needs at least 3 frequency steps");
    std::vector<std::array<double, 8>> rows(num_steps);
    for (std::size_t i = 0; i < num_steps; ++i)
      for (std::size_t k = 0; k < columns_.size(); ++k)
        Store(columns_[k], values[k][i], "element " + std::to_string(i + 1), internal::FormatNumber(values[k][i]),
              rows[i]);
    return MakeLevel(rows);
  }

 private:
  [[noreturn]] void Fail(const std::string& column, const std::string& problem, const std::string& fix) const {
    throw InputError(source_, "", column.empty() ? problem : "column '" + column + "': " + problem, fix);
  }

  // The columns the options map, by number or header text, whatever their
  // names say: an export's "X-Data [Hz]" or "Laser (M - Filtered) [m/s]".
  // The quantity of a mapped response or excitation is its name's when the
  // name says one, else its unit's.
  std::vector<int> MapColumns(const std::vector<HeaderCell>& cells) {
    std::vector<int> mapped;
    const std::pair<const std::string*, ColumnRole> mappings[] = {
        {&options_.columns.frequency, ColumnRole::kFrequency},
        {&options_.columns.excitation, ColumnRole::kForce},
        {&options_.columns.response, ColumnRole::kResponse},
        {&options_.columns.phase, ColumnRole::kPhase}};
    for (const auto& [wanted, role] : mappings) {
      if (wanted->empty()) continue;
      const int i = FindMappedCell(cells, *wanted);
      if (i < 0)
        Fail("", "the " + std::string(RoleName(role)) + " is mapped to column '" + internal::Excerpt(*wanted) +
                     "', which the header does not hold (" + std::to_string(cells.size()) + " columns: " +
                     HeaderExcerpt(cells) + ")",
             "map it to a header text as written or to a column number from 1");
      if (std::find(mapped.begin(), mapped.end(), i) != mapped.end())
        Fail(cells[static_cast<std::size_t>(i)].text, "mapped to two roles", "map each column to one role");
      const auto& cell = cells[static_cast<std::size_t>(i)];
      const auto named = Classify(cell, i);
      const std::string unit = cell.unit_line > 0 ? cell.unit : SplitNameAndUnit(cell.text).second;
      Column column{.header = cell.text, .role = role, .unit = unit, .index = i};
      if (named && !named->is_std && named->role == role) column.quantity = named->quantity;
      columns_.push_back(column);
      mapped.push_back(i);
    }
    return mapped;
  }

  void ReadHeader(const std::vector<HeaderCell>& cells) {
    num_cells_ = static_cast<int>(cells.size());
    const std::vector<int> mapped = MapColumns(cells);
    for (int i = 0; i < num_cells_; ++i) {
      if (std::find(mapped.begin(), mapped.end(), i) != mapped.end()) continue;
      const auto column = Classify(cells[static_cast<std::size_t>(i)], i);
      if (!column) continue;
      // A role mapped by the options takes no other column by name (its uncertainty still does).
      if (!column->is_std && Main(column->role) != nullptr && std::find(mapped.begin(), mapped.end(),
                                                                         Main(column->role)->index) != mapped.end())
        continue;
      for (const auto& other : columns_)
        if (other.role == column->role && other.is_std == column->is_std)
          Fail(column->header,
               "a second column for the " + std::string(RoleName(column->role)) + (column->is_std ? "'s uncertainty" : "") +
                   " (the first is '" + other.header + "')",
               "keep one of them or rename the other");
      columns_.push_back(*column);
    }
    for (ColumnRole role : {ColumnRole::kFrequency, ColumnRole::kForce, ColumnRole::kResponse, ColumnRole::kPhase}) {
      if (Main(role) != nullptr) continue;
      Fail(std::string(RoleName(role)), "missing (the header has " + HeaderExcerpt(cells) + ")",
           "name the columns frequency_Hz, force_N (or voltage_V, base_acceleration_m_s2), one of "
           "acceleration_m_s2 / velocity_m_s / "
           "displacement_m (or response [unit]), and phase_rad or phase_deg (docs/phasor-table.md); or, for an "
           "export's own names, map them (--column ROLE=COLUMN), and skip a metadata block above the header "
           "(--lines-before-header N)");
    }
    ResolveUnits();
  }

  double UnitFactor(const Column& column) const {
    const std::optional<std::string> unit =
        column.unit.empty() ? std::optional<std::string>("") : PhasorTableUnit(column.unit);
    auto unknown = [&](const std::string& accepted) {
      Fail(column.header, "unknown unit '" + column.unit + "'", "use one of: " + accepted);
    };
    // An amplitude without unit is in its quantity's SI unit.
    auto quantity_factor = [&](Quantity q) {
      if (unit && unit->empty()) return 1.0;
      const auto factor = unit ? UnitToSiFactor(q, *unit) : std::nullopt;
      if (!factor) unknown(AcceptedUnits(q) + " (for a " + std::string(QuantityName(q)) + ")");
      return *factor;
    };
    switch (column.role) {
      case ColumnRole::kFrequency:
        if (!unit || (*unit != "" && *unit != "Hz" && *unit != "rad/s")) unknown("Hz, rad/s");
        return *unit == "rad/s" ? 1.0 / (2 * std::numbers::pi) : 1.0;
      case ColumnRole::kForce: return quantity_factor(*excitation_quantity_);
      case ColumnRole::kPhase:
        if (!unit || (*unit != "rad" && *unit != "deg")) {
          if (column.unit.empty())
            Fail(column.header, "the phase has no unit", "write phase_rad or phase_deg (or phase [deg])");
          unknown("rad, deg");
        }
        return *unit == "deg" ? std::numbers::pi / 180 : 1.0;
      case ColumnRole::kResponse: return quantity_factor(*response_quantity_);
    }
    return 1.0;
  }

  void ResolveUnits() {
    const Column& response = *Main(ColumnRole::kResponse);
    response_quantity_ = response.quantity;
    if (!response_quantity_) {
      const auto unit = PhasorTableUnit(response.unit);
      for (Quantity q : {Quantity::kAcceleration, Quantity::kVelocity, Quantity::kDisplacement})
        if (unit && UnitToSiFactor(q, *unit)) response_quantity_ = q;
      if (!response_quantity_)
        Fail(response.header,
             response.unit.empty() ? "neither the name nor a unit says which quantity the response is"
                                   : "unknown unit '" + response.unit + "'",
             "name it acceleration, velocity or displacement, or give its unit: m/s^2, g, m/s, mm/s, m or mm");
    }
    // The excitation: named (force, voltage, base_acceleration), else said by
    // the unit of an "excitation" or "input" column, else a force.
    const Column& excitation = *Main(ColumnRole::kForce);
    excitation_quantity_ = excitation.quantity;
    if (!excitation_quantity_) {
      excitation_quantity_ = Quantity::kForce;
      const auto unit = PhasorTableUnit(excitation.unit);
      for (Quantity q : {Quantity::kVoltage, Quantity::kBaseAcceleration})
        if (unit && UnitToSiFactor(q, *unit)) excitation_quantity_ = q;
    }
    if (excitation_quantity_ == Quantity::kBaseAcceleration && response_quantity_ != Quantity::kAcceleration)
      Fail(response.header,
           "with a base acceleration as excitation the response must be an acceleration (its motion relative to the "
           "base is the mode's), not a " + std::string(QuantityName(*response_quantity_)),
           "give the accelerometer's amplitude and phase relative to the base acceleration");
    for (const auto& c : columns_) {
      // An uncertainty column in another unit than its value is a typo waiting to happen: same rules.
      factor_[static_cast<int>(c.role) + (c.is_std ? 4 : 0)] = UnitFactor(c);
    }
  }

  std::array<double, 8> ReadRow(const TableReader& table) const {
    const int line_number = table.Line();
    const auto& cells = table.Cells();
    if (static_cast<int>(cells.size()) < num_cells_)
      Fail("", table.Format().Describe() + ": line " + std::to_string(line_number) + " has " +
                   std::to_string(cells.size()) + " cells, the header " + std::to_string(num_cells_),
           "give every row a value in every column");
    std::array<double, 8> values{};
    for (const auto& c : columns_) {
      const auto index = static_cast<std::size_t>(c.index);
      const std::string cell(table.CellText(index));
      double value = 0.0;
      if (!table.Number(index, value))
        throw InputError(source_, "", table.NotANumber(index, "'" + c.header + "'"),
                         table.Format().decimal_mark == ','
                             ? "write a number there with ',' as the decimal mark (as the rest of the file), or drop the row"
                             : "write a number there or drop the row");
      Store(c, value, "line " + std::to_string(line_number), cell, values);
    }
    return values;
  }

  // A column's value at `where` (a CSV line, a vector's element) checked and
  // stored in SI into its slot of the row; `cell` is the value as written.
  void Store(const Column& c, double value, const std::string& where, const std::string& cell,
             std::array<double, 8>& row) const {
    if (!std::isfinite(value))
      Fail(c.header, where + ": '" + cell + "' is not a finite number", "write a number there or drop the row");
    const int slot = static_cast<int>(c.role) + (c.is_std ? 4 : 0);
    if ((c.is_std && value < 0) || (!c.is_std && c.role != ColumnRole::kPhase && value <= 0))
      Fail(c.header, where + ": " + cell + (c.is_std ? " is negative" : " is not positive"),
           "frequencies and amplitudes are positive, uncertainties not negative");
    row[static_cast<std::size_t>(slot)] = value * factor_[static_cast<std::size_t>(slot)];
  }

  FirstHarmonicLevel MakeLevel(const std::vector<std::array<double, 8>>& rows) const {
    FirstHarmonicLevel level{.label = label_, .source = source_,
                             .channel = Main(ColumnRole::kResponse)->header,
                             .response_quantity = *response_quantity_,
                             .excitation_quantity = *excitation_quantity_};
    for (const auto& r : rows) {
      FirstHarmonicPoint p;
      p.frequency_hz = r[0];
      p.frequency_std_hz = r[4];
      p.force.value = r[1];
      p.force.std_real = r[5];
      const double amplitude = r[2], phase = r[3];
      p.response.value = std::polar(amplitude, phase);
      const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(phase).toRotationMatrix();
      const Eigen::Vector2d polar_std(r[6], amplitude * r[7]);
      p.response.SetCovariance(rotation * polar_std.cwiseAbs2().asDiagonal() * rotation.transpose());
      if (level.excitation_quantity == Quantity::kBaseAcceleration) ReferToBase(p.response, p.force);
      level.points.push_back(p);
    }
    return level;
  }

  std::string source_, label_;
  PhasorTableOptions options_;
  int num_cells_ = 0;
  const Column* Main(ColumnRole role) const {
    for (const auto& c : columns_)
      if (c.role == role && !c.is_std) return &c;
    return nullptr;
  }

  std::vector<Column> columns_;
  std::array<double, 8> factor_{1, 1, 1, 1, 1, 1, 1, 1};
  std::optional<Quantity> response_quantity_;
  std::optional<Quantity> excitation_quantity_;
};

}  // namespace

bool PhasorColumnMapping::Empty() const {
  return frequency.empty() && excitation.empty() && response.empty() && phase.empty();
}

void PhasorColumnMapping::Assign(std::string_view assignment) {
  const auto equals = assignment.find('=');
  const std::string role = internal::Lowercase(TrimBlanksAndQuotes(assignment.substr(0, equals)));
  const std::string column = equals == std::string_view::npos ? "" : TrimBlanksAndQuotes(assignment.substr(equals + 1));
  std::string* target = role == "frequency"    ? &frequency
                        : role == "excitation" ? &excitation
                        : role == "response"   ? &response
                        : role == "phase"      ? &phase
                                               : nullptr;
  const std::string given = "--column " + internal::Excerpt(assignment);
  if (!target || column.empty())
    throw InputError(given + ": not ROLE=COLUMN. Fix: ROLE is frequency, excitation, response or phase; COLUMN the "
                     "header text as written or a column number from 1 (--column 'response=Laser (M - Filtered) "
                     "[m/s]')");
  if (!target->empty())
    throw InputError(given + ": the " + role + " is already mapped to '" + *target + "'. Fix: map each role once");
  *target = column;
}

FirstHarmonicLevel ParsePhasorTable(std::string_view text, const std::string& source, const std::string& label,
                                    const PhasorTableOptions& options) {
  return TableParser(source, label, options).Parse(text);
}

FirstHarmonicLevel ReadPhasorTable(const std::filesystem::path& file, const PhasorTableOptions& options) {
  if (IsArrayFile(file))
    return TableParser(file.string(), file.stem().string(), options).ParseArrays(*OpenArrayFile(file, file.string()));
  return ParsePhasorTable(ReadTextFile(file, "phasor table", "check the path"), file.string(), file.stem().string(),
                          options);
}

}  // namespace beamid::signal
