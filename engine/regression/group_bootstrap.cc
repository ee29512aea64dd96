#include "engine/regression/group_bootstrap.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "engine/base/case_seed.h"
#include "engine/base/parallel_for.h"

namespace vesselid {

bool GroupBootstrapOptions::IsValid(std::string* error) const {
  if (runs < 0 || runs == 1) {
    *error = "bootstrap: runs must be 0 (none) or >= 2, not " + std::to_string(runs);
    return false;
  }
  if (blocks < 2) {
    *error = "bootstrap: blocks must be >= 2, not " + std::to_string(blocks);
    return false;
  }
  if (threads < 0) {
    *error = "bootstrap: threads must be >= 0";
    return false;
  }
  return true;
}

int BootstrapSummary::Find(const std::string& name) const {
  const auto found = std::find(names.begin(), names.end(), name);
  return found == names.end() ? -1 : static_cast<int>(found - names.begin());
}

std::string BootstrapDescription(const BootstrapSummary& summary) {
  std::string text = "bootstrap over " + std::to_string(summary.groups) + " " +
                     summary.resampled + ", " + std::to_string(summary.runs) + " replicates";
  if (summary.failed > 0) text += " (" + std::to_string(summary.failed) + " not fitted)";
  return text + (summary.lambda_held ? ", lambda held" : ", lambda selected per replicate");
}

double SortedPercentile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double position = q * (sorted.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(position));
  const size_t above = std::min(below + 1, sorted.size() - 1);
  const double t = position - below;
  return sorted[below] + t * (sorted[above] - sorted[below]);
}

bool RunGroupBootstrap(const std::vector<int>& strata, const std::vector<std::string>& names,
                       const std::vector<std::string>& coefficient_names,
                       const BootstrapReplicate& replicate, const GroupBootstrapOptions& options,
                       BootstrapSummary* summary, std::string* error) {
  if (!options.IsValid(error)) return false;
  int groups = 0;
  for (int size : strata) {
    if (size <= 0) {
      *error = "bootstrap: a stratum has no groups";
      return false;
    }
    groups += size;
  }
  const int runs = options.runs;
  const size_t nv = names.size(), nc = coefficient_names.size();
  std::vector<std::vector<double>> values(runs), coefficients(runs);
  std::vector<char> fitted(runs, 0);
  ParallelFor(runs, options.threads, [&](int r) {
    std::mt19937_64 random(CaseSeed(options.seed, kBootstrapPart, r));
    std::vector<int> counts(groups, 0);
    for (int s = 0, first = 0; s < static_cast<int>(strata.size()); first += strata[s++]) {
      std::uniform_int_distribution<int> draw(0, strata[s] - 1);
      for (int k = 0; k < strata[s]; ++k) ++counts[first + draw(random)];
    }
    std::vector<double> v, c;
    if (!replicate(counts, &v, &c)) return;
    if (v.size() != nv || (!c.empty() && c.size() != nc)) return;
    for (double x : v) {
      if (!std::isfinite(x)) return;
    }
    values[r] = std::move(v);
    coefficients[r] = std::move(c);
    fitted[r] = 1;
  });

  BootstrapSummary s;
  s.runs = runs;
  s.groups = groups;
  s.lambda_held = options.hold_lambda;
  s.names = names;
  s.coefficient_names = coefficient_names;
  int good = 0;
  for (char f : fitted) good += f;
  s.failed = runs - good;
  if (good < 2) {
    *error = "bootstrap: " + std::to_string(good) + " of " + std::to_string(runs) +
             " replicates could be fitted";
    return false;
  }
  for (size_t q = 0; q < nv; ++q) {
    std::vector<double> x;
    for (int r = 0; r < runs; ++r) {
      if (fitted[r]) x.push_back(values[r][q]);
    }
    double mean = 0.0, square = 0.0;
    for (double v : x) mean += v / x.size();
    for (double v : x) square += (v - mean) * (v - mean);
    std::sort(x.begin(), x.end());
    s.std_error.push_back(std::sqrt(square / (x.size() - 1)));
    s.lower.push_back(SortedPercentile(x, 0.025));
    s.upper.push_back(SortedPercentile(x, 0.975));
  }
  for (size_t q = 0; q < nc; ++q) {
    int zero = 0, counted = 0;
    for (int r = 0; r < runs; ++r) {
      if (!fitted[r] || coefficients[r].empty() || !std::isfinite(coefficients[r][q])) continue;
      ++counted;
      zero += coefficients[r][q] == 0.0;
    }
    s.zero_share.push_back(counted > 0 ? double(zero) / counted
                                       : std::numeric_limits<double>::quiet_NaN());
  }
  *summary = std::move(s);
  return true;
}

}  // namespace vesselid
