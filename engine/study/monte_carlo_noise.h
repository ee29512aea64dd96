// The noise a Monte Carlo study (monte_carlo_study.h) puts on the stage's data: Gaussian
// noise N(0, sigma_c^2) on every sample of each compared output c, and N(0, sigma_u^2) on
// every logged sample of each noisy input u, which the identification then reads as the
// recorded input (errors in variables: the truth was simulated with the input as recorded).
#pragma once

#include <string>
#include <vector>

#include "engine/model/experiment.h"
#include "engine/study/study_options.h"
#include "engine/study/study_stage.h"

namespace vesselid {

struct MonteCarloNoise {
  std::vector<double> output;       // per model output; NaN where none is compared
  std::vector<double> input;        // per model input; 0: the recorded input as it is
  std::vector<bool> output_of_fit;  // per model output: sigma is the fit's residual SD

  bool any_input() const;
};

// The levels `options.noise` gives. With `fit` (the clean samples of the stage's experiments
// at the estimate, truth: estimate) each compared output it does not name takes the fit's
// residual SD over that output's samples,
//   s_c^2 = SSR_c / (n_c - p n_c / n)   (n_c of the n samples, p free unknowns of the stage),
// the degrees of freedom shared out in proportion to the samples. Without `fit` every
// compared output must be named.
bool ResolveMonteCarloNoise(const StudyStage& stage, const MonteCarloOptions& options,
                            const std::vector<std::vector<double>>* fit, MonteCarloNoise* noise,
                            std::string* error);

// The stage's experiments rebuilt from its records as the stage builds them (interpolation,
// segments, weights) after N(0, sigma_u^2) is added, seeded by `seed`, to every present
// sample of the column each noisy input is read from (model units: degree columns are
// radians once read). False (with `error`) when the noisy input cuts the records into other
// experiments than the stage's (input_range), which leaves nothing to compare.
bool NoisyInputExperiments(const StudyStage& stage, const std::vector<double>& input_sigma,
                           unsigned seed, std::vector<Experiment>* experiments, std::string* error);

}  // namespace vesselid
