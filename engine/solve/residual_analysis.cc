#include "engine/solve/residual_analysis.h"

#include <algorithm>
#include <cmath>

#include "engine/base/chi_square.h"
#include "engine/base/nan.h"
#include "engine/base/parallel_for.h"

namespace vesselid {
namespace {

double Mean(const std::vector<double>& x) {
  double sum = 0.0;
  for (double v : x) sum += v;
  return x.empty() ? 0.0 : sum / static_cast<double>(x.size());
}

// 1/N sum_t (a_{t+k} - mean a)(b_t - mean b) over the t where both exist; k may be negative.
double Covariance(const std::vector<double>& a, double mean_a, const std::vector<double>& b,
                  double mean_b, int k) {
  const int n = static_cast<int>(a.size());
  const int first = std::max(0, -k), last = std::min(n, n - k);  // t in [first, last)
  double sum = 0.0;
  for (int t = first; t < last; ++t) sum += (a[t + k] - mean_a) * (b[t] - mean_b);
  return sum / n;
}

// Largest |dt - median dt| / median dt of increasing times (0 for fewer than 3).
double IntervalSpread(const std::vector<double>& t) {
  if (t.size() < 3) return 0.0;
  std::vector<double> dt(t.size() - 1);
  for (size_t i = 0; i + 1 < t.size(); ++i) dt[i] = t[i + 1] - t[i];
  std::vector<double> sorted = dt;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  if (!(median > 0.0)) return kNaN;
  double spread = 0.0;
  for (double d : dt) spread = std::max(spread, std::abs(d - median) / median);
  return spread;
}

// Each lag is a pass over the record: over a long record (hundreds of thousands of samples)
// the lags are shared out over the cores; a short one stays on the caller's thread, where
// starting threads would cost more than the passes.
int LagThreads(const std::vector<double>& e) { return e.size() >= 50000 ? 0 : 1; }

}  // namespace

int ResidualLags(int samples) {
  if (samples < kResidualMinSamples) return 0;
  return std::min(kResidualMaxLags, samples / 5);
}

std::vector<double> Autocorrelation(const std::vector<double>& e, int max_lag) {
  std::vector<double> r(max_lag + 1, kNaN);
  const double mean = Mean(e);
  const double c0 = Covariance(e, mean, e, mean, 0);
  if (!(c0 > 0.0)) return r;
  ParallelFor(max_lag + 1, LagThreads(e), [&](int k) { r[k] = Covariance(e, mean, e, mean, k) / c0; });
  return r;
}

std::vector<double> CrossCorrelation(const std::vector<double>& e, const std::vector<double>& u,
                                     int max_lag) {
  std::vector<double> r(2 * max_lag + 1, kNaN);
  const double mean_e = Mean(e), mean_u = Mean(u);
  const double scale =
      std::sqrt(Covariance(e, mean_e, e, mean_e, 0) * Covariance(u, mean_u, u, mean_u, 0));
  if (!(scale > 0.0) || e.size() != u.size()) return r;
  ParallelFor(2 * max_lag + 1, LagThreads(e), [&](int i) {
    r[i] = Covariance(e, mean_e, u, mean_u, i - max_lag) / scale;
  });
  return r;
}

double LjungBoxQ(const std::vector<double>& autocorrelation, int n) {
  double sum = 0.0;
  for (size_t k = 1; k < autocorrelation.size(); ++k) {
    sum += autocorrelation[k] * autocorrelation[k] / (n - static_cast<double>(k));
  }
  return static_cast<double>(n) * (n + 2.0) * sum;
}

ResidualAnalysis AnalyseResiduals(const std::string& experiment, const std::string& output,
                                  const std::vector<double>& t, const std::vector<double>& e,
                                  const std::vector<std::string>& input_names,
                                  const std::vector<std::vector<double>>& inputs) {
  ResidualAnalysis a;
  a.experiment = experiment;
  a.output = output;
  a.samples = static_cast<int>(e.size());
  a.interval_spread = IntervalSpread(t);
  a.lags = ResidualLags(a.samples);
  if (a.lags == 0) return a;
  const int n = a.samples, lags = a.lags;
  a.band_99 = kBand99 / std::sqrt(n);
  a.band_95 = kBand95 / std::sqrt(n);
  a.autocorrelation = Autocorrelation(e, lags);
  a.lag1 = a.autocorrelation[1];
  if (std::isnan(a.lag1)) {  // constant residual: nothing to test
    a.lags = 0;
    a.autocorrelation.clear();
    return a;
  }
  a.ljung_box_q = LjungBoxQ(a.autocorrelation, n);
  a.ljung_box_p = ChiSquareUpperTail(a.ljung_box_q, lags);
  a.white = a.ljung_box_p >= kWhitenessLevel;
  for (size_t i = 0; i < inputs.size() && i < input_names.size(); ++i) {
    ResidualCrossCorrelation c;
    c.input = input_names[i];
    c.values = CrossCorrelation(e, inputs[i], lags);
    const std::vector<double> ru = Autocorrelation(inputs[i], lags);
    double bartlett = 1.0;  // sum_{|k|<=L} r_ee(k) r_uu(k), r(-k) = r(k); never below white's
    if (!std::isnan(ru[0])) {
      double sum = 1.0;
      for (int k = 1; k <= lags; ++k) sum += 2.0 * a.autocorrelation[k] * ru[k];
      bartlett = std::max(1.0, sum);
    }
    c.band_99 = kBand99 * std::sqrt(bartlett / n);
    for (int k = 0; k <= lags; ++k) {
      c.correlated |= std::abs(c.values[lags + k]) > c.band_99;  // NaN compares false
    }
    a.input_correlated |= c.correlated;
    a.cross_correlation.push_back(std::move(c));
  }
  return a;
}

}  // namespace vesselid
