#include "signal/quantity.h"

#include <array>
#include <stdexcept>

namespace beamid::signal {
namespace {

struct UnitEntry {
  Quantity quantity;
  std::string_view unit;
  double to_si;
};

constexpr double kStandardGravity_m_s2 = 9.80665;

constexpr std::array<UnitEntry, 11> kUnits = {{
    {Quantity::kForce, "N", 1.0},
    {Quantity::kAcceleration, "m/s^2", 1.0},
    {Quantity::kAcceleration, "g", kStandardGravity_m_s2},
    {Quantity::kVelocity, "m/s", 1.0},
    {Quantity::kVelocity, "mm/s", 1e-3},
    {Quantity::kDisplacement, "m", 1.0},
    {Quantity::kDisplacement, "mm", 1e-3},
    {Quantity::kVoltage, "V", 1.0},
    {Quantity::kVoltage, "mV", 1e-3},
    {Quantity::kBaseAcceleration, "m/s^2", 1.0},
    {Quantity::kBaseAcceleration, "g", kStandardGravity_m_s2},
}};

}  // namespace

std::string_view QuantityName(Quantity quantity) {
  const std::string_view name = schema::NameOf(quantity, kQuantityNames);
  return name.empty() ? "unknown" : name;
}

std::optional<Quantity> ParseQuantity(std::string_view name) {
  for (const auto& [q, n] : kQuantityNames)
    if (n == name) return q;
  return std::nullopt;
}

std::string_view SiUnit(Quantity quantity) {
  for (const auto& entry : kUnits)
    if (entry.quantity == quantity && entry.to_si == 1.0) return entry.unit;
  return "";
}

std::optional<double> UnitToSiFactor(Quantity quantity, std::string_view unit) {
  for (const auto& entry : kUnits)
    if (entry.quantity == quantity && entry.unit == unit) return entry.to_si;
  return std::nullopt;
}

std::string AcceptedUnits(Quantity quantity) {
  std::string list;
  for (const auto& entry : kUnits) {
    if (entry.quantity != quantity) continue;
    if (!list.empty()) list += ", ";
    list += entry.unit;
  }
  return list;
}

int DerivativeOrder(Quantity quantity) {
  switch (quantity) {
    case Quantity::kDisplacement: return 0;
    case Quantity::kVelocity: return 1;
    case Quantity::kAcceleration:
    case Quantity::kBaseAcceleration: return 2;
    case Quantity::kForce:
    case Quantity::kVoltage: break;
  }
  throw std::invalid_argument("a " + std::string(QuantityName(quantity)) +
                              " is not a time derivative of a displacement; it cannot be converted");
}

bool IsExcitationQuantity(Quantity quantity) {
  return quantity == Quantity::kForce || quantity == Quantity::kVoltage || quantity == Quantity::kBaseAcceleration;
}

bool IsResponseQuantity(Quantity quantity) {
  return quantity == Quantity::kAcceleration || quantity == Quantity::kVelocity ||
         quantity == Quantity::kDisplacement;
}

}  // namespace beamid::signal
