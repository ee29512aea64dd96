#include "engine/run/run_config.h"

namespace vesselid {

const char* StageKindToString(StageConfig::Kind kind) {
  switch (kind) {
    case StageConfig::Kind::kLeastSquares:
      return "least_squares";
    case StageConfig::Kind::kStepRegression:
      return "step_regression";
    case StageConfig::Kind::kOutputError:
      break;
  }
  return "output_error";
}

bool StringToStageKind(const std::string& text, StageConfig::Kind* kind) {
  for (StageConfig::Kind k : {StageConfig::Kind::kOutputError, StageConfig::Kind::kLeastSquares,
                              StageConfig::Kind::kStepRegression}) {
    if (text == StageKindToString(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

const char* FinalChoiceToString(FinalChoice choice) {
  return choice == FinalChoice::kLast ? "last" : "best_validation";
}

bool StringToFinalChoice(const std::string& text, FinalChoice* choice) {
  for (FinalChoice c : {FinalChoice::kBestValidation, FinalChoice::kLast}) {
    if (text == FinalChoiceToString(c)) {
      *choice = c;
      return true;
    }
  }
  return false;
}

const char* HeldOutPerExperimentToString(HeldOutPerExperiment mode) {
  return mode == HeldOutPerExperiment::kHold ? "hold" : "fit";
}

bool StringToHeldOutPerExperiment(const std::string& text, HeldOutPerExperiment* mode) {
  for (HeldOutPerExperiment m : {HeldOutPerExperiment::kFit, HeldOutPerExperiment::kHold}) {
    if (text == HeldOutPerExperimentToString(m)) {
      *mode = m;
      return true;
    }
  }
  return false;
}

const char* HeldOutStartModeToString(HeldOutStart::Mode mode) {
  return mode == HeldOutStart::Mode::kRefitted ? "refitted" : "measured";
}

bool StringToHeldOutStartMode(const std::string& text, HeldOutStart::Mode* mode) {
  for (HeldOutStart::Mode m : {HeldOutStart::Mode::kMeasured, HeldOutStart::Mode::kRefitted}) {
    if (text == HeldOutStartModeToString(m)) {
      *mode = m;
      return true;
    }
  }
  return false;
}

const ExperimentSpec* RunConfig::FindExperiment(const std::string& name) const {
  for (const ExperimentSpec& e : experiments) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

}  // namespace vesselid
