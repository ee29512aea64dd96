// Why a stage cannot begin (engine/solve/start_failure.h): a simulation that breaks is named
// by experiment, time, outputs and inputs, with the physical conditions the start values
// break; a derivative that is not finite where every value is, by experiment, output, time
// and variable.
#include "engine/solve/start_failure.h"

#include <cmath>

#include "engine/model/model_handle.h"
#include "engine/solve/local_solve.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace start_failure_test {

// x' = -sqrt(a) x + g u, y = x: finite at a = 0, but d sqrt(a)/da is not; g < 0 breaks
// "the gain is positive".
struct SqrtDecay {
  static constexpr int kNumStates = 1;
  static constexpr int kNumInputs = 1;
  static constexpr int kNumOutputs = 1;

  ModelInfo Info() const {
    ModelInfo info;
    info.name = "sqrt_decay";
    info.states = {"x"};
    info.inputs = {"u"};
    info.outputs = {"x"};
    info.parameters = {"a", "g"};
    info.parameter_defaults = {1.0, 1.0};
    return info;
  }
  template <class T, class U>
  bool operator()(const T* x, const U* u, const T* p, T* xdot) const {
    xdot[0] = -sqrt(p[0]) * x[0] + p[1] * u[0];
    return true;
  }
  template <class T, class U>
  void Output(const T* x, const U*, const T*, T* y) const {
    y[0] = x[0];
  }
  std::vector<std::string> Admissibility(const double* p, const double*) const {
    if (p[1] > 0.0) return {};
    return {"the gain g is not positive"};
  }
};

Experiment MakeRun(const ModelHandle& model, double input) {
  Trajectory data;
  data.source = "run.csv";
  data.names = {"u", "x"};
  data.columns.resize(2);
  for (int k = 0; k <= 100; ++k) {
    data.t.push_back(0.1 * k);
    data.columns[0].push_back(k < 50 ? 0.1 : input);
    data.columns[1].push_back(0.01 * k);
  }
  ExperimentSpec spec;
  spec.name = "run";
  spec.inputs = {{"u", "u"}};
  spec.outputs = {{"x", "x"}};
  Experiment experiment;
  std::string error;
  EXPECT_TRUE(BuildExperiment(spec, data, model.info(), {}, &experiment, &error)) << error;
  return experiment;
}

ParameterSpec Free(const std::string& name, double start) {
  ParameterSpec spec;
  spec.name = name;
  spec.start = start;
  spec.lower = -10.0;
  spec.upper = 10.0;
  return spec;
}

TEST(StartFailure, NonFiniteDerivativeNamesTheVariable) {
  const auto model = MakeModelHandle(SqrtDecay{});
  std::string error;
  ParameterSpec a = Free("a", 0.0);
  a.lower = 0.0;
  auto problem = OutputErrorProblem::Create(model.get(), {MakeRun(*model, 0.1)},
                                            {a, Free("g", 1.0)}, {}, &error);
  ASSERT_NE(problem, nullptr) << error;
  EXPECT_EQ(StartFailure(problem.get()),
            "at the start values, experiment 'run': its derivative by a is not finite");
  // The solve that cannot begin says so (Ceres' trust regions evaluate the start on its bound).
  LocalSolveOptions ceres;
  ceres.trust_region = TrustRegion::kLevenbergMarquardt;
  LocalSolveSummary summary;
  EXPECT_FALSE(RunLocalSolve(ceres, problem.get(), &summary));
  EXPECT_EQ(summary.message, StartFailure(problem.get()));
  // The reflective region starts strictly inside the bounds, where the derivative exists.
  LocalSolveOptions reflective;
  reflective.trust_region = TrustRegion::kReflective;
  EXPECT_TRUE(RunLocalSolve(reflective, problem.get(), &summary)) << summary.message;
}

TEST(StartFailure, DivergenceNamesTimeInputsAndBrokenConditions) {
  const auto model = MakeModelHandle(SqrtDecay{});
  std::string error;
  // An input of 1e90 from t = 5 s on, times a gain of -1e300: the state overflows.
  auto problem = OutputErrorProblem::Create(model.get(), {MakeRun(*model, 1e90)},
                                            {Free("a", 1.0), Free("g", -1.0)}, {}, &error);
  ASSERT_NE(problem, nullptr) << error;
  for (const Variable& v : problem->variables()) {
    if (v.name == "g") v.set_value(-1e300);
  }
  EXPECT_EQ(StartFailure(problem.get()),
            "the simulation diverges at the start values: simulation of experiment 'run' "
            "diverges after t = 4.9 s; x not finite at t = 5 s (inputs at t = 4.9 s: u = 0.1); "
            "at these values the gain g is not positive");
}

TEST(StartFailure, NothingWhenTheStartValuesEvaluate) {
  const auto model = MakeModelHandle(SqrtDecay{});
  std::string error;
  auto problem = OutputErrorProblem::Create(model.get(), {MakeRun(*model, 0.1)},
                                            {Free("a", 1.0), Free("g", 1.0)}, {}, &error);
  ASSERT_NE(problem, nullptr) << error;
  EXPECT_EQ(StartFailure(problem.get()), "");
}

}  // namespace start_failure_test
}  // namespace vesselid
