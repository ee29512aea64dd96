#include "engine/output/residual_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "engine/base/json_number.h"
#include "engine/diagnose/residual_findings.h"

namespace vesselid {
namespace {

using nlohmann::json;

json Numbers(const std::vector<double>& values) {
  json j = json::array();
  for (double v : values) j.push_back(JsonNumber(v));
  return j;
}

// Rank for "worst first": coloured, then input-correlated, then white; |lag-1| within.
bool WorseChannel(const ResidualAnalysis* a, const ResidualAnalysis* b) {
  const int ra = !a->tested() ? 3 : !a->white ? 0 : a->input_correlated ? 1 : 2;
  const int rb = !b->tested() ? 3 : !b->white ? 0 : b->input_correlated ? 1 : 2;
  if (ra != rb) return ra < rb;
  return std::abs(a->lag1) > std::abs(b->lag1);
}

}  // namespace

std::vector<const ResidualAnalysis*> ResidualsWorstFirst(
    const std::vector<ResidualAnalysis>& analyses) {
  std::vector<const ResidualAnalysis*> list;
  for (const ResidualAnalysis& a : analyses) list.push_back(&a);
  std::stable_sort(list.begin(), list.end(), WorseChannel);
  return list;
}

json ResidualAnalysisToJson(const ResidualAnalysis& a) {
  json cross = json::object();
  for (const ResidualCrossCorrelation& c : a.cross_correlation) {
    std::vector<int> lags;
    for (int k = -a.lags; k <= a.lags; ++k) lags.push_back(k);
    cross[c.input] = {{"lags", lags},
                      {"values", Numbers(c.values)},
                      {"band_99", JsonNumber(c.band_99)},
                      {"correlated", c.correlated}};
  }
  return {{"experiment", a.experiment},
          {"output", a.output},
          {"samples", a.samples},
          {"lags", a.lags},
          {"tested", a.tested()},
          {"autocorrelation", Numbers(a.autocorrelation)},
          {"band_99", JsonNumber(a.band_99)},
          {"band_95", JsonNumber(a.band_95)},
          {"ljung_box",
           {{"q", JsonNumber(a.ljung_box_q)}, {"dof", a.lags}, {"p", JsonNumber(a.ljung_box_p)}}},
          {"lag1", JsonNumber(a.lag1)},
          {"white", a.white},
          {"cross_correlation", cross},
          {"input_correlated", a.input_correlated},
          {"interval_spread", JsonNumber(a.interval_spread)},
          {"irregular_sampling", a.irregular()},
          {"noise_free", a.noise_free},
          {"input_noise_share", JsonNumber(a.input_noise_share)}};
}

json ResidualAnalysesToJson(const std::vector<ResidualAnalysis>& analyses, JsonSplices* splices) {
  return JsonSplices::ArrayIn(splices, analyses.size(),
                              [&analyses](size_t i) { return ResidualAnalysisToJson(analyses[i]); });
}

std::string ResidualAnalysesText(const std::vector<ResidualAnalysis>& analyses,
                                 const std::string& indent) {
  std::vector<std::string> outputs;
  std::map<std::string, std::vector<const ResidualAnalysis*>> by_output;
  for (const ResidualAnalysis* a : ResidualsWorstFirst(analyses)) {
    if (by_output[a->output].empty()) outputs.push_back(a->output);
    by_output[a->output].push_back(a);
  }
  std::ostringstream out;
  for (const std::string& output : outputs) {
    const std::vector<const ResidualAnalysis*>& list = by_output[output];
    if (list.size() <= kResidualLinesMax) {
      // In the experiments' order.
      for (const ResidualAnalysis& a : analyses) {
        if (a.output == output) {
          out << indent << "residuals " << a.experiment << " " << a.output << ": "
              << DescribeResiduals(a) << "\n";
        }
      }
      continue;
    }
    int white = 0, tested = 0, correlated = 0, irregular = 0;
    for (const ResidualAnalysis* a : list) {
      tested += a->tested();
      white += a->tested() && a->white;
      correlated += a->input_correlated;
      irregular += a->irregular();
    }
    out << indent << "residuals " << output << ": " << white << " of " << tested
        << " experiments white";
    if (tested < static_cast<int>(list.size())) {
      out << " (" << list.size() - tested << " too short to test)";
    }
    if (correlated > 0) out << ", " << correlated << " correlated with past inputs";
    if (irregular > 0) out << ", " << irregular << " irregularly sampled";
    out << "\n";
    size_t named = 0;
    for (const ResidualAnalysis* a : list) {
      if (named == 6 || !a->tested() || (a->white && !a->input_correlated)) break;
      out << indent << "  " << a->experiment << ": " << DescribeResiduals(*a) << "\n";
      ++named;
    }
    const size_t doubtful = static_cast<size_t>(tested - white) +
                            std::count_if(list.begin(), list.end(), [](const ResidualAnalysis* a) {
                              return a->tested() && a->white && a->input_correlated;
                            });
    if (doubtful > named) out << indent << "  ... " << doubtful - named << " more\n";
  }
  return out.str();
}

}  // namespace vesselid
