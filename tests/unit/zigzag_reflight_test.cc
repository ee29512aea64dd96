// A recorded zigzag re-flown in closed loop (engine/run/zigzag_reflight.h), on the patrol
// vessel's 20/20 zigzag simulated by the seed 003 closed-loop simulator (problems/nomoto), its
// steering gear rate-limited: the true model re-flown from the record's start reproduces the
// record's overshoots; a model whose gain is 30 % high reaches each check sooner, reverses the
// rudder there (not where the logged rudder reversed), and its overshoots are its own.
#include "engine/run/zigzag_reflight.h"

#include <cmath>
#include <string>
#include <vector>

#include "engine/model/experiment.h"
#include "gtest/gtest.h"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"

namespace vesselid {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Record {
  std::vector<double> t, delta, psi;
  Experiment experiment;
};

// The patrol vessel (seed 003: T1 2.0875, T2 0.3179, T3 0.1830, K -0.1724) flying a
// `rudder`/`heading` zigzag from a straight course, its gear at 4 deg/s; noise-free unless
// `noise` (deg, on the logged rudder and heading).
Record Zigzag(const ModelHandle& model, double rudder, double heading, double noise = 0.0,
              double sample_time = 0.05, double rudder_rate = 4.0 * kDeg) {
  nomoto::ClosedLoopOptions loop;
  loop.steering_time_constant = 0.05;
  loop.rudder_rate = rudder_rate;  // 0: the lag alone
  loop.sample_time = sample_time;
  loop.duration = 120.0;
  loop.excitation.type = nomoto::Excitation::Type::kZigzag;
  loop.excitation.zigzag_rudder = rudder * kDeg;
  loop.excitation.zigzag_heading = heading * kDeg;
  loop.rudder_noise = noise * kDeg;
  loop.heading_noise = noise * kDeg;
  Trajectory trajectory;
  std::string error;
  EXPECT_TRUE(nomoto::SimulateClosedLoop(model, {2.0875, 0.3179, 0.1830, -0.1724, 0.0}, loop,
                                         &trajectory, &error))
      << error;
  trajectory.source = "zigzag";
  Record record;
  record.t = trajectory.t;
  for (size_t c = 0; c < trajectory.names.size(); ++c) {
    if (trajectory.names[c] == "delta") record.delta = trajectory.columns[c];
    if (trajectory.names[c] == "psi") record.psi = trajectory.columns[c];
  }
  ExperimentSpec spec;
  spec.name = "zigzag";
  spec.inputs = {{"delta", "delta"}};
  spec.outputs = {{"psi", "psi"}};
  spec.default_interpolation = Interpolation::kLinear;
  EXPECT_TRUE(BuildExperiment(spec, trajectory, model.info(), ExperimentOptions(),
                              &record.experiment, &error))
      << error;
  return record;
}

// A zigzag record read as the re-flight reads it, and flown again with parameters p.
struct Flight {
  Record record;
  ZigzagTest test;
  ZigzagFigures measured;  // on the record
  ZigzagCommands commands;
  ZigzagReflight flown;
};

void Fly(const ModelHandle& model, double rudder, double heading, double noise,
         const std::vector<double>& p, Flight* f, double sample_time = 0.05,
         double rudder_rate = 4.0 * kDeg) {
  f->record = Zigzag(model, rudder, heading, noise, sample_time, rudder_rate);
  const Record& r = f->record;
  std::string why;
  ASSERT_TRUE(DetectZigzag(r.t, r.delta, r.psi, &f->test, &why)) << why;
  f->measured = MeasureZigzag(r.t, r.psi, f->test);
  ASSERT_TRUE(FindZigzagCommands(r.t, r.delta, r.psi, f->test, &f->commands, &why)) << why;
  const std::vector<double> x0(model.info().states.size(), 0.0);
  ASSERT_TRUE(ReflyZigzag(model, r.experiment, p.data(), x0.data(), f->test, f->commands,
                          f->commands.rate, &f->flown, &why))
      << why;
}

const std::vector<double> kTruth = {2.0875, 0.3179, 0.1830, -0.1724, 0.0};

// The re-flight reversed at least three times and its overshoots within `tolerance` deg of
// the record's.
void ExpectOvershootsAgree(const Flight& f, double tolerance) {
  ASSERT_GE(f.flown.reversals, 3);
  ASSERT_TRUE(std::isfinite(f.measured.first_overshoot) &&
              std::isfinite(f.measured.second_overshoot));
  EXPECT_NEAR(f.flown.figures.first_overshoot, f.measured.first_overshoot, tolerance * kDeg);
  EXPECT_NEAR(f.flown.figures.second_overshoot, f.measured.second_overshoot, tolerance * kDeg);
}

TEST(ZigzagReflight, TheTrueModelReproducesTheRecordsOvershoots) {
  const auto model = nomoto::MakeSecondOrderHandle();
  Flight f;
  ASSERT_NO_FATAL_FAILURE(Fly(*model, 20.0, 20.0, 0.0, kTruth, &f));
  EXPECT_NEAR(f.commands.amplitude, 20.0 * kDeg, 0.01 * kDeg);
  EXPECT_NEAR(f.commands.neutral, 0.0, 0.01 * kDeg);
  // The simulator reverses at the first 0.05 s sample past 20 deg (at 2 deg/s of yaw, up to
  // 0.1 deg past it).
  EXPECT_NEAR(f.commands.check, 20.05 * kDeg, 0.06 * kDeg);
  ExpectOvershootsAgree(f, 0.05);
  EXPECT_NEAR(f.flown.figures.time_to_first_check, f.measured.time_to_first_check, 0.1);
}

// A 10/10 zigzag logged with 0.1 deg of noise on the rudder and the heading: the commands and
// the check are read through the noise, and the true model's overshoots land within the noise.
TEST(ZigzagReflight, ANoisyLogGivesTheTestAsFlown) {
  const auto model = nomoto::MakeSecondOrderHandle();
  Flight f;
  ASSERT_NO_FATAL_FAILURE(Fly(*model, 10.0, 10.0, 0.1, kTruth, &f));
  EXPECT_NEAR(f.commands.amplitude, 10.0 * kDeg, 0.05 * kDeg);
  EXPECT_NEAR(f.commands.check, 10.0 * kDeg, 0.25 * kDeg);
  ExpectOvershootsAgree(f, 0.4);
}

// A 1 Hz log (the run's RK4 step a whole second): the re-flight still checks the heading
// every 0.05 s, and the gear's rate comes from the log's ramps.
TEST(ZigzagReflight, AOneHertzLogIsReflownAtItsOwnChecks) {
  const auto model = nomoto::MakeSecondOrderHandle();
  Flight f;
  ASSERT_NO_FATAL_FAILURE(Fly(*model, 20.0, 20.0, 0.0, kTruth, &f, 1.0));
  EXPECT_NEAR(f.commands.rate, 4.0 * kDeg, 0.2 * kDeg);
  ExpectOvershootsAgree(f, 0.15);
}

// A gear faster than the log (no sample on its ramps): the move is taken as half an interval,
// not replaced by IMO's 2.3 deg/s (which put the overshoots 13 deg high, a second user's
// finding). The 0.5 s samples leave each check uncertain by the heading's change over one
// (up to 1 deg here): within 0.5 deg.
TEST(ZigzagReflight, AGearFasterThanTheLogIsFlownFast) {
  const auto model = nomoto::MakeSecondOrderHandle();
  Flight f;
  ASSERT_NO_FATAL_FAILURE(Fly(*model, 20.0, 20.0, 0.0, kTruth, &f, 0.5, 0.0));
  EXPECT_GT(f.commands.rate, 30.0 * kDeg);
  ExpectOvershootsAgree(f, 0.5);
}

TEST(ZigzagReflight, AModelReversesTheRudderAtItsOwnChecks) {
  const auto model = nomoto::MakeSecondOrderHandle();
  std::vector<double> p = kTruth;
  p[3] *= 1.3;  // K 30 % high
  Flight f;
  ASSERT_NO_FATAL_FAILURE(Fly(*model, 20.0, 20.0, 0.0, p, &f));
  const ZigzagReflight& flown = f.flown;
  ASSERT_GE(flown.reversals, 2);
  // The stronger ship reaches the first check sooner, and its rudder leaves the plateau
  // there: where the heading change first reaches the check, not where the logged rudder
  // (reversed at the true ship's check) left it.
  EXPECT_LT(flown.figures.time_to_first_check, f.measured.time_to_first_check - 0.5);
  size_t reached = 0, left = 0;
  while (reached < flown.t.size() &&
         std::abs(flown.psi[reached] - flown.psi[0]) < f.commands.check) {
    ++reached;
  }
  while (left < flown.t.size() && !(flown.t[left] > f.test.first_execute + 1.0 &&
                                    flown.delta[left] > flown.delta[left - 1])) {
    ++left;  // the rudder first moves back (the first command is -20 deg: K < 0)
  }
  ASSERT_LT(reached, flown.t.size());
  EXPECT_NEAR(flown.t[left], flown.t[reached], 0.1);
  EXPECT_GT(std::abs(flown.figures.first_overshoot - f.measured.first_overshoot), 0.3 * kDeg);
}

TEST(ZigzagReflight, CommandsAreTheLoggedPlateausAroundABiasedNeutral) {
  std::vector<double> t, delta, psi;
  for (int i = 0; i < 600; ++i) {  // a 10/10 zigzag logged with a 2 deg offset, first to port
    t.push_back(0.1 * i);
    psi.push_back(0.001 * i);  // a heading that only moves on: the checks are its changes
    const int half = i < 50 ? -1 : (i / 150) % 2;
    delta.push_back((2.0 + (half < 0 ? 0.0 : (half == 0 ? -10.0 : 10.0))) * kDeg);
  }
  ZigzagTest test;
  test.first_execute = 5.0;
  ZigzagCommands commands;
  std::string why;
  ASSERT_TRUE(FindZigzagCommands(t, delta, psi, test, &commands, &why)) << why;
  EXPECT_NEAR(commands.neutral, 2.0 * kDeg, 1e-9);
  EXPECT_NEAR(commands.amplitude, 10.0 * kDeg, 1e-9);
  EXPECT_EQ(commands.first_sign, -1.0);
  // Left at samples 149, 299 and 449, from the heading at t_0 (sample 50): the median 0.249.
  EXPECT_NEAR(commands.check, 0.249, 1e-9);
  // A record cut inside the zigzag, its rudder on a plateau at its first sample: refused.
  ZigzagTest late = test;
  late.first_execute = 0.0;
  const std::vector<double> inside(delta.begin() + 60, delta.end());
  const std::vector<double> inside_t(t.begin() + 60, t.end()), inside_psi(psi.begin() + 60,
                                                                            psi.end());
  EXPECT_FALSE(FindZigzagCommands(inside_t, inside, inside_psi, late, &commands, &why));
  EXPECT_NE(why.find("starts inside the zigzag"), std::string::npos) << why;
  // A rudder that never leaves its neutral has no plateaus.
  EXPECT_FALSE(
      FindZigzagCommands(t, std::vector<double>(t.size(), 0.0), psi, test, &commands, &why));
  EXPECT_NE(why.find("no plateau"), std::string::npos) << why;
}

}  // namespace
}  // namespace vesselid
