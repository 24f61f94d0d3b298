// Candidate physics: the effects a real test holds that the base model (the
// polynomial support M = k1·θ + k2·θ² + k3·θ³ + c·θ̇ on the nominal beam with
// its loss factor η) leaves out. Each candidate is a NESTED extension of the
// base: its extra parameters at their base values (jenkins stiffness → 0,
// clamp compliance 0, added mass 0, EI scale 1, one-sided stiffness 0, more
// harmonics) give back the base model, so a likelihood-ratio test compares
// the two:
//     Λ = (χ²_base − χ²_candidate) / s²  ~  χ²(q)  under the base,
// q the extra parameters, s² = max(1, χ²_candidate/dof) (quasi-likelihood:
// the scatter is trusted only when it is worse than the stated uncertainties).
//
// Each candidate also states the signature it leaves in the base fit's
// residuals (solver/misfit_location.h), as a score in [0, 1]: a ranking hint
// before the refits, which decide.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "solver/estimation/fit_data.h"
#include "solver/diagnosis/misfit_location.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_structure.h"

namespace beamid::solver {

// What a candidate may look at to extend the fitted base model.
struct BaseFitContext {
  const FitData* data = nullptr;
  // Largest first-harmonic support rotation |Θ₁| of every step at the base fit [rad].
  std::vector<double> theta_amplitude_rad;
  int model_harmonics = 5;  // H of the base model
};

struct CandidateExtension {
  ModelStructure structure;                 // base parameters first, then the extra ones
  std::vector<std::string> extra_parameters;
  // Starts of the refit (physical values, structure order): the base optimum
  // with the extra parameters at one or more plausible sizes.
  std::vector<std::vector<double>> starts;
  // H of the refit. A candidate with parameters of its own balanced with
  // more harmonics than the base is tested against the refit with no
  // parameters of its own at the same H (HarmonicTruncation), when there is one.
  int model_harmonics = 5;
  // Extra degrees of freedom of the likelihood-ratio test (the parameter
  // count; 1 for an extension with no parameter of its own, see
  // HarmonicTruncation).
  int test_dof = 0;
};

struct CandidatePhysics {
  std::string name;         // one of the names of CandidateNames() (support_friction, …)
  std::string description;  // what it is, in a test engineer's words
  std::string rig_check;    // what to check or do on the rig when it is named
  // Extends the base structure (its values are the base optimum).
  std::function<CandidateExtension(const ModelStructure& base, const BaseFitContext& context)> extend;
  // How well the located misfit matches the candidate's signature, 0..1.
  std::function<double(const MisfitLocation& location)> signature;
  // The check for the fitted parameters (their names and values), when it
  // depends on them; empty: rig_check as it stands.
  std::function<std::string(const std::vector<ParameterEstimate>& fitted)> rig_check_for;
};

// Friction at the support: a Jenkins element (spring k_t in series with a
// Coulomb slider slipping at M_slip) in parallel with the polynomial; the
// base's k1 is shared between the two at the start. Signature: quadrature
// (dissipation) misfit near resonance that grows with level, a loop whose
// equivalent damping changes with amplitude.
CandidatePhysics SupportFriction();
// A rotational spring at the clamp (x = 0), compliance 1/k_clamp from 0:
// shifts the mode shapes (the sensors' amplitude ratios), in phase, at every level alike.
CandidatePhysics ClampCompliance();
// An unreported point mass (a cable clamp, a sensor or the shaker's moving
// part heavier than stated) of unknown mass and position.
CandidatePhysics AddedMass();
// Masses at the instruments heavier than campaign.json states, one unknown
// mass per site at fixed positions: the drive point (the shaker's moving
// part, the force transducer) and every fitted accelerometer (the sensor, its
// cable and glue) — the usual suspects, which one mass of free position
// cannot represent when several sites are off.
CandidatePhysics InstrumentMasses();
// A bending stiffness EI different from the nominal one (modulus, thickness).
CandidatePhysics ModulusError();
// A support stiffer for one sense of rotation than for the other:
// M_extra = k_a·max(θ, 0) (a contact whose patch grows when the beam rotates
// into the rod). Even harmonics whose share does not grow with amplitude, which
// k2·θ² cannot follow over several levels. Its kink has slowly decaying
// harmonics: it is balanced with as many as HarmonicTruncation (2H + 1, at
// least 9).
CandidatePhysics SupportAsymmetry();
// Content beyond the modelled harmonics: the same law with more harmonics in
// the balance (2H + 1, at least 9; no new parameter).
CandidatePhysics HarmonicTruncation();

// All of the above, in a fixed order (instrument_masses after added_mass).
std::vector<CandidatePhysics> CandidateLibrary();

// Names accepted by diagnose: "none" and the library's.
std::vector<std::string> CandidateNames();

}  // namespace beamid::solver
