// The uniform Euler–Bernoulli beam of the test: geometry and material, SI.
// The beam obeys EI·y'''' + ρA·ÿ = f(x, t) (seed Eq. 1, with the load added);
// an optional structural loss factor η makes the modulus E(1 + iη) in the
// frequency domain (light material damping, η ≈ 1e-4…1e-3 for steel), and
// optional Rayleigh damping C = α·M + β·K of the beam (and of the point
// masses on it), in the frequency domain ρA·(ω² − iαω) for ρA·ω² and
// EI·(1 + iη + iβω) for EI: the other damping law a real beam may follow
// (air and joint losses grow with velocity, not with strain); and an optional
// modal loss factor η_m, the loss factor matched per mode at the harmonic that
// drives it, as time-domain codes integrate a loss factor
// (hb/matched_modal_loss.h).
#pragma once

#include <stdexcept>
#include <string>

namespace beamid::hb {

struct BeamProperties {
  double length_m = 0.600;
  double width_m = 0.040;
  double thickness_m = 0.005;
  double youngs_modulus_Pa = 2.1e11;
  double density_kg_m3 = 7850.0;
  // η: hysteretic (structural) loss factor of the material; 0 = undamped.
  double loss_factor = 0.0;
  // η_m: mode j of the beam dissipates as E(1 + iη_m) at the harmonic of the
  // drive nearest its frequency (hb/matched_modal_loss.h); 0 = none.
  double modal_loss_factor = 0.0;
  // α [1/s] and β [s] of the Rayleigh damping; 0 = none.
  double rayleigh_mass_1_s = 0.0;
  double rayleigh_stiffness_s = 0.0;

  double Area_m2() const { return width_m * thickness_m; }
  double SecondMomentOfArea_m4() const { return width_m * thickness_m * thickness_m * thickness_m / 12.0; }
  // EI [N·m²]
  double BendingStiffness_Nm2() const { return youngs_modulus_Pa * SecondMomentOfArea_m4(); }
  // ρA [kg/m]
  double MassPerLength_kg_m() const { return density_kg_m3 * Area_m2(); }

  // Throws std::invalid_argument naming the first field that is not physical
  // or lies outside what a beam test can have (the stated limits keep a
  // typing error such as 1e300 from reaching the solvers as a number).
  void Validate() const {
    auto within = [](double v, double low, double high, const char* name, const char* range) {
      if (!(v >= low && v <= high))
        throw std::invalid_argument(std::string("beam: ") + name + " = " + std::to_string(v) +
                                    " is not a beam test's (" + range + ")");
    };
    within(length_m, 1e-3, 100.0, "length_m", "1 mm to 100 m");
    within(width_m, 1e-6, length_m, "width_m", "1 µm to the length");
    within(thickness_m, 1e-6, length_m, "thickness_m", "1 µm to the length");
    within(youngs_modulus_Pa, 1e6, 1e13, "youngs_modulus_Pa", "1e6 to 1e13 Pa");
    within(density_kg_m3, 1.0, 1e5, "density_kg_m3", "1 to 1e5 kg/m³");
    if (!(loss_factor >= 0.0 && loss_factor < 1.0))
      throw std::invalid_argument("beam: loss_factor must lie in [0, 1)");
    if (!(modal_loss_factor >= 0.0 && modal_loss_factor < 1.0))
      throw std::invalid_argument("beam: modal_loss_factor must lie in [0, 1)");
    within(rayleigh_mass_1_s, 0.0, 1e4, "rayleigh_mass_1_s", "0 to 1e4 1/s");
    within(rayleigh_stiffness_s, 0.0, 1.0, "rayleigh_stiffness_s", "0 to 1 s");
  }
};

}  // namespace beamid::hb
