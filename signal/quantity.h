// Physical quantities a campaign channel carries and the units the campaign
// format (stepped-sine-campaign/1) accepts for each:
//     force N;  acceleration m/s^2, g (= 9.80665 m/s^2);  velocity m/s, mm/s;
//     displacement m, mm;  and for an excitation other than a force:
//     voltage V, mV (the amplifier's drive signal);  base_acceleration m/s^2, g
//     (the clamp's own acceleration, for a base-excited beam).
// A value v in unit u is v·UnitToSiFactor(q, u) in SI. Inside beamid every
// number is SI.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "hb/enum_names.h"

namespace beamid::signal {

enum class Quantity { kForce, kAcceleration, kVelocity, kDisplacement, kVoltage, kBaseAcceleration };
inline constexpr schema::Name<Quantity> kQuantityNames[] = {
    {Quantity::kForce, "force"},
    {Quantity::kAcceleration, "acceleration"},
    {Quantity::kVelocity, "velocity"},
    {Quantity::kDisplacement, "displacement"},
    {Quantity::kVoltage, "voltage"},
    {Quantity::kBaseAcceleration, "base_acceleration"},
};

// "force", "acceleration", "velocity", "displacement", "voltage",
// "base_acceleration" (the campaign's words).
std::string_view QuantityName(Quantity quantity);
std::optional<Quantity> ParseQuantity(std::string_view name);

// The SI unit every value of the quantity is stored in: "N", "m/s^2", "m/s", "m".
std::string_view SiUnit(Quantity quantity);

// Factor to SI, or nullopt when the unit is not one the format accepts for
// this quantity (e.g. "mm" for an acceleration).
std::optional<double> UnitToSiFactor(Quantity quantity, std::string_view unit);

// "m/s^2, g": the accepted units of a quantity, for error messages.
std::string AcceptedUnits(Quantity quantity);

// Number of time derivatives from displacement: displacement 0, velocity 1,
// acceleration and base acceleration 2. Force and voltage have none (throws
// std::invalid_argument).
int DerivativeOrder(Quantity quantity);

// What may drive a campaign: a force, a voltage or a base acceleration.
bool IsExcitationQuantity(Quantity quantity);
// What a response sensor may measure: acceleration, velocity, displacement.
bool IsResponseQuantity(Quantity quantity);

}  // namespace beamid::signal
