// The uniform Euler–Bernoulli beam of the test: geometry and material, SI.
// The beam obeys EI·y'''' + ρA·ÿ = f(x, t) (seed Eq. 1, with the load added);
// an optional structural loss factor η makes the modulus E(1 + iη) in the
// frequency domain (light material damping, η ≈ 1e-4…1e-3 for steel).
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

  double Area_m2() const { return width_m * thickness_m; }
  double SecondMomentOfArea_m4() const { return width_m * thickness_m * thickness_m * thickness_m / 12.0; }
  // EI [N·m²]
  double BendingStiffness_Nm2() const { return youngs_modulus_Pa * SecondMomentOfArea_m4(); }
  // ρA [kg/m]
  double MassPerLength_kg_m() const { return density_kg_m3 * Area_m2(); }

  // Throws std::invalid_argument naming the first field that is not physical.
  void Validate() const {
    auto positive = [](double v, const char* name) {
      if (!(v > 0.0)) throw std::invalid_argument(std::string("beam: ") + name + " must be a positive number");
    };
    positive(length_m, "length_m");
    positive(width_m, "width_m");
    positive(thickness_m, "thickness_m");
    positive(youngs_modulus_Pa, "youngs_modulus_Pa");
    positive(density_kg_m3, "density_kg_m3");
    if (!(loss_factor >= 0.0 && loss_factor < 1.0))
      throw std::invalid_argument("beam: loss_factor must lie in [0, 1)");
  }
};

}  // namespace beamid::hb
