// A model family: one way of computing the beam's periodic steady state
// with its support, e.g. the exact harmonic balance of the clamped beam
// (IdentificationProblem: per step the harmonics Θ_0..Θ_H of the support
// rotation θ = y'(L), with D(kω)·Θ_k + M_k(Θ) = B(kω)·F_k) or the seed's
// method of multiple scales (MultipleScalesProblem: per step the modal
// phasor U of the first mode, with the solvability condition S(U) = 0).
// Everything that identify, predict, diagnose and report need of a model
// goes through this interface — build the fit problem, name and size its
// state, rebuild the identified model's response at any position — so a
// new family (another beam damping law, say) is one new file implementing
// it and its StepModel (solver/estimation/stepped_fit_problem.h: what the
// family knows of one step; the fit problem is assembled from it) and one
// line in ModelFamilies().
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hb/enum_names.h"
#include "solver/estimation/model_options.h"

namespace beamid::solver {

struct FitData;
class FitProblem;
struct IdentifiedModel;
struct ModelStructure;
struct SensorBackbonePoint;  // solver/estimation/sensor_backbone.h

// The model's first-harmonic response under a pure sine force, as a report
// draws it: points in continuation order (a fold goes back in frequency).
struct ModelResponsePoint {
  double omega_rad_s = 0.0;
  bool stable = true;
  Eigen::MatrixXcd displacement_m;  // Y_0..Y_K (columns) at each position asked for (rows)
};
struct ModelResponse {
  std::vector<ModelResponsePoint> points;
  bool reached_end = true;  // false: the curve stops short of omega_end
  std::string message;      // why, when it does
};

// The families, by the key of result.json's "model.kind", prediction.json's
// "model" and `--model`.
enum class ModelKind { kHarmonicBalance, kMultipleScales };
inline constexpr schema::Name<ModelKind> kModelKindNames[] = {{ModelKind::kHarmonicBalance, "hb"},
                                                              {ModelKind::kMultipleScales, "ms"}};

class ModelFamily {
 public:
  virtual ~ModelFamily() = default;

  virtual ModelKind Kind() const = 0;
  // Kind()'s key ("hb", "ms").
  std::string Name() const { return std::string(schema::NameOf(Kind(), kModelKindNames)); }
  // For people: "harmonic balance".
  virtual std::string Description() const = 0;
  // result.json's name of a step's state ("theta_rad", "modal_phasor_m"),
  // and how many complex phasors it holds in a model of H harmonics.
  virtual std::string StateName() const = 0;
  virtual int StateSize(int num_harmonics) const = 0;
  // The highest harmonic the family's model gives when H is asked for.
  virtual int ModelHarmonics(int requested_harmonics) const = 0;

  // Throws InputError (or std::invalid_argument) for data or a structure
  // the family cannot hold, before any work is spent on it.
  virtual void CheckCanHold(const FitData& data, const ModelStructure& structure,
                            const ModelOptions& options) const = 0;
  virtual std::unique_ptr<FitProblem> MakeProblem(const FitData& data, const ModelStructure& structure,
                                                  const ModelOptions& options) const = 0;

  // The identified model with parameters p (structure order) at every one of
  // its steps: the displacement phasors Y_0..Y_H at position_m, on the branch
  // of the step's fitted state. converged[i] (when given) says whether step i
  // has a steady state.
  virtual std::vector<Eigen::VectorXcd> DisplacementAt(const IdentifiedModel& model, const std::vector<double>& p,
                                                       double position_m, std::vector<bool>* converged) const = 0;
  // The identified model (its identified parameters) at every one of its
  // steps from the step's fitted state as it stands, not solved again:
  // the displacement phasors Y_0..Y_H at positions (positions × (H + 1)),
  // what the fit set beside the data (the report's residual map).
  virtual std::vector<Eigen::MatrixXcd> FittedDisplacements(const IdentifiedModel& model,
                                                            const std::vector<double>& positions_m) const = 0;
  // The identified model's response to a pure sine force of this amplitude
  // from omega_start to omega_end, Y_1 at positions; at most max_points
  // points. `on_fraction`, if given, is told the fraction done.
  virtual ModelResponse FrequencyResponse(const IdentifiedModel& model, double force_amplitude_N,
                                          double omega_start_rad_s, double omega_end_rad_s, int max_points,
                                          const std::vector<double>& positions_m,
                                          const std::function<void(double)>& on_fraction) const = 0;
  // The identified model's backbone at a sensor (frequency against |Y_1|,
  // solver/estimation/sensor_backbone.h), num_points over the amplitudes its
  // steps reached (from a thirtieth of the largest to 1.3 times it); empty
  // when the steps have no amplitude. Throws std::runtime_error when it
  // cannot be traced.
  virtual std::vector<SensorBackbonePoint> BackboneAtSensor(const IdentifiedModel& model, double sensor_position_m,
                                                            int num_points) const = 0;
  // The support rotation's harmonics Θ_0..Θ_H in a step's state, when the
  // family's state holds them (empty otherwise).
  virtual Eigen::VectorXcd SupportRotation_rad(const Eigen::VectorXcd& state) const = 0;
};

// Every family, in the order `--model` lists them.
std::vector<const ModelFamily*> ModelFamilies();
// The family of this name; throws InputError naming the known ones.
const ModelFamily& FindModelFamily(const std::string& name);
const ModelFamily& FindModelFamily(ModelKind kind);
// "hb, ms": for help texts and messages.
std::string ModelFamilyNames();

const ModelFamily& HarmonicBalanceFamily();  // "hb"
const ModelFamily& MultipleScalesFamily();   // "ms"

}  // namespace beamid::solver
