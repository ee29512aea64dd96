#include "engine/data/latent_input.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

namespace vesselid {
namespace {

// Uniform cubic B-spline: span i of [t0, t0 + n h] carries coefficients i..i+3 with weights
// ((1-u)^3, 3u^3 - 6u^2 + 4, -3u^3 + 3u^2 + 3u + 1, u^3) / 6, u the position in the span.
struct Span {
  int first;
  std::array<double, 4> b;
};

Span SpanAt(double t, double t0, double h, int spans) {
  double s = (t - t0) / h;
  int i = static_cast<int>(std::floor(s));
  i = std::clamp(i, 0, spans - 1);
  const double u = std::clamp(s - i, 0.0, 1.0);
  const double u2 = u * u, u3 = u2 * u;
  return {i,
          {(1 - u) * (1 - u) * (1 - u) / 6.0, (3 * u3 - 6 * u2 + 4) / 6.0,
           (-3 * u3 + 3 * u2 + 3 * u + 1) / 6.0, u3 / 6.0}};
}

// Symmetric positive definite band matrix (half-bandwidth 3) solved in place by Cholesky:
// a[j][d] holds A(j, j + d), d = 0..3.
bool SolveBand(std::vector<std::array<double, 4>>* a, std::vector<double>* b) {
  const int m = static_cast<int>(a->size());
  auto& l = *a;  // overwritten by L^T: l[j][d] = L(j + d, j)
  for (int j = 0; j < m; ++j) {
    double d = l[j][0];
    for (int k = std::max(0, j - 3); k < j; ++k) d -= l[k][j - k] * l[k][j - k];
    if (!(d > 0.0)) return false;
    l[j][0] = std::sqrt(d);
    for (int r = 1; r <= 3 && j + r < m; ++r) {
      double v = l[j][r];
      for (int k = std::max(0, j + r - 3); k < j; ++k) v -= l[k][j - k] * l[k][j + r - k];
      l[j][r] = v / l[j][0];
    }
  }
  std::vector<double>& x = *b;
  for (int j = 0; j < m; ++j) {  // L y = b
    for (int k = std::max(0, j - 3); k < j; ++k) x[j] -= l[k][j - k] * x[k];
    x[j] /= l[j][0];
  }
  for (int j = m - 1; j >= 0; --j) {  // L^T c = y
    for (int r = 1; r <= 3 && j + r < m; ++r) x[j] -= l[j][r] * x[j + r];
    x[j] /= l[j][0];
  }
  return true;
}

struct Candidate {
  double spacing = 0.0;
  int basis = 0;
  double rss = 0.0;
  std::vector<double> coefficients;
};

bool FitSpacing(const Channel& c, double spacing, Candidate* out) {
  const double t0 = c.t.front(), t1 = c.t.back();
  const int spans = std::max(1, static_cast<int>(std::ceil((t1 - t0) / spacing - 1e-9)));
  const int m = spans + 3;
  std::vector<std::array<double, 4>> a(m, {0.0, 0.0, 0.0, 0.0});
  std::vector<double> rhs(m, 0.0);
  for (size_t k = 0; k < c.t.size(); ++k) {
    const Span s = SpanAt(c.t[k], t0, spacing, spans);
    for (int p = 0; p < 4; ++p) {
      rhs[s.first + p] += s.b[p] * c.value[k];
      for (int q = p; q < 4; ++q) a[s.first + p][q - p] += s.b[p] * s.b[q];
    }
  }
  // Second-difference penalty, tiny against the data term (scale: mean diagonal).
  double mean_diagonal = 0.0;
  for (const auto& row : a) mean_diagonal += row[0];
  const double lambda = 1e-8 * mean_diagonal / m;
  for (int j = 0; j + 2 < m; ++j) {
    const double d[3] = {1.0, -2.0, 1.0};
    for (int p = 0; p < 3; ++p) {
      for (int q = p; q < 3; ++q) a[j + p][q - p] += lambda * d[p] * d[q];
    }
  }
  if (!SolveBand(&a, &rhs)) return false;
  double rss = 0.0;
  for (size_t k = 0; k < c.t.size(); ++k) {
    const Span s = SpanAt(c.t[k], t0, spacing, spans);
    double v = 0.0;
    for (int p = 0; p < 4; ++p) v += s.b[p] * rhs[s.first + p];
    rss += (c.value[k] - v) * (c.value[k] - v);
  }
  *out = {spacing, m, rss, std::move(rhs)};
  return true;
}

}  // namespace

bool LatentInputSpline::Fit(const Channel& channel, const LatentInputOptions& options,
                            std::string* error) {
  const int n = static_cast<int>(channel.t.size());
  if (n < 8) {
    *error = "input noise: " + std::to_string(n) + " samples, at least 8 are needed";
    return false;
  }
  std::vector<double> intervals;
  for (int k = 1; k < n; ++k) intervals.push_back(channel.t[k] - channel.t[k - 1]);
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  sample_interval_ = intervals[intervals.size() / 2];
  const double span = channel.t.back() - channel.t.front();
  if (!(sample_interval_ > 0.0) || !(span > 0.0)) {
    *error = "input noise: the samples do not advance in time";
    return false;
  }
  std::vector<double> spacings;
  if (options.knot_spacing > 0.0) {
    if (options.knot_spacing < 2.0 * sample_interval_) {
      char text[200];
      std::snprintf(text, sizeof(text),
                    "input noise: knots %g s is shorter than two sample intervals (%g s)",
                    options.knot_spacing, 2.0 * sample_interval_);
      *error = text;
      return false;
    }
    spacings.push_back(options.knot_spacing);
  } else {
    // 2, 3, 4, 6, 8, 12, ... sample intervals while at least 4 spans fit (n - m > n / 4).
    for (double f = 2.0; f * sample_interval_ <= span / 4.0; f *= std::sqrt(2.0)) {
      const double h = std::round(f) * sample_interval_;
      if (spacings.empty() || h > spacings.back()) spacings.push_back(h);
    }
    if (spacings.empty()) spacings.push_back(span / 4.0);
  }
  Candidate best;
  double best_score = std::numeric_limits<double>::infinity();
  for (double h : spacings) {
    Candidate c;
    if (!FitSpacing(channel, h, &c) || n - c.basis < n / 4) continue;
    const double score = options.sigma > 0.0
                             ? c.rss + 2.0 * options.sigma * options.sigma * c.basis
                             : n * c.rss / (double(n - c.basis) * (n - c.basis));
    if (score < best_score) {
      best_score = score;
      best = std::move(c);
    }
  }
  if (best.coefficients.empty()) {
    *error = "input noise: the spline fit failed (too few samples for the knot spacing)";
    return false;
  }
  t0_ = channel.t.front();
  t1_ = channel.t.back();
  spacing_ = best.spacing;
  coefficients_ = std::move(best.coefficients);
  samples_ = n;
  residual_rms_ = std::sqrt(best.rss / n);
  sigma_ = options.sigma > 0.0 ? options.sigma : std::sqrt(best.rss / (n - best.basis));
  return true;
}

double LatentInputSpline::operator()(double t) const {
  const int spans = static_cast<int>(coefficients_.size()) - 3;
  const Span s = SpanAt(std::clamp(t, t0_, t1_), t0_, spacing_, spans);
  double v = 0.0;
  for (int p = 0; p < 4; ++p) v += s.b[p] * coefficients_[s.first + p];
  return v;
}

std::vector<double> LatentInputSpline::At(const std::vector<double>& times) const {
  std::vector<double> values;
  values.reserve(times.size());
  for (double t : times) values.push_back((*this)(t));
  return values;
}

}  // namespace vesselid
