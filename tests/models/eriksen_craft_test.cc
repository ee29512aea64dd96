// Physical planing craft (speeds, one-to-one steady map, mirror symmetry, RK4 order) and the
// seed-004 step campaign and validation runs (levels, settling, columns, determinism).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "engine/data/trajectory.h"
#include "engine/model/rk4.h"
#include "gtest/gtest.h"
#include "problems/eriksen2dof/campaign.h"
#include "problems/eriksen2dof/craft.h"

namespace vesselid::eriksen2dof {
namespace eriksen_craft_test {

CraftSteadyState Steady(const CraftParameters& p, double tau_m, double tau_delta) {
  CraftSteadyState s;
  EXPECT_TRUE(SteadyState(p, tau_m, tau_delta, &s)) << tau_m << ", " << tau_delta;
  return s;
}

// State after `duration` s of constant commands from x0, RK4 step h, calm surroundings.
std::vector<double> Hold(const CraftParameters& p, std::vector<double> x, double tau_m,
                         double tau_delta, double duration, double h) {
  const CraftEnvironment calm;
  const double tau[2] = {tau_m, tau_delta};
  for (long k = 0; k < std::lround(duration / h); ++k) {
    EXPECT_TRUE(
        (Rk4Step<CraftRhs, double>(CraftRhs{&p, &calm}, tau, tau, tau, nullptr, h, x.data())));
  }
  return x;
}

std::vector<double> SteadyStateVector(const CraftParameters& p, double tau_m, double tau_delta) {
  const CraftSteadyState s = Steady(p, tau_m, tau_delta);
  std::vector<double> x(kCraftStates, 0.0);
  x[kCraftU] = s.u;
  x[kCraftV] = s.v;
  x[kCraftR] = s.r;
  x[kCraftThrust] = s.thrust;
  x[kCraftAngle] = s.angle;
  return x;
}

TEST(EriksenCraft, TopAndIdleSpeed) {
  const CraftParameters p;
  const CraftSteadyState top = Steady(p, 1.0, 0.0), idle = Steady(p, 0.0, 0.0);
  EXPECT_GT(top.sog, 16.0);
  EXPECT_LT(top.sog, 20.0);
  EXPECT_GT(idle.sog, 1.0);
  EXPECT_LT(idle.sog, 2.5);
  EXPECT_NEAR(top.r, 0.0, 1e-9);
  EXPECT_NEAR(top.v, 0.0, 1e-9);
  // Motor response flattens above the knee: g(0.6) = 6/7, the last 0.4 of throttle adds 1/7.
  EXPECT_NEAR(ThrottleCurve(p, 0.6), 6.0 / 7.0, 1e-12);
  EXPECT_DOUBLE_EQ(ThrottleCurve(p, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(CommandedThrust(p, 0.0), p.thrust_idle);
}

// The surge time constant is short on the hump's steep flank, long on the flat stretch above it
// and at idle.
TEST(EriksenCraft, SurgeTimeConstantVariesAcrossRegimes) {
  const CraftParameters p;
  const double idle = SurgeTimeConstant(p, 2.0), hump = SurgeTimeConstant(p, 4.5);
  const double flat = SurgeTimeConstant(p, 8.0), planing = SurgeTimeConstant(p, 18.0);
  EXPECT_GT(idle, 4.0 * hump);
  EXPECT_GT(flat, 3.0 * hump);
  EXPECT_GT(flat, planing);
  for (double u = 0.1; u < 25.0; u += 0.1) {
    EXPECT_GT(HullResistance(p, u + 0.1), HullResistance(p, u)) << u;  // monotone, no fold
  }
}

// Steady U increases with throttle at fixed rudder, steady r with rudder at fixed throttle,
// and the Jacobian d(U, r) / d(tau_m, tau_delta) keeps its sign: the map is one-to-one.
TEST(EriksenCraft, SteadyMapIsOneToOne) {
  const CraftParameters p;
  for (double td : {0.0, 0.5, 1.0}) {
    double last = 0.0;
    for (int i = 0; i <= 10; ++i) {
      const double u = Steady(p, 0.1 * i, td).sog;
      EXPECT_GT(u, last + 0.05) << "tau_m " << 0.1 * i << " tau_delta " << td;
      last = u;
    }
  }
  for (double tm : {0.0, 0.3, 0.6, 1.0}) {
    double last = -1.0;
    for (int j = 0; j <= 10; ++j) {
      const double r = Steady(p, tm, 0.1 * j).r;
      EXPECT_GT(r, last + (j == 0 ? 0.0 : 0.002)) << "tau_m " << tm << " tau_delta " << 0.1 * j;
      last = r;
    }
  }
  const double d = 1e-4;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      const double tm = 0.1 + 0.2 * i, td = 0.1 + 0.2 * j;
      const CraftSteadyState a = Steady(p, tm, td), b = Steady(p, tm + d, td),
                             c = Steady(p, tm, td + d);
      const double det = (b.sog - a.sog) * (c.r - a.r) - (c.sog - a.sog) * (b.r - a.r);
      EXPECT_GT(det / (d * d), 0.1) << tm << ", " << td;
    }
  }
}

// Negative rudder mirrors the response exactly in still water: u equal, v and r opposite.
TEST(EriksenCraft, MirrorSymmetry) {
  const CraftParameters p;
  for (double tm : {0.1, 0.5, 0.9}) {
    for (double td : {0.3, 1.0}) {
      const CraftSteadyState plus = Steady(p, tm, td), minus = Steady(p, tm, -td);
      EXPECT_NEAR(plus.sog, minus.sog, 1e-8);
      EXPECT_NEAR(plus.r, -minus.r, 1e-9);
      EXPECT_GT(plus.r, 0.0);  // positive rudder turns to starboard
    }
  }
  const std::vector<double> x0 = SteadyStateVector(p, 0.4, 0.0);
  const std::vector<double> plus = Hold(p, x0, 0.8, 0.7, 30.0, 0.02);
  const std::vector<double> minus = Hold(p, x0, 0.8, -0.7, 30.0, 0.02);
  EXPECT_NEAR(plus[kCraftU], minus[kCraftU], 1e-9);
  EXPECT_NEAR(plus[kCraftV], -minus[kCraftV], 1e-9);
  EXPECT_NEAR(plus[kCraftR], -minus[kCraftR], 1e-9);
  EXPECT_NEAR(plus[kCraftPsi], -minus[kCraftPsi], 1e-9);
  EXPECT_NEAR(plus[kCraftE], -minus[kCraftE], 1e-6);
  EXPECT_GT(plus[kCraftPsi], 1.0);  // heading increases in a starboard turn
}

// Halving the RK4 step shrinks the error ~16-fold.
TEST(EriksenCraft, Rk4FourthOrder) {
  const CraftParameters p;
  const std::vector<double> x0 = SteadyStateVector(p, 0.2, 0.0);
  std::vector<std::vector<double>> x;
  for (double h : {0.1, 0.05, 0.025}) x.push_back(Hold(p, x0, 0.6, 0.8, 20.0, h));
  double e1 = 0.0, e2 = 0.0;
  for (int i : {kCraftN, kCraftE, kCraftU, kCraftR}) {
    e1 = std::max(e1, std::abs(x[0][i] - x[1][i]));
    e2 = std::max(e2, std::abs(x[1][i] - x[2][i]));
  }
  ASSERT_GT(e2, 0.0);
  EXPECT_GT(e1 / e2, 12.0);
  EXPECT_LT(e1 / e2, 20.0);
}

CampaignOptions SmallCampaign() {
  CampaignOptions o;
  o.rudder_settings = {0.0, 1.0};
  o.throttle_settings = {0.3};
  o.throttle_step = 0.5;
  o.rudder_step = 0.5;
  o.max_steady = 40.0;
  o.validation_runs = 4;
  o.validation_duration = 120.0;
  return o;
}

// Rows [begin, end) of each level: maximal stretches of one run with constant commands.
struct Level {
  size_t begin, end;
  int run;
  double throttle, rudder;
};

std::vector<Level> Levels(const Trajectory& t) {
  const int run = t.Find("run"), throttle = t.Find("throttle"), rudder = t.Find("rudder");
  std::vector<Level> levels;
  for (size_t k = 0; k < t.t.size(); ++k) {
    const int id = static_cast<int>(t.columns[run][k]);
    const double m = t.columns[throttle][k], d = t.columns[rudder][k];
    if (levels.empty() || levels.back().run != id || levels.back().throttle != m ||
        levels.back().rudder != d) {
      levels.push_back({k, k, id, m, d});
    }
    levels.back().end = k + 1;
  }
  return levels;
}

TEST(EriksenCampaign, StepCampaignLevelsAndSettling) {
  CampaignOptions o = SmallCampaign();
  o.current_speed = 0.0;  // calm: settled means sog_true constant
  o.wind_speed = 0.0;
  o.gust_sd = 0.0;
  Trajectory t;
  std::string error;
  ASSERT_TRUE(SimulateStepCampaign(CraftParameters(), o, &t, &error)) << error;
  const std::vector<std::string> names = {"run", "n",        "e",      "course",   "sog",
                                          "rot", "throttle", "rudder", "sog_true", "rot_true"};
  EXPECT_EQ(t.names, names);
  for (size_t k = 1; k < t.t.size(); ++k) {
    ASSERT_GT(t.t[k], t.t[k - 1]) << k;
  }

  const std::vector<Level> levels = Levels(t);
  ASSERT_EQ(levels.size(), 15u);  // 3 runs x (0, 0.5, 1, 0.5, 0)
  const double expected_level[5] = {0.0, 0.5, 1.0, 0.5, 0.0};
  const int sog = t.Find("sog_true");
  for (size_t i = 0; i < levels.size(); ++i) {
    const Level& l = levels[i];
    EXPECT_EQ(l.run, static_cast<int>(i / 5));  // contiguous ids 0, 1, 2
    if (l.run < 2) {
      EXPECT_EQ(l.throttle, expected_level[i % 5]);
      EXPECT_EQ(l.rudder, l.run == 0 ? 0.0 : 1.0);
    } else {
      EXPECT_EQ(l.throttle, 0.3);
      EXPECT_EQ(l.rudder, expected_level[i % 5]);
    }
    const double duration = t.t[l.end - 1] - t.t[l.begin] + o.sample_period;
    EXPECT_GE(duration, o.min_settle + o.min_steady - 1e-6);
    // Settled: the last 5 s of every level have a constant speed.
    size_t k = l.end - 1;
    while (t.t[l.end - 1] - t.t[k - 1] <= 5.0) --k;
    for (; k + 1 < l.end; ++k) {
      const double rate = (t.columns[sog][k + 1] - t.columns[sog][k]) / (t.t[k + 1] - t.t[k]);
      EXPECT_LT(std::abs(rate), 0.005) << "level " << i << " t " << t.t[k];
    }
  }
}

TEST(EriksenCampaign, NoiseAndEnvironment) {
  Trajectory t;
  std::string error;
  const CampaignOptions o = SmallCampaign();
  ASSERT_TRUE(SimulateStepCampaign(CraftParameters(), o, &t, &error)) << error;
  const int course = t.Find("course"), sog = t.Find("sog"), sog_true = t.Find("sog_true");
  const int rot = t.Find("rot"), rot_true = t.Find("rot_true");
  double s2 = 0.0, r2 = 0.0;
  for (size_t k = 0; k < t.t.size(); ++k) {
    EXPECT_GT(t.columns[course][k], -M_PI);
    EXPECT_LE(t.columns[course][k], M_PI);
    EXPECT_GT(t.columns[sog_true][k], 0.3);  // COG stays defined
    s2 += std::pow(t.columns[sog][k] - t.columns[sog_true][k], 2);
    r2 += std::pow(t.columns[rot][k] - t.columns[rot_true][k], 2);
  }
  EXPECT_NEAR(std::sqrt(s2 / t.t.size()), o.sog_noise, 0.1 * o.sog_noise);
  EXPECT_NEAR(std::sqrt(r2 / t.t.size()), o.rot_noise, 0.1 * o.rot_noise);
}

bool Same(const Trajectory& a, const Trajectory& b) {
  return a.t == b.t && a.names == b.names && a.columns == b.columns;
}

TEST(EriksenCampaign, DeterministicBySeed) {
  CampaignOptions o = SmallCampaign();
  o.rudder_settings = {0.6};
  o.throttle_settings = {};
  Trajectory a, b, c, va, vb;
  std::string error;
  ASSERT_TRUE(SimulateStepCampaign(CraftParameters(), o, &a, &error)) << error;
  ASSERT_TRUE(SimulateStepCampaign(CraftParameters(), o, &b, &error)) << error;
  ASSERT_TRUE(SimulateValidationRuns(CraftParameters(), o, &va, &error)) << error;
  ASSERT_TRUE(SimulateValidationRuns(CraftParameters(), o, &vb, &error)) << error;
  EXPECT_TRUE(Same(a, b));
  EXPECT_TRUE(Same(va, vb));
  o.seed = 2;
  ASSERT_TRUE(SimulateStepCampaign(CraftParameters(), o, &c, &error)) << error;
  EXPECT_FALSE(Same(a, c));
}

TEST(EriksenCampaign, ValidationRuns) {
  CampaignOptions o = SmallCampaign();
  o.validation_throttle_min = 0.1;
  o.validation_throttle_max = 0.4;
  Trajectory t;
  std::string error;
  ASSERT_TRUE(SimulateValidationRuns(CraftParameters(), o, &t, &error)) << error;
  ASSERT_EQ(t.t.size(), 4u * 600u);
  const int run = t.Find("run"), throttle = t.Find("throttle"), rudder = t.Find("rudder");
  std::set<double> rudder_values;
  for (size_t k = 0; k < t.t.size(); ++k) {
    if (k > 0) {
      ASSERT_GT(t.t[k], t.t[k - 1]);
    }
    EXPECT_EQ(t.columns[run][k], static_cast<double>(k / 600));
    EXPECT_GE(t.columns[throttle][k], 0.1);
    EXPECT_LE(t.columns[throttle][k], 0.4);
    EXPECT_GE(t.columns[rudder][k], -1.0);
    EXPECT_LE(t.columns[rudder][k], 1.0);
    if (k / 600 == 2) {
      EXPECT_LE(t.columns[rudder][k], 0.0);  // negative-rudder run
    }
    if (k / 600 == 0) rudder_values.insert(t.columns[rudder][k]);
  }
  EXPECT_GE(rudder_values.size(), 3u);  // run 0: steps, several levels
}

TEST(EriksenCampaign, RejectsBadOptions) {
  std::string error;
  CampaignOptions o;
  EXPECT_TRUE(o.IsValid(&error)) << error;
  o.throttle_step = 0.3;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("throttle_step"), std::string::npos);
  o = CampaignOptions();
  o.sample_period = 0.03;
  EXPECT_FALSE(o.IsValid(&error));
  o = CampaignOptions();
  o.validation_throttle_max = 1.5;
  EXPECT_FALSE(o.IsValid(&error));
  Trajectory t;
  EXPECT_FALSE(SimulateStepCampaign(CraftParameters(), o, &t, &error));
}

}  // namespace eriksen_craft_test
}  // namespace vesselid::eriksen2dof
