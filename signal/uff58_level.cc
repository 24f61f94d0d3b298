#include "signal/uff58_level.h"

#include <cmath>
#include <complex>
#include <optional>

#include <fmt/core.h>

#include "signal/input_error.h"
#include "signal/internal/text.h"
#include "signal/table_reader.h"

namespace beamid::signal {
namespace {

using namespace uff58;

// The steps' frequencies agree between the force and the response to the
// six digits a single-precision export (E13.5) keeps.
constexpr double kSameFrequency = 1e-5;

struct Role {
  const Uff58Dataset* dataset = nullptr;
  Quantity quantity = Quantity::kForce;
  double to_si = 1.0;  // of the ordinate (a frequency response: numerator over denominator)
};

[[noreturn]] void Fail(const std::string& source, const std::string& problem, const std::string& fix) {
  throw InputError(source, "", problem, fix);
}

std::string Name(const Uff58Dataset& d) {
  return d.id_lines[0].empty() ? d.NodeDirection() : std::string(internal::Excerpt(d.id_lines[0]));
}

// The quantity a record 9 or 10 states by its specific data type, else by its unit.
std::optional<Quantity> QuantityOf(const Uff58Axis& axis) {
  if (const auto named = Uff58Quantity(axis.data_type)) return named;
  const std::string unit = Uff58Unit(axis.unit);
  for (Quantity q : {Quantity::kForce, Quantity::kAcceleration, Quantity::kVelocity, Quantity::kDisplacement})
    if (UnitToSiFactor(q, unit)) return q;
  return std::nullopt;
}

double ToSi(const std::string& source, const Uff58Dataset& d, const Uff58Axis& axis, Quantity q, const char* record) {
  if (axis.unit.empty()) return 1.0;
  const auto factor = UnitToSiFactor(q, Uff58Unit(axis.unit));
  if (!factor)
    Fail(source,
         d.Describe() + ": " + record + " gives the unit '" + internal::Excerpt(axis.unit) + "', not one of " +
             std::string(QuantityName(q)),
         "export the " + std::string(QuantityName(q)) + " in " + AcceptedUnits(q));
  return *factor;
}

void CheckFrequencyAxis(const std::string& source, const Uff58Dataset& d) {
  const Uff58Axis& x = d.abscissa;
  if (x.data_type != kUnknownType && x.data_type != kGeneralType && x.data_type != kFrequencyType)
    Fail(source, d.Describe() + ": the abscissa (record 8) is of specific data type " + std::to_string(x.data_type) +
                     ", not a frequency (18)",
         "export the spectra and frequency responses over frequency");
  if (!x.unit.empty() && NormaliseUnit(x.unit) != std::optional<std::string>("Hz"))
    Fail(source, d.Describe() + ": the abscissa's unit is '" + internal::Excerpt(x.unit) + "', not Hz",
         "export the frequencies in Hz");
}

}  // namespace

FirstHarmonicLevel FirstHarmonicLevelFromUff58(const std::vector<Uff58Dataset>& datasets, const std::string& source,
                                               const std::string& label) {
  std::optional<Role> force, response;
  std::string found;
  for (const Uff58Dataset& d : datasets) {
    if (d.function_type != kFrequencyResponse && d.function_type != kSpectrum) continue;
    found += (found.empty() ? "" : ", ") + d.Describe();
    CheckFrequencyAxis(source, d);
    const std::optional<Quantity> q = QuantityOf(d.ordinate);
    if (!q)
      Fail(source, d.Describe() + ": record 9 says neither by its specific data type (" +
                       std::to_string(d.ordinate.data_type) + ") nor by its unit ('" +
                       internal::Excerpt(d.ordinate.unit) + "') what the values are",
           "export it with its data type (8 displacement, 11 velocity, 12 acceleration, 13 force) or its unit");
    Role role{.dataset = &d, .quantity = *q, .to_si = ToSi(source, d, d.ordinate, *q, "record 9")};
    if (d.function_type == kFrequencyResponse) {
      if (*q == Quantity::kForce || QuantityOf(d.denominator) != std::optional<Quantity>(Quantity::kForce))
        Fail(source, d.Describe() + ": a frequency response that is not a response (record 9) per force (record 10)",
             "export the response's frequency response to the force (e.g. acceleration per N)");
      role.to_si /= ToSi(source, d, d.denominator, Quantity::kForce, "record 10");
    }
    std::optional<Role>& slot = *q == Quantity::kForce ? force : response;
    if (slot)
      Fail(source, "two datasets hold the " + std::string(*q == Quantity::kForce ? "force" : "response") + ": " +
                       slot->dataset->Describe() + " and " + d.Describe(),
           "export one level's force spectrum and one response per file");
    slot = role;
  }
  if (found.empty())
    Fail(source, "no spectrum or frequency response (function type 12 or 4) among its " +
                     std::to_string(datasets.size()) + " datasets 58" +
                     (datasets.empty() ? "" : " (the first of function type " +
                                                  std::to_string(datasets.front().function_type) + ")"),
         "give a stepped sine's result (the force's spectrum and the response's spectrum or frequency response); a "
         "universal file of time histories is one step's recording: give its campaign folder");
  if (!response)
    Fail(source, "no response spectrum or frequency response among " + found,
         "export the response's spectrum or its frequency response to the force into the same file");
  if (!force)
    Fail(source,
         "no force spectrum beside " + response->dataset->Describe() +
             ": a frequency response alone does not say the force a nonlinear level was measured at",
         "export the force's spectrum (function type 12, at the reference DOF) into the same file");
  const Uff58Dataset& x = *response->dataset;
  const Uff58Dataset& f = *force->dataset;
  if (x.num_points != f.num_points)
    Fail(source, x.Describe() + " has " + std::to_string(x.num_points) + " steps, " + f.Describe() + " " +
                     std::to_string(f.num_points),
         "export the force and the response over the same steps");
  FirstHarmonicLevel level{.label = label,
                           .source = source,
                           .channel = Name(x),
                           .response_quantity = response->quantity,
                           .excitation_quantity = Quantity::kForce};
  for (int i = 0; i < x.num_points; ++i) {
    const double frequency = x.Abscissa(i);
    if (!(frequency > 0) || !std::isfinite(frequency) ||
        !(std::abs(f.Abscissa(i) - frequency) <= kSameFrequency * frequency))
      Fail(source, fmt::format("step {}: {} is at {:.9g} Hz, {} at {:.9g} Hz", i + 1, x.Describe(), frequency,
                               f.Describe(), f.Abscissa(i)),
           "export the force and the response over the same positive frequencies");
    const std::complex<double> force_si = f.Ordinate(i) * force->to_si;
    std::complex<double> response_si = x.Ordinate(i) * response->to_si;
    if (x.function_type == kFrequencyResponse) response_si *= force_si;
    if (!std::isfinite(std::abs(force_si)) || !std::isfinite(std::abs(response_si)) || !(std::abs(force_si) > 0))
      Fail(source, fmt::format("step {} ({:.9g} Hz): the force or the response is not a finite number, or the force "
                               "is zero", i + 1, frequency),
           "export the steps the test measured");
    // The force as the phase reference: real and positive.
    const std::complex<double> turn = std::conj(force_si) / std::abs(force_si);
    FirstHarmonicPoint p{.frequency_hz = frequency};
    p.force.value = std::abs(force_si);
    p.response.value = response_si * turn;
    level.points.push_back(p);
  }
  if (level.points.size() < 3)
    Fail(source, "only " + std::to_string(level.points.size()) + " steps", "a level needs at least 3 frequency steps");
  return level;
}

FirstHarmonicLevel ReadUff58Level(const std::filesystem::path& file) {
  return FirstHarmonicLevelFromUff58(ReadUff58(file, Uff58Functions::kFrequencyFunctions), file.string(),
                                     file.stem().string());
}

}  // namespace beamid::signal
