// excitation.quantity "base_acceleration" (docs/simulator.md): the clamp and
// the support rod move together with a_b(t). The simulated accelerometers
// (absolute: relative + a_b) must match the exact harmonic response of the
// same FE model under the inertial load −M·r·a_b, below, at and above the
// first resonance; campaign.json names the base channel; the reader refuses
// what base excitation cannot hold.
#include <cmath>
#include <complex>
#include <filesystem>
#include <numbers>
#include <string>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "tests/support/json_file.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

constexpr double kBase_m_s2 = 2.0;
constexpr double kK1_Nm_rad = 150.0;
constexpr double kC_Nms_rad = 0.3;

const std::string kScenario = R"({
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.0e11,
           "density_kg_m3": 7850},
  "support": {"polynomial": {"k1_Nm_rad": 150, "c_Nms_rad": 0.3}},
  "attachments": {"point_masses": [{"position_m": 0.45, "mass_kg": 0.03}]},
  "excitation": {"channel": "base", "quantity": "base_acceleration"},
  "sensors": [{"channel": "acc3", "position_m": 0.57}, {"channel": "acc1", "position_m": 0.1, "unit": "g"}],
  "levels": [{"label": "below", "base_acceleration_amplitude_m_s2": 2.0, "frequencies_Hz": [40.0]},
             {"label": "at", "base_acceleration_amplitude_m_s2": 2.0, "frequencies_Hz": [52.8]},
             {"label": "above", "base_acceleration_amplitude_m_s2": 2.0, "frequencies_Hz": [70.0]}],
  "timing": {"sample_rate_Hz": 4096, "settle_min_s": 0.2, "settle_max_s": 4.0, "settle_tolerance": 1e-6,
             "transient_s": 0.05, "record_s": 0.5}
})";

std::complex<double> Harmonic(const nlohmann::json& phasors, int k) {
  const auto& h = phasors.at("harmonics").at(k - 1);
  return {h.at(0).get<double>(), h.at(1).get<double>()};
}

TEST(BaseExcitation, AccelerometersMatchTheExactHarmonicResponseOfTheMovingBase) {
  const std::filesystem::path directory = beamid::testing::UniqueTempPath("beamid_base");
  std::filesystem::remove_all(directory);
  const Scenario scenario = ParseScenario(kScenario, "base.json");
  beamid::testing::SimulateInto(scenario, directory);
  const nlohmann::json campaign = beamid::testing::ReadJsonFile(directory / "campaign.json");
  const nlohmann::json truth = beamid::testing::ReadJsonFile(directory / "truth.json");
  std::filesystem::remove_all(directory);
  EXPECT_EQ(campaign.at("excitation"), nlohmann::json::parse(R"({"channel": "base", "position_m": 0.0,
      "quantity": "base_acceleration", "unit": "m/s^2"})"));

  // The exact steady state of the same FE model: (K + k1·e_θe_θᵀ − ω²M +
  // iω·c·e_θe_θᵀ)·X = −M·r·A, the accelerometers reading −ω²X + A.
  const SteppedSineSimulation simulation(scenario);  // not run: the FE model it simulated
  const FeBeam& fe = simulation.simulator().fe_beam();
  const int theta = fe.SupportRotationDof();
  Eigen::VectorXd translation = Eigen::VectorXd::Zero(fe.NumDofs());
  for (double x : fe.node_positions_m())
    if (fe.DeflectionDof(x) != FeBeam::kConstrained) translation(fe.DeflectionDof(x)) = 1.0;
  ASSERT_EQ(truth.at("steps").size(), 3u);
  double largest_relative_motion = 0.0;
  for (const nlohmann::json& step : truth.at("steps")) {
    SCOPED_TRACE(step.at("file").get<std::string>());
    EXPECT_EQ(step.at("base_acceleration_amplitude_m_s2").get<double>(), kBase_m_s2);
    EXPECT_FALSE(step.contains("force_amplitude_N"));
    const nlohmann::json& base = step.at("channels").at("base");
    EXPECT_EQ(base.at("quantity"), "base_acceleration");
    EXPECT_LT(std::abs(Harmonic(base, 1) - kBase_m_s2), 1e-9);

    const double omega = 2.0 * std::numbers::pi * step.at("frequency_Hz").get<double>();
    Eigen::MatrixXcd dynamic = (fe.Stiffness() - omega * omega * fe.Mass()).cast<std::complex<double>>();
    dynamic(theta, theta) += std::complex<double>(kK1_Nm_rad, omega * kC_Nms_rad);
    const Eigen::VectorXcd load = (-(fe.Mass() * translation) * kBase_m_s2).cast<std::complex<double>>();
    const Eigen::VectorXcd relative = dynamic.partialPivLu().solve(load);
    for (const auto& [channel, x] : {std::pair<std::string, double>{"acc3", 0.57}, {"acc1", 0.1}}) {
      const std::complex<double> expected = -omega * omega * relative(fe.DeflectionDof(x)) + kBase_m_s2;
      const std::complex<double> simulated = Harmonic(step.at("channels").at(channel), 1);
      EXPECT_LT(std::abs(simulated - expected), 1e-4 * std::abs(expected))
          << channel << ": simulated " << simulated << ", exact " << expected;
      largest_relative_motion = std::max(largest_relative_motion, std::abs(expected - kBase_m_s2) / kBase_m_s2);
    }
  }
  // The resonant step moves the beam far beyond the base (the test compares
  // more than the base's own acceleration).
  EXPECT_GT(largest_relative_motion, 2.0);
}

TEST(BaseExcitation, TheReaderRefusesWhatAMovingBaseCannotHold) {
  auto refused = [](const std::string& from, const std::string& to, const std::string& expected) {
    std::string text = kScenario;
    text.replace(text.find(from), from.size(), to);
    try {
      ParseScenario(text, "base.json");
      ADD_FAILURE() << "accepted: " << expected;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  refused(R"("quantity": "base_acceleration"})", R"("quantity": "base_acceleration", "position_m": 0.3})",
          "excitation.position_m\" must be left out");
  refused(R"("position_m": 0.1, "unit": "g"})", R"("position_m": 0.1, "quantity": "velocity", "unit": "m/s"})",
          "sensors[1].quantity\" breaks the rule: quantity is acceleration with excitation.quantity");
  refused(R"("label": "below", "base_acceleration_amplitude_m_s2": 2.0)", R"("label": "below", "force_amplitude_N": 2.0)",
          "levels[0].force_amplitude_N\" is not the drive with excitation.quantity \"base_acceleration\". "
          "Fix: give base_acceleration_amplitude_m_s2");
  refused(R"("label": "below", "base_acceleration_amplitude_m_s2": 2.0, )", R"("label": "below", )",
          "levels[0].base_acceleration_amplitude_m_s2\" is missing");
  // The written scenario reads back as the same base excitation.
  const Scenario s = ParseScenario(kScenario, "base.json");
  const Scenario read = ParseScenario(ScenarioToJson(s), "written.json");
  EXPECT_TRUE(read.BaseExcitation());
  EXPECT_EQ(read.levels[2].base_acceleration_amplitude_m_s2, kBase_m_s2);
  EXPECT_EQ(ScenarioToJson(read), ScenarioToJson(s));
}

}  // namespace
}  // namespace beamid::hb
