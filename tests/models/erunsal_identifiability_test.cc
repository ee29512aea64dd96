// What the 6-DOF model's data cannot determine (MODELS.md §1), found by the run itself: a
// stage that leaves such a combination free reports it by name and gives its parameters no
// standard error, instead of precise-looking numbers. The contrasting stage with the
// combination anchored determines everything.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/config/config.h"
#include "engine/diagnose/run_findings.h"
#include "engine/run/pipeline.h"
#include "engine/run/records.h"
#include "gtest/gtest.h"
#include "problems/registry.h"

namespace vesselid {
namespace erunsal_identifiability_test {

namespace fs = std::filesystem;

// A 40 s spiral and a yaw decay of the reference tugboat in surge-sway-yaw, 10 s segments.
constexpr char kCampaign[] = R"(model: {family: erunsal6dof, active_dofs: [surge, sway, yaw]}
simulation:
  sample_time: 0.02
  substeps: 2
  noise: {position: 0.02, angle_deg: 0.2}
  experiments:
    - {file: spiral.csv, type: spiral, duration: 40, mean_command: 0.6, differential: 0.1, seed: 5, active_dofs: [surge, sway, yaw]}
    - {file: yaw.csv, type: decay, duration: 15, initial_state: {r: 0.8}, seed: 6, active_dofs: [surge, sway, yaw]}
experiments:
  - {name: spiral, file: spiral.csv, inputs: {c_L: c_L, c_R: c_R}, outputs: {x: x, y: y, psi: psi}, interpolation: zero_order_hold, segment_length: 10}
  - {name: yaw, file: yaw.csv, outputs: {psi: psi}}
)";

// Horizontal-manoeuvre parameters free in a spiral stage; the thruster ones are appended.
constexpr char kManoeuvring[] = R"(
      Iz: {lower: 0.01, upper: 10}
      Xudot: {lower: -10, upper: 5}
      Yvdot: {lower: -10, upper: 5}
      Yrdot: {lower: -10, upper: 5}
      Xu: {lower: -60, upper: 0}
      Yv: {lower: -40, upper: 0}
      Yr: {lower: -1, upper: 1}
      Nv: {lower: -10, upper: 0}
      Nr: {lower: -2, upper: 0}
      Xuu: {lower: -30, upper: 0}
      Yvv: {lower: -40, upper: 0}
      Nrr: {lower: -3, upper: 0}
)";

class Identifiability : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One folder per process: CTest runs these tests in parallel processes.
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("vesselid_identifiability_test_" + std::to_string(getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    std::ofstream(*dir_ / "campaign.yaml") << kCampaign << "stages: [{parameters: {}}]\n";
    const std::string simulate = std::string(VESSELID_BINARY) + " simulate " +
                                 (*dir_ / "campaign.yaml").string() + " --out " +
                                 dir_->string() + " > /dev/null";
    ASSERT_EQ(std::system(simulate.c_str()), 0) << simulate;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }

  // Runs the campaign with `stages`; parameters start at the reference values.
  static RunResult Run(const std::string& stages) {
    std::ofstream(*dir_ / "run.yaml") << kCampaign << stages;
    RunConfig config;
    RunResult result;
    std::string error;
    EXPECT_TRUE(LoadRunConfig((*dir_ / "run.yaml").string(), "", DefaultRegistry(), &config,
                              &error))
        << error;
    EXPECT_TRUE(Identify(config, &result, &error)) << error;
    return result;
  }

  static const FinalParameter& Final(const RunResult& result, const std::string& name) {
    for (const FinalParameter& p : result.parameters) {
      if (p.name == name) return p;
    }
    static FinalParameter none;
    ADD_FAILURE() << "no parameter " << name;
    return none;
  }

  // The stage's undetermined combinations, each required to name every one of `names`.
  static void ExpectUndetermined(const RunResult& result, const std::vector<std::string>& names) {
    ASSERT_EQ(result.stages.size(), 1u);
    const Uncertainty& u = result.stages[0].summary.uncertainty;
    ASSERT_EQ(u.undetermined.size(), 1u) << "expected one undetermined combination";
    for (const std::string& name : names) {
      EXPECT_NE(u.undetermined[0].find(" " + name), std::string::npos)
          << name << " missing from '" << u.undetermined[0] << "'";
      EXPECT_TRUE(Final(result, name).undetermined) << name;
      EXPECT_TRUE(std::isnan(Final(result, name).std_error)) << name;
    }
  }

  static fs::path* dir_;
};

fs::path* Identifiability::dir_ = nullptr;

TEST_F(Identifiability, InertiaAndAddedInertiaOfOneAxisAreOnlyDeterminedAsADifference) {
  const std::string yaw_stage = R"(stages:
  - name: yaw
    experiments: [yaw]
    free_initial_states: [psi, r]
    parameters:
      Iz: {lower: 0.01, upper: 10, role: shared}
      Nr: {lower: -2, upper: 0, role: shared}
)";
  const RunResult free_pair =
      Run(yaw_stage + "      Nrdot: {lower: -2, upper: 0.5, role: shared}\n");
  ExpectUndetermined(free_pair, {"Iz", "Nrdot"});
  EXPECT_FALSE(Final(free_pair, "Nr").undetermined);
  // Nrdot held (as the shipped config does): Iz is determined.
  const RunResult anchored = Run(yaw_stage);
  EXPECT_TRUE(anchored.stages[0].summary.uncertainty.undetermined.empty());
  EXPECT_FALSE(Final(anchored, "Iz").undetermined);
}

TEST_F(Identifiability, ForceScaleIsUndeterminedWithoutThrustMeasurements) {
  const std::string stage = R"(stages:
  - name: spiral
    experiments: [spiral]
    free_initial_states: [x, y, psi, u, v, r]
    parameters:)";
  const RunResult free_scale = Run(stage + kManoeuvring + R"(
      L_TS: {lower: 1, upper: 50}
      L_TO: {lower: -2, upper: 2}
      R_TS: {lower: 1, upper: 50}
      R_TO: {lower: -2, upper: 2}
)");
  // Scaling inertia, damping and thrust by one factor leaves x, y, psi unchanged.
  ExpectUndetermined(free_scale, {"Iz", "Xudot", "Yvdot", "Xu", "Yv", "Xuu", "Yvv", "L_TS",
                                  "R_TS"});
  // Thrusters fixed (as a thrust measurement stage would leave them): everything determined.
  const RunResult anchored = Run(stage + kManoeuvring);
  EXPECT_TRUE(anchored.stages[0].summary.uncertainty.undetermined.empty());
  for (const FinalParameter& p : anchored.parameters) EXPECT_FALSE(p.undetermined) << p.name;
}

TEST_F(Identifiability, AirDragIsCollinearWithQuadraticDampingInStillAir) {
  const RunResult still_air = Run(R"(stages:
  - name: spiral
    experiments: [spiral]
    free_initial_states: [x, y, psi, u, v, r]
    parameters:
      Xu: {lower: -60, upper: 0}
      Xuu: {lower: -30, upper: 0}
      Yvv: {lower: -40, upper: 0}
      C_DA: {lower: 0, upper: 5}
)");
  ExpectUndetermined(still_air, {"Xuu", "Yvv", "C_DA"});
  EXPECT_FALSE(Final(still_air, "Xu").undetermined);
}

}  // namespace erunsal_identifiability_test
}  // namespace vesselid
