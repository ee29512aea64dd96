#include "engine/run/innovation_structure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "Eigen/Dense"
#include "engine/model/filter_innovations.h"
#include "engine/run/fit_residuals.h"

namespace vesselid {
namespace {

// Fewer samples than this per experiment and output: no test.
constexpr int kMinSamples = 50;

// The three functions of a signal scaled to unit SD: s, s|s|, s^3 (a dead band, backlash and
// cubic or quadratic damping are odd in the motion; the linear term is the test's control).
void AddFeatures(const std::vector<double>& signal, std::vector<std::vector<double>>* features) {
  double mean = 0.0, power = 0.0;
  for (double v : signal) mean += v;
  mean /= signal.size();
  for (double v : signal) power += (v - mean) * (v - mean);
  const double sd = std::sqrt(power / signal.size());
  if (!(sd > 0.0) || !std::isfinite(sd)) return;
  std::vector<double> s(signal.size()), s2(signal.size()), s3(signal.size());
  for (size_t i = 0; i < signal.size(); ++i) {
    const double z = signal[i] / sd;
    s[i] = z;
    s2[i] = z * std::abs(z);
    s3[i] = z * z * z;
  }
  features->push_back(std::move(s));
  features->push_back(std::move(s2));
  features->push_back(std::move(s3));
}

// N R^2 of e on the features with an intercept (least squares by column-pivoted QR).
double LagrangeMultiplier(const std::vector<double>& e,
                          const std::vector<std::vector<double>>& features, int* rank) {
  const int n = static_cast<int>(e.size()), m = static_cast<int>(features.size());
  Eigen::MatrixXd x(n, m + 1);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    x(i, 0) = 1.0;
    for (int j = 0; j < m; ++j) x(i, j + 1) = features[j][i];
    y[i] = e[i];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(x);
  *rank = static_cast<int>(qr.rank()) - 1;
  const Eigen::VectorXd fitted = x * qr.solve(y);
  const double mean = y.mean();
  const double total = (y.array() - mean).square().sum();
  const double explained = (fitted.array() - mean).square().sum();
  return total > 0.0 ? n * explained / total : 0.0;
}

}  // namespace

double ChiSquareTail(double x, int m) {
  if (m <= 0 || !(x >= 0.0)) return std::numeric_limits<double>::quiet_NaN();
  const double k = 2.0 / (9.0 * m);
  const double z = (std::cbrt(x / m) - (1.0 - k)) / std::sqrt(k);
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

std::vector<InnovationStructure> TestInnovationStructure(const OutputErrorProblem& problem) {
  std::vector<InnovationStructure> tests;
  if (!problem.filter_error()) return tests;
  const ModelInfo& info = problem.model().info();
  for (size_t x = 0; x < problem.experiments().size(); ++x) {
    const Experiment& experiment = problem.experiments()[x];
    FilterRun run;
    if (!problem.RunFilter(static_cast<int>(x), 0, &run)) continue;
    const NodeInputs fed_inputs(experiment);
    const size_t num_inputs = fed_inputs.count();
    for (size_t o = 0; o < info.outputs.size(); ++o) {
      // Per sample: the normalised innovation; the rate of change of the output's one-step
      // predictions y - nu over the two samples before it; the inputs at the node before it.
      // All known before the sample, also where an autopilot steers from the measurements (the
      // rudder at the sample and the prediction over the step to it already answer its gust).
      std::vector<double> e, rate;
      std::vector<std::vector<double>> inputs(num_inputs);
      double last_prediction = NAN, last_time = NAN, last_rate = NAN;
      for (int k = 0; k < experiment.num_nodes(); ++k) {
        for (int i = experiment.node_first_sample[k]; i < experiment.node_first_sample[k + 1];
             ++i) {
          if (experiment.samples[i].output != static_cast<int>(o)) continue;
          const double predicted = experiment.samples[i].value - run.innovation[i];
          const double t = experiment.node_time[k];
          double now = NAN;
          if (std::isfinite(last_prediction) && t > last_time) {
            double change = predicted - last_prediction;
            if (experiment.Wrapped(static_cast<int>(o))) {
              change -= 2.0 * M_PI * std::round(change / (2.0 * M_PI));
            }
            now = change / (t - last_time);
          }
          if (std::isfinite(last_rate) && run.variance[i] > 0.0) {
            rate.push_back(last_rate);
            e.push_back(run.innovation[i] / std::sqrt(run.variance[i]));
            fed_inputs.Append(static_cast<size_t>(k - 1), &inputs);
          }
          last_rate = now;
          last_prediction = predicted;
          last_time = t;
        }
      }
      if (static_cast<int>(e.size()) < kMinSamples) continue;
      std::vector<std::vector<double>> features;
      AddFeatures(rate, &features);
      for (size_t u = 0; u < num_inputs && u < info.inputs.size(); ++u) {
        const std::vector<double>& input = inputs[u];
        const bool usable = input.size() == e.size() &&
                            std::all_of(input.begin(), input.end(),
                                        [](double v) { return std::isfinite(v); });
        if (usable) AddFeatures(input, &features);
      }
      if (features.empty()) continue;
      InnovationStructure test;
      test.experiment = experiment.name;
      test.output = info.outputs[o];
      test.samples = static_cast<int>(e.size());
      test.statistic = LagrangeMultiplier(e, features, &test.features);
      test.p_value = ChiSquareTail(test.statistic, test.features);
      tests.push_back(test);
    }
  }
  return tests;
}

void AddInnovationStructureFindings(const std::string& stage,
                                    const std::vector<InnovationStructure>& tests,
                                    std::vector<std::string>* notes,
                                    std::vector<Finding>* findings) {
  if (tests.empty()) return;
  const double level = kInnovationStructureLevel / tests.size();
  std::map<std::string, std::vector<const InnovationStructure*>> by_output;
  for (const InnovationStructure& t : tests) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  "innovation structure: %s %s: N R^2 %.1f on %d functions of the predicted "
                  "motion and the inputs (p %.2g)",
                  t.experiment.c_str(), t.output.c_str(), t.statistic, t.features, t.p_value);
    notes->push_back(text);
    if (t.p_value < level) by_output[t.output].push_back(&t);
  }
  for (const auto& [output, failed] : by_output) {
    std::string which;
    const InnovationStructure* worst = failed.front();
    for (const InnovationStructure* t : failed) {
      char part[160];
      std::snprintf(part, sizeof(part), "%s%s (N R^2 %.1f on %d, p %.2g)",
                    which.empty() ? "" : ", ", t->experiment.c_str(), t->statistic, t->features,
                    t->p_value);
      which += part;
      if (t->p_value < worst->p_value) worst = t;
    }
    Finding f = MakeFinding(
        FindingKind::kDisturbanceAbsorbsStructure,
        "the filter's innovations of " + output + " follow the predicted motion and the inputs in " +
            std::to_string(failed.size()) + " experiment(s): " + which +
            "; under a correct ship model they follow nothing known before their sample, "
            "whatever the noise: the disturbance model (noise:) absorbs structure the ship "
            "model lacks (a rudder dead band or rate limit, a missing damping term)");
    f.stage = stage;
    f.output = output;
    f.experiment = failed.size() == 1 ? worst->experiment : "";
    f.value = worst->p_value;
    f.threshold = level;
    findings->push_back(std::move(f));
  }
}

}  // namespace vesselid
