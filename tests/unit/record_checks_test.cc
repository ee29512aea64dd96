// The quantisation rule of record_checks.h: a compass in whole degrees and a rudder in 1-degree
// steps are quantised, with their step; a smooth or noisy channel and a held two-level input
// are not.
#include "engine/diagnose/record_checks.h"

#include <cmath>
#include <random>

#include "gtest/gtest.h"

namespace vesselid {
namespace record_checks_test {

TEST(RecordChecks, QuantisationStepOfAWholeDegreeCompass) {
  std::vector<double> heading;
  for (int k = 0; k < 600; ++k) heading.push_back(std::round(20.0 * std::sin(0.01 * k)));
  EXPECT_DOUBLE_EQ(QuantisationStep(heading), 1.0);
  // In radians (as the engine holds a degree column), the step is one degree.
  for (double& h : heading) h *= M_PI / 180.0;
  EXPECT_NEAR(QuantisationStep(heading), M_PI / 180.0, 1e-12);
}

TEST(RecordChecks, SmoothNoisyAndTwoLevelChannelsAreNotQuantised) {
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<double> smooth, noisy, two_level;
  for (int k = 0; k < 600; ++k) {
    smooth.push_back(std::sin(0.01 * k));
    noisy.push_back(std::sin(0.01 * k) + noise(random));
    two_level.push_back((k / 50) % 2 == 0 ? 0.35 : -0.35);
  }
  EXPECT_EQ(QuantisationStep(smooth), 0.0);
  EXPECT_EQ(QuantisationStep(noisy), 0.0);
  EXPECT_EQ(QuantisationStep(two_level), 0.0);  // fewer than 3 distinct values
  EXPECT_EQ(QuantisationStep({1.0, 2.0, 3.0}), 0.0);  // too few samples to judge
}

// A rudder held at +-20 deg, converted to radians with round-off in the last digits: its values
// differ by 1e-16-1e-13, which is no quantisation (the note said "steps of 1e-12").
TEST(RecordChecks, RoundOffIsNotQuantisation) {
  std::vector<double> rudder;
  for (int k = 0; k < 600; ++k) {
    const double level = ((k / 50) % 2 == 0 ? 20.0 : -20.0) * M_PI / 180.0;
    rudder.push_back(level * (1.0 + 1e-13 * (k % 7)));
  }
  EXPECT_EQ(QuantisationStep(rudder), 0.0);
}

}  // namespace record_checks_test
}  // namespace vesselid

#include "problems/nomoto/handles.h"

namespace vesselid {
namespace record_checks_test {

// The record checks through a run's config and cache: a rudder that starts hard over and a
// compass in whole degrees are named (in degrees, the column's unit), a dead rudder column is
// an all_zero_input warning, and a clean record of the same shape says nothing.
TEST(RecordChecks, FindingsNameTheExperimentAndChannel) {
  RunConfig config;
  config.model = nomoto::MakeSecondOrderHandle();
  ExperimentSpec spec;
  spec.name = "zz";
  spec.inputs = {{"delta", "rudder"}};
  spec.outputs = {{"psi", "heading"}};
  spec.degree_columns = {"rudder", "heading"};
  config.experiments = {spec};
  auto record = [](double rudder_start, bool quantised, bool dead) {
    Trajectory t;
    t.names = {"rudder", "heading"};
    t.columns.resize(2);
    for (int k = 0; k < 400; ++k) {
      t.t.push_back(0.1 * k);
      const double rudder = k < 50 ? rudder_start : 20.0 * std::sin(0.05 * k);
      const double heading = 15.0 * std::sin(0.02 * k + 0.3) + 0.013 * k;
      t.columns[0].push_back(dead ? 0.0 : rudder * M_PI / 180.0);
      t.columns[1].push_back((quantised ? std::round(heading) : heading) * M_PI / 180.0);
    }
    return t;
  };
  auto findings_of = [&](Trajectory t) {
    TrajectoryCache cache;
    cache.Put("zz", std::move(t));
    std::vector<Finding> findings;
    AddRecordCheckFindings(config, &cache, &findings);
    return findings;
  };
  std::vector<Finding> found = findings_of(record(30.0, true, false));
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].kind, FindingKind::kStartsMidManoeuvre);
  EXPECT_EQ(found[0].experiment, "zz");
  EXPECT_EQ(found[0].input, "delta");  // an input is named as one
  EXPECT_TRUE(found[0].output.empty());
  EXPECT_NEAR(found[0].value, 30.0, 1e-9);
  EXPECT_EQ(found[0].message.rfind("column 'rudder' starts at 30 deg", 0), 0u) << found[0].message;
  EXPECT_EQ(found[1].kind, FindingKind::kQuantised);
  EXPECT_EQ(found[1].output, "psi");
  EXPECT_NEAR(found[1].value, 1.0, 1e-9);
  EXPECT_EQ(found[1].severity, FindingSeverity::kInfo);
  found = findings_of(record(0.0, false, true));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].kind, FindingKind::kAllZeroInput);
  EXPECT_EQ(found[0].severity, FindingSeverity::kWarning);
  EXPECT_TRUE(findings_of(record(0.0, false, false)).empty());
}

