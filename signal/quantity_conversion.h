// Conversions between displacement, velocity and acceleration phasors, per
// harmonic: with x(t) = Re(X_k e^{ikωt}) (docs/fourier-convention.md) each
// time derivative multiplies X_k by ikω, so
//     X_k[to] = (ikω)^{m} · X_k[from],   m = order(to) − order(from)
// (order: displacement 0, velocity 1, acceleration 2; m < 0 integrates).
// The covariance of (Re, Im) is rotated by arg (ikω)^m and scaled by |kω|^{2m}.
// The mean X_0 of a derivative is 0 and that of an integral is unknown: a
// converted channel has mean 0. Force cannot be converted.
#pragma once

#include <complex>

#include "signal/phasor_set.h"
#include "signal/quantity.h"

namespace beamid::signal {

// (ikω)^order for harmonic k ≥ 1; ω > 0.
std::complex<double> DerivativeFactor(int harmonic, double omega_rad_s, int order);

HarmonicPhasor ConvertHarmonic(const HarmonicPhasor& phasor, Quantity from, Quantity to, double omega_rad_s);

// All harmonics of a channel; THD is recomputed (it depends on the quantity),
// snr_db is kept (a property of the recording), noise_rms becomes 0 (not
// defined for a converted quantity).
ChannelPhasors ConvertChannel(const ChannelPhasors& channel, Quantity to, double omega_rad_s);

}  // namespace beamid::signal
