// A model's backbone as a test engineer measures it: phase resonance of one
// sensor (its first-harmonic displacement Y_1 in quadrature with the force),
// frequency against |Y_1|, to set beside a measured backbone
// (solver/measured_backbone.h). Traced from the exact harmonic-balance
// backbone of θ (hb/backbone.h): at each of its points the force is kept and
// ω moved (secant steps, a Newton harmonic-balance solve each) until the
// sensor is in quadrature. The two definitions differ by the other modes'
// share of the response (a few mHz at the paper's first mode), which is why
// the sensor's own is computed.
#pragma once

#include <vector>

#include "hb/backbone.h"
#include "hb/linear_beam.h"
#include "hb/support_law.h"

namespace beamid::solver {

struct SensorBackbonePoint {
  double amplitude_m = 0.0;   // |Y_1| at the sensor
  double frequency_hz = 0.0;
};

// Throws std::runtime_error when the backbone cannot be traced at all.
std::vector<SensorBackbonePoint> ModelBackboneAtSensor(const hb::LinearBeamModel& beam, const hb::SupportLaw& law,
                                                       double force_position_m, double sensor_position_m,
                                                       const hb::BackboneOptions& options, int num_harmonics = 5);

// Linear interpolation in amplitude (the points in increasing amplitude);
// NaN outside their range.
double BackboneFrequencyAt_hz(const std::vector<SensorBackbonePoint>& backbone, double amplitude_m);

}  // namespace beamid::solver