// A heading held for 4 samples at a time while the rudder moves is stale_repeats; the same
// heading updated every sample, or held only where the rudder is held too, is not. A hole
// in the heading is a gap, with its length (10.5 s).
TEST(RecordChecks, StaleRepeatsAndGapsOfAMeasuredOutput) {
  RunConfig config;
  config.model = nomoto::MakeSecondOrderHandle();
  ExperimentSpec spec;
  spec.name = "log";
  spec.inputs = {{"delta", "rudder"}};
  spec.outputs = {{"psi", "heading"}};
  config.experiments = {spec};
  auto record = [](int hold, bool rudder_held, bool gap) {
    Trajectory t;
    t.names = {"rudder", "heading"};
    t.columns.resize(2);
    for (int k = 0; k < 600; ++k) {
      if (gap && k >= 300 && k < 320) continue;
      t.t.push_back(0.5 * k);
      const int held = k - k % hold;
      t.columns[0].push_back(0.3 * std::sin(0.05 * (rudder_held ? held : k)));
      t.columns[1].push_back(0.5 + 0.4 * std::sin(0.011 * held + 0.2));
    }
    return t;
  };
  auto findings_of = [&](Trajectory t, FindingKind kind) {
    TrajectoryCache cache;
    cache.Put("log", std::move(t));
    std::vector<Finding> findings, of_kind;
    AddRecordCheckFindings(config, &cache, &findings);
    for (const Finding& f : findings) {
      if (f.kind == kind) of_kind.push_back(f);
    }
    return of_kind;
  };
  std::vector<Finding> stale = findings_of(record(4, false, false), FindingKind::kStaleRepeats);
  ASSERT_EQ(stale.size(), 1u);
  EXPECT_EQ(stale[0].output, "psi");
  EXPECT_EQ(stale[0].value, 450.0);  // 3 of every 4 samples
  EXPECT_NE(stale[0].message.find("screen: {stale: 3}"), std::string::npos) << stale[0].message;
  EXPECT_TRUE(findings_of(record(1, false, false), FindingKind::kStaleRepeats).empty());
  EXPECT_TRUE(findings_of(record(4, true, false), FindingKind::kStaleRepeats).empty());
  EXPECT_TRUE(findings_of(record(1, false, false), FindingKind::kGaps).empty());
  std::vector<Finding> gaps = findings_of(record(1, false, true), FindingKind::kGaps);
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_DOUBLE_EQ(gaps[0].value, 10.5);
  EXPECT_NE(gaps[0].message.find("10.5 s at t = 149.5 s"), std::string::npos) << gaps[0].message;
}

}  // namespace record_checks_test
}  // namespace vesselid
