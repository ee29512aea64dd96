// How a stage estimates the covariance of its estimate (`uncertainty: {method: ...}`):
//   hessian       s^2 (J^T J)^-1 (covariance.h): right for white residuals;
//   sandwich_hac  A^-1 B A^-1 with the residuals' serial correlation in B (hac_covariance.h);
//   auto          both, and the HAC when residuals are serially correlated (the rule below);
//   block_bootstrap, experiment_bootstrap   the spread of re-solved replicates
//                 (engine/run/bootstrap_uncertainty.h), computed after the stage's final
//                 solve; until then, and where it cannot be, the stage keeps `auto`'s figures.
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/solve/covariance.h"
#include "engine/solve/hac_covariance.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

enum class UncertaintyMethod {
  kAuto,
  kHessian,
  kSandwichHac,
  kBlockBootstrap,
  kExperimentBootstrap
};

inline bool IsBootstrap(UncertaintyMethod method) {
  return method == UncertaintyMethod::kBlockBootstrap ||
         method == UncertaintyMethod::kExperimentBootstrap;
}

const char* UncertaintyMethodToString(UncertaintyMethod method);  // "auto", "hessian", ...
bool StringToUncertaintyMethod(const std::string& text, UncertaintyMethod* method);

// The bootstrap methods' settings (`runs`, `block_length`, `seed`).
struct BootstrapOptions {
  int runs = 100;             // replicates, >= kMinBootstrapRuns
  double block_length = 0.0;  // block_bootstrap: s; 0: auto (sqrt of the experiment's nodes)
  unsigned seed = 1;          // replicate r of part p draws from CaseSeed(seed, p, r)
  int num_threads = 0;        // replicates in parallel; <= 0: the machine's cores
};
inline constexpr int kMinBootstrapRuns = 10;

struct UncertaintyOptions {
  UncertaintyMethod method = UncertaintyMethod::kAuto;
  HacOptions hac;
  BootstrapOptions bootstrap;
  // Noise on measured inputs in the standard errors (input_noise_uncertainty.h): `input_noise:
  // auto` (true) or off, and its refits.
  bool input_noise = true;
  int input_noise_runs = 12;
};

// HAC standard error over the Hessian's above which the residuals count as serially
// correlated: `auto` reports the HAC, `hessian` warns that its intervals are too narrow.
inline constexpr double kHacRatioLimit = 1.5;

// One shared free parameter's standard errors by the two methods.
struct StdErrorRatio {
  std::string name;
  double hessian = 0.0, hac = 0.0;
  double ratio() const { return hac / hessian; }
};

// Per shared free parameter with finite, positive standard errors by both methods.
std::vector<StdErrorRatio> StdErrorRatios(const OutputErrorProblem& problem,
                                          const Uncertainty& hessian, const Uncertainty& hac);

// The rule of `auto`: the HAC when any shared parameter's ratio exceeds kHacRatioLimit (its
// scores are serially correlated), else the Hessian.
UncertaintyMethod ChooseUncertaintyMethod(const std::vector<StdErrorRatio>& ratios);

// The stage's uncertainty by options.method, at the problem's current values (final cost
// `final_cost`). The method used, the Hessian's standard errors beside another's, and why,
// go into `uncertainty`; with `hessian`, a finding (narrow_intervals) when the HAC says its
// intervals are too narrow, and a note when the HAC could not be computed. `solution` (may be
// null) gets the residuals and Jacobian evaluated for the HAC, for later analyses to reuse
// (evaluated after the Hessian covariance, so that the two Jacobians are never held at once).
bool ComputeStageUncertainty(const UncertaintyOptions& options, OutputErrorProblem* problem,
                             double final_cost, Uncertainty* uncertainty,
                             std::vector<std::string>* notes, std::vector<Finding>* findings,
                             SolutionJacobian* solution = nullptr);

}  // namespace vesselid
