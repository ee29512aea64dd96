// What a Monte Carlo study's runs say per free parameter, and the notes on what they show to
// be doubtful (monte_carlo_study.h):
//   bias = mean(theta^) - theta*,  SD of theta^,  RMSE,  mean reported SE / SD,
//   bias / mean SE,  coverage = share of runs with |theta^ - theta*| <= z se,
// with the binomial standard error of the coverage sqrt(c (1 - c) / N). With a parametric
// bootstrap (truth: estimate) also the stage's own reported SE on the data beside the
// bootstrap SD.
#pragma once

#include <string>
#include <vector>

#include "nlohmann/json.hpp"

namespace vesselid {

struct MonteCarloTruth {
  std::vector<std::string> names;  // free parameters, study order
  std::vector<double> values;      // their truth (the estimate in a bootstrap)
  // Bootstrap only: the stage's reported SE of each on the data (empty otherwise).
  std::vector<double> stage_std_errors;
};

// {runs, usable_runs, parameters: [...]} over the cases' "estimates" and "std_errors".
nlohmann::json MonteCarloSummary(const MonteCarloTruth& truth, double z,
                                 const std::vector<nlohmann::json>& cases);

// One line per doubtful finding, naming the parameter: unusable runs, coverage of the
// reported intervals off the nominal beyond its binomial noise, a bias significant against
// its own noise and sizeable against the reported SE, a bootstrap SD far from the stage's SE.
std::vector<std::string> MonteCarloNotes(const nlohmann::json& summary, double confidence,
                                         bool bootstrap, const std::vector<nlohmann::json>& cases);

}  // namespace vesselid
