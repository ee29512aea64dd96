// The one rule of a run's RK4 steps (engine/run/integration_step.h): each use of a simulation
// gets the step the header states, and a stage re-refined at a shorter step hands it on.
#include "engine/run/integration_step.h"

#include "gtest/gtest.h"

namespace vesselid {
namespace integration_step_test {

StageResult WithStep(double step) {
  StageResult s;
  s.integration_step = step;
  return s;
}

TEST(IntegrationStep, StageFitTakesTheConfiguredStepOrTheMedianInterval) {
  EXPECT_EQ(IntegrationStep(StepUse::kStageFit, 0.0), 0.0);  // 0: the median interval
  EXPECT_EQ(IntegrationStep(StepUse::kStageFit, 0.05), 0.05);
}

TEST(IntegrationStep, ValidationSimulatesAsTheStageEnded) {
  const StageResult plain = WithStep(0.0), reduced = WithStep(0.02);
  EXPECT_EQ(IntegrationStep(StepUse::kStageValidation, 0.0, {&plain}), 0.0);
  EXPECT_EQ(IntegrationStep(StepUse::kStageValidation, 0.1, {&plain}), 0.1);
  EXPECT_EQ(IntegrationStep(StepUse::kStageValidation, 0.1, {&reduced}), 0.02);
  EXPECT_EQ(IntegrationStep(StepUse::kStageValidation, 0.0, {&reduced}), 0.02);
}

TEST(IntegrationStep, FinalValidationTakesTheShortestStepOfTheAcceptedStages) {
  const StageResult a = WithStep(0.0), b = WithStep(0.04), c = WithStep(0.01);
  EXPECT_EQ(IntegrationStep(StepUse::kFinalValidation, 0.0, {&a}), 0.0);
  EXPECT_EQ(IntegrationStep(StepUse::kFinalValidation, 0.0, {&a, &b, &c}), 0.01);
  EXPECT_EQ(IntegrationStep(StepUse::kFinalValidation, 0.005, {&a, &b, &c}), 0.005);
  EXPECT_EQ(IntegrationStep(StepUse::kFinalValidation, 0.03, {&a, &b}), 0.03);
}

TEST(IntegrationStep, VelocityValidationTakesATenthOfTheGridOrAShorterStageStep) {
  const StageResult plain = WithStep(0.0), reduced = WithStep(0.01);
  EXPECT_DOUBLE_EQ(IntegrationStep(StepUse::kVelocityValidation, 0.0, {&plain}, 1.0), 0.1);
  EXPECT_DOUBLE_EQ(IntegrationStep(StepUse::kVelocityValidation, 0.0, {&reduced}, 1.0), 0.01);
  EXPECT_DOUBLE_EQ(IntegrationStep(StepUse::kVelocityValidation, 0.05, {&plain}, 1.0), 0.05);
  // A configured step longer than a tenth of the grid does not lengthen it.
  EXPECT_DOUBLE_EQ(IntegrationStep(StepUse::kVelocityValidation, 0.5, {}, 1.0), 0.1);
}

}  // namespace integration_step_test
}  // namespace vesselid
