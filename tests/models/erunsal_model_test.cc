// The 6-DOF model beyond the model battery (model_battery_test.cc, which runs it under the
// DOF restrictions): the open-loop simulator's RK4 order, the restricted roll equation,
// absent commands, admissibility, and the reference vessel's behaviour quoted in MODELS.md.
#include <cmath>

#include "engine/model/open_loop_simulation.h"
#include "gtest/gtest.h"
#include "problems/erunsal6dof/erunsal_model.h"
#include "problems/erunsal6dof/handles.h"
#include "tests/support/erunsal_data.h"

namespace vesselid::erunsal6dof {
namespace erunsal_model_test {

// The open-loop simulator that makes the campaigns (its own RK4; the battery checks the
// identification's).
TEST(ErunsalModel, OpenLoopSimulationConvergesWithFourthOrder) {
  auto handle = MakeHandle(Model());
  const std::vector<double> p = ReferenceParameters();
  auto final_state = [&](int substeps) {
    Trajectory data;
    std::string error;
    OpenLoopOptions options;
    options.substeps = substeps;
    EXPECT_TRUE(SimulateOpenLoop(*handle, p, testing::ErunsalInitialState(Model()),
                                 testing::ErunsalCommands(4.0, 0.1, false), options,
                                 &data, &error));
    std::vector<double> x;
    for (int i = 0; i < 12; ++i) x.push_back(data.columns[2 + i].back());
    return x;
  };
  const std::vector<double> reference = final_state(256);
  auto error = [&](int substeps) {
    std::vector<double> x = final_state(substeps);
    double e = 0.0;
    for (int i = 0; i < 12; ++i) e = std::max(e, std::abs(x[i] - reference[i]));
    return e;
  };
  // Heave and pitch periods are ~0.6 s: steps of 0.05, 0.025 and 0.0125 s.
  const double e1 = error(2), e2 = error(4), e3 = error(8);
  EXPECT_NEAR(std::log2(e1 / e2), 4.0, 0.35);
  EXPECT_NEAR(std::log2(e2 / e3), 4.0, 0.35);
}

TEST(ErunsalModel, RollRestrictionIsTheDecoupledRollEquation) {
  const Model model = testing::Restricted({kRoll});
  const std::vector<double> p = ReferenceParameters();
  std::vector<double> x(12, 0.0), xdot(12);
  x[kRoll] = 0.2;
  x[6 + kRoll] = -0.3;
  x[6 + kSurge] = 1.0;  // inactive: ignored
  const double u[4] = {NAN, NAN, NAN, NAN};
  ASSERT_TRUE(model(x.data(), u, p.data(), xdot.data()));
  const double pr = -0.3;
  const double expected = (p[kKp] * pr + p[kKpp] * std::abs(pr) * pr - 4.32 * std::sin(0.2)) /
                          (p[kIx] - p[kKpdot]);
  EXPECT_NEAR(xdot[6 + kRoll], expected, 1e-12);
  EXPECT_NEAR(xdot[kRoll], pr, 1e-12);
  for (int i = 0; i < 12; ++i) {
    if (i != kRoll && i != 6 + kRoll) {
      EXPECT_EQ(xdot[i], 0.0) << i;
    }
  }
}

TEST(ErunsalModel, AbsentCommandsMeanMotorsOff) {
  const Model model = testing::Restricted({kSurge});
  const std::vector<double> p = ReferenceParameters();
  std::vector<double> x(12, 0.0), off(12), zero(12);
  const double absent[4] = {NAN, NAN, NAN, NAN};
  const double zero_command[4] = {0.0, 0.0, NAN, NAN};
  ASSERT_TRUE(model(x.data(), absent, p.data(), off.data()));
  ASSERT_TRUE(model(x.data(), zero_command, p.data(), zero.data()));
  EXPECT_EQ(off[6], 0.0);
  // c = 0 still applies the offsets L_TO + R_TO = 0 here, but their yaw moment is not zero.
  const Model surge_yaw = testing::Restricted({kSurge, kYaw});
  ASSERT_TRUE(surge_yaw(x.data(), zero_command, p.data(), zero.data()));
  EXPECT_NEAR(zero[6 + kYaw] * (p[kIz] - p[kNrdot]), 0.06 * (p[kLTO] - p[kRTO]), 1e-12);
}

TEST(ErunsalModel, Admissibility) {
  const Model model;
  std::vector<double> p = ReferenceParameters();
  EXPECT_TRUE(model.Admissibility(p.data(), nullptr).empty());
  p[kIx] = -2.5;  // seed 002 Table 1's inertia
  ASSERT_EQ(model.Admissibility(p.data(), nullptr).size(), 1u);
  EXPECT_NE(model.Admissibility(p.data(), nullptr)[0].find("M is not positive definite"), std::string::npos);
  p = ReferenceParameters();
  p[kXu] = 1.0;  // negative damping
  ASSERT_EQ(model.Admissibility(p.data(), nullptr).size(), 1u);
  EXPECT_NE(model.Admissibility(p.data(), nullptr)[0].find("damping"), std::string::npos);
}

TEST(ErunsalModel, ReferenceVesselBehaviour) {
  // Full thrust ahead in surge: top speed about 1.9 m/s.
  auto surge = MakeHandle(testing::Restricted({kSurge}));
  Trajectory commands;
  commands.names = {"c_L", "c_R"};
  commands.columns.resize(2);
  for (int k = 0; k <= 600; ++k) {
    commands.t.push_back(0.1 * k);
    commands.columns[0].push_back(1.0);
    commands.columns[1].push_back(1.0);
  }
  Trajectory run;
  std::string error;
  ASSERT_TRUE(SimulateOpenLoop(*surge, ReferenceParameters(), std::vector<double>(12, 0.0),
                               commands, {}, &run, &error));
  // Steady state: 20 N = -Xu u - (Xuu - rho/2 C_DA A_x) u^2 (MODELS.md quotes about 1.9 m/s).
  const std::vector<double> p = ReferenceParameters();
  const double a = -p[kXuu] + 0.5 * 1.225 * p[kCDA] * 0.05, b = -p[kXu];
  const double top = (-b + std::sqrt(b * b + 4 * a * 20.0)) / (2 * a);
  EXPECT_NEAR(top, 1.9, 0.1);
  EXPECT_NEAR(run.columns[run.Find("u")].back(), top, 1e-3);
  // Roll free decay: period about 1.21 s (zero crossings of phi).
  auto roll = MakeHandle(Model());
  Trajectory silence;
  silence.names = {};
  for (int k = 0; k <= 1000; ++k) silence.t.push_back(0.005 * k);
  std::vector<double> x0(12, 0.0);
  x0[kRoll] = 0.2;
  ASSERT_TRUE(SimulateOpenLoop(*roll, ReferenceParameters(), x0, silence, {}, &run, &error));
  const std::vector<double>& phi = run.columns[run.Find("phi")];
  std::vector<double> crossings;
  for (size_t k = 1; k < phi.size(); ++k) {
    if (phi[k - 1] > 0 && phi[k] <= 0) crossings.push_back(run.t[k]);
  }
  ASSERT_GE(crossings.size(), 3u);
  EXPECT_NEAR((crossings.back() - crossings.front()) / (crossings.size() - 1), 1.21, 0.03);
}

}  // namespace erunsal_model_test
}  // namespace vesselid::erunsal6dof
