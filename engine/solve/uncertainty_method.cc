#include "engine/solve/uncertainty_method.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesselid {
namespace {

// Ratios in decreasing order, at most `count`, as "K 12x, T1 7.4x".
std::string DescribeRatios(std::vector<StdErrorRatio> ratios, size_t count) {
  std::sort(ratios.begin(), ratios.end(),
            [](const StdErrorRatio& a, const StdErrorRatio& b) { return a.ratio() > b.ratio(); });
  std::string text;
  for (size_t i = 0; i < ratios.size() && i < count; ++i) {
    char item[128];
    std::snprintf(item, sizeof(item), "%s%s %.2gx", i > 0 ? ", " : "", ratios[i].name.c_str(),
                  ratios[i].ratio());
    text += item;
  }
  return text;
}

}  // namespace

const char* UncertaintyMethodToString(UncertaintyMethod method) {
  switch (method) {
    case UncertaintyMethod::kAuto:
      return "auto";
    case UncertaintyMethod::kHessian:
      return "hessian";
    case UncertaintyMethod::kSandwichHac:
      return "sandwich_hac";
    case UncertaintyMethod::kBlockBootstrap:
      return "block_bootstrap";
    case UncertaintyMethod::kExperimentBootstrap:
      return "experiment_bootstrap";
  }
  return "auto";
}

bool StringToUncertaintyMethod(const std::string& text, UncertaintyMethod* method) {
  for (UncertaintyMethod m :
       {UncertaintyMethod::kAuto, UncertaintyMethod::kHessian, UncertaintyMethod::kSandwichHac,
        UncertaintyMethod::kBlockBootstrap, UncertaintyMethod::kExperimentBootstrap}) {
    if (text == UncertaintyMethodToString(m)) {
      *method = m;
      return true;
    }
  }
  return false;
}

std::vector<StdErrorRatio> StdErrorRatios(const OutputErrorProblem& problem,
                                          const Uncertainty& hessian, const Uncertainty& hac) {
  std::vector<StdErrorRatio> ratios;
  for (size_t i = 0; i < hessian.variables.size(); ++i) {
    const Variable& v = problem.variables()[hessian.variables[i]];
    if (v.kind != Variable::Kind::kParameter || v.experiment >= 0) continue;
    const double a = hessian.std_errors[i], b = hac.StdError(hessian.variables[i]);
    if (!(a > 0.0) || !std::isfinite(a) || !(b > 0.0) || !std::isfinite(b)) continue;
    ratios.push_back({v.name, a, b});
  }
  return ratios;
}

UncertaintyMethod ChooseUncertaintyMethod(const std::vector<StdErrorRatio>& ratios) {
  for (const StdErrorRatio& r : ratios) {
    if (r.ratio() > kHacRatioLimit) return UncertaintyMethod::kSandwichHac;
  }
  return UncertaintyMethod::kHessian;
}

bool ComputeStageUncertainty(const UncertaintyOptions& configured, OutputErrorProblem* problem,
                             double final_cost, Uncertainty* uncertainty,
                             std::vector<std::string>* notes, std::vector<Finding>* findings,
                             SolutionJacobian* solution) {
  // A bootstrap replaces these figures after the final solve; until then, those of `auto`.
  UncertaintyOptions options = configured;
  if (IsBootstrap(options.method)) options.method = UncertaintyMethod::kAuto;
  // One Jacobian at the optimum serves the Hessian covariance, the HAC and (via `solution`)
  // the local analysis.
  SolutionJacobian evaluated;
  SolutionJacobian* target = solution != nullptr ? solution : &evaluated;
  const SolutionJacobian* shared =
      EvaluateSolutionJacobian(problem, options.hac.num_threads, target) ? target : nullptr;
  Uncertainty hessian;
  if (!ComputeUncertainty(problem, final_cost, &hessian, shared)) {
    *uncertainty = hessian;
    return false;
  }
  Uncertainty hac;
  if (!ComputeHacCovariance(options.hac, problem, hessian, &hac, shared)) {
    *uncertainty = hessian;
    if (options.method == UncertaintyMethod::kSandwichHac) {
      uncertainty->available = false;
      uncertainty->message = "sandwich_hac: " + hac.message;
      return false;
    }
    notes->push_back("uncertainty: the HAC covariance could not be computed (" + hac.message +
                     "); the Hessian's assumes white residuals");
    return true;
  }
  const std::vector<StdErrorRatio> ratios = StdErrorRatios(*problem, hessian, hac);
  std::vector<StdErrorRatio> wide;  // beyond the limit
  for (const StdErrorRatio& r : ratios) {
    if (r.ratio() > kHacRatioLimit) wide.push_back(r);
  }
  UncertaintyMethod chosen = options.method;
  char limit[32];
  std::snprintf(limit, sizeof(limit), "%g", kHacRatioLimit);
  if (options.method == UncertaintyMethod::kAuto) {
    chosen = ChooseUncertaintyMethod(ratios);
    if (chosen == UncertaintyMethod::kSandwichHac) {
      hac.method_reason = "auto: the HAC standard error exceeds " + std::string(limit) +
                          "x the Hessian's (residuals serially correlated): " +
                          DescribeRatios(wide, 6);
    } else {
      hessian.method_reason = "auto: the HAC standard errors are within " + std::string(limit) +
                              "x the Hessian's" +
                              (ratios.empty() ? "" : " (" + DescribeRatios(ratios, 3) + ")");
    }
  } else if (chosen == UncertaintyMethod::kSandwichHac) {
    hac.method_reason = "configured" +
                        (ratios.empty() ? "" : " (HAC / Hessian: " + DescribeRatios(ratios, 6) + ")");
  } else {
    hessian.method_reason = "configured";
    if (!wide.empty()) {
      std::sort(wide.begin(), wide.end(), [](const StdErrorRatio& a, const StdErrorRatio& b) {
        return a.ratio() > b.ratio();
      });
      std::string text = "the Hessian intervals are too narrow (residuals serially correlated): ";
      for (size_t i = 0; i < wide.size(); ++i) {
        char item[256];
        std::snprintf(item, sizeof(item), "%s%s: Hessian SE %.2g is %.2gx narrower than the HAC SE %.2g",
                      i > 0 ? "; " : "", wide[i].name.c_str(), wide[i].hessian, wide[i].ratio(),
                      wide[i].hac);
        text += item;
      }
      Finding narrow = MakeFinding(FindingKind::kNarrowIntervals,
                                   text + " (method sandwich_hac or auto reports the HAC)");
      narrow.parameter = wide[0].name;
      narrow.value = wide[0].ratio();
      narrow.threshold = kHacRatioLimit;
      narrow.count = static_cast<int>(wide.size());
      findings->push_back(std::move(narrow));
    }
  }
  if (chosen == UncertaintyMethod::kSandwichHac) {
    hac.hessian_std_errors = hessian.std_errors;
    *uncertainty = std::move(hac);
  } else {
    *uncertainty = std::move(hessian);
  }
  return true;
}

}  // namespace vesselid
