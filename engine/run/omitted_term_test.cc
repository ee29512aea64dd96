#include "engine/run/omitted_term_test.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "Eigen/Dense"
#include "engine/model/omitted_terms.h"
#include "engine/run/innovation_structure.h"

namespace vesselid {
namespace {

// Eigenvalues below this share of the largest (of a matrix scaled to unit diagonal) count as
// zero: a candidate the model already has, or two free unknowns the data cannot tell apart.
constexpr double kScoreRankTolerance = 1e-7;

bool Velocity(const ModelInfo& info, int state) {
  const std::string unit = info.StateUnit(state);
  return unit.size() > 2 && unit.compare(unit.size() - 2, 2, "/s") == 0;
}

// A state whose equation is kinematic (a heading or position: psi' = r): a term added there
// would blame the ship for a disturbance placed on the wrong state.
bool Kinematic(const ModelInfo& info, int state) {
  const std::string unit = info.StateUnit(state);
  return unit == "rad" || unit == "deg" || unit == "m";
}

// The candidates: per state the process noise acts on, a constant and sign(z), z, z|z|, z^3 of each
// velocity state and each input, z scaled by the signal's size in the records (a state's
// largest |x| over the operating range, an input's root mean square; a signal that never
// moves is left out).
std::vector<OmittedTerm> Candidates(const OutputErrorProblem& problem,
                                    const std::vector<double>& operating_range) {
  const ModelHandle& model = problem.model();
  const ModelInfo& info = model.info();
  const int nx = static_cast<int>(info.states.size()), nu = static_cast<int>(info.inputs.size());
  std::vector<OmittedTerm> terms;
  std::vector<int> targets;
  for (int i = 0; i < nx && i < static_cast<int>(problem.disturbance().process.size()); ++i) {
    if (problem.disturbance().process[i] >= 0 && !Kinematic(info, i)) targets.push_back(i);
  }
  if (targets.empty()) return terms;
  const std::vector<double> state_scale(operating_range.begin(), operating_range.begin() + nx);
  std::vector<double> input_power(nu, 0.0);
  std::vector<long> input_count(nu, 0);
  for (const Experiment& x : problem.experiments()) {
    for (size_t r = 0; r + x.num_inputs <= x.input_cache.size(); r += x.num_inputs) {
      for (int u = 0; u < nu && u < x.num_inputs; ++u) {
        const double v = x.input_cache[r + u];
        if (!std::isfinite(v)) continue;
        input_power[u] += v * v;
        ++input_count[u];
      }
    }
  }
  std::vector<OmittedTerm> signals;
  for (int i = 0; i < nx; ++i) {
    if (!Velocity(info, i) || !(state_scale[i] > 0.0) || !std::isfinite(state_scale[i])) continue;
    OmittedTerm s;
    s.signal = OmittedTerm::Signal::kState;
    s.index = i;
    s.scale = state_scale[i];
    signals.push_back(s);
  }
  for (int u = 0; u < nu; ++u) {
    const double rms = input_count[u] > 0 ? std::sqrt(input_power[u] / input_count[u]) : 0.0;
    if (!(rms > 0.0) || !std::isfinite(rms)) continue;
    OmittedTerm s;
    s.signal = OmittedTerm::Signal::kInput;
    s.index = u;
    s.scale = rms;
    signals.push_back(s);
  }
  for (int target : targets) {
    OmittedTerm constant;
    constant.target = target;
    terms.push_back(constant);
    for (OmittedTerm s : signals) {
      s.target = target;
      for (int power : {0, 1, 2, 3}) {
        s.power = power;
        terms.push_back(s);
      }
    }
  }
  return terms;
}

// "r|r| in r'", "1 in r'", "delta^3 in v'".
std::string Label(const ModelInfo& info, const OmittedTerm& t) {
  const std::string in = " in " + info.states[t.target] + "'";
  if (t.signal == OmittedTerm::Signal::kConstant) return "a constant" + in;
  const std::string z =
      t.signal == OmittedTerm::Signal::kState ? info.states[t.index] : info.inputs[t.index];
  if (t.power == 2) return z + "|" + z + "|" + in;
  if (t.power == 3) return z + "^3" + in;
  if (t.power == 0) return "sign(" + z + ")" + in;
  return z + in;
}

// The pseudo-inverse of a symmetric positive semi-definite matrix scaled to unit diagonal,
// eigenvalues below kScoreRankTolerance times the largest dropped; `rank` gets the kept count.
Eigen::MatrixXd PseudoInverse(const Eigen::MatrixXd& m, int* rank) {
  *rank = 0;
  if (m.rows() == 0) return m;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(m);
  const Eigen::VectorXd& values = eigen.eigenvalues();
  const double largest = values.maxCoeff();
  Eigen::VectorXd inverse = Eigen::VectorXd::Zero(values.size());
  for (int i = 0; i < values.size(); ++i) {
    if (largest > 0.0 && values[i] > kScoreRankTolerance * largest) {
      inverse[i] = 1.0 / values[i];
      ++*rank;
    }
  }
  return eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace

std::vector<OmittedTermTest> TestOmittedTerms(const OutputErrorProblem& problem,
                                              const std::vector<double>& operating_range) {
  std::vector<OmittedTermTest> tests;
  if (!problem.filter_error()) return tests;
  const std::vector<OmittedTerm> terms = Candidates(problem, operating_range);
  if (terms.empty()) return tests;
  const ModelInfo& info = problem.model().info();
  const int na = static_cast<int>(terms.size());
  for (size_t e = 0; e < problem.experiments().size(); ++e) {
    OmittedTermScore score;
    std::vector<std::string> free;
    if (!problem.ScoreOmittedTerms(static_cast<int>(e), terms, &score, &free)) {
      OmittedTermTest skipped;  // rank 0: not scored
      skipped.experiment = problem.experiments()[e].name;
      skipped.samples = problem.experiments()[e].num_samples();
      skipped.memory = OmittedTermScoreExceedsMemory(skipped.samples, problem.num_free() + na);
      tests.push_back(skipped);
      continue;
    }
    const int nb = static_cast<int>(free.size());
    // Scaled to unit diagonal: the unknowns' units (a spectral density of 1e-7 beside a time
    // constant of 30 s) must not decide what counts as rank.
    Eigen::VectorXd d = score.information.diagonal();
    for (int i = 0; i < d.size(); ++i) d[i] = d[i] > 0.0 ? 1.0 / std::sqrt(d[i]) : 0.0;
    const Eigen::MatrixXd info_scaled = d.asDiagonal() * score.information * d.asDiagonal();
    const Eigen::VectorXd g = d.asDiagonal() * score.gradient;
    int rank_b = 0;
    const Eigen::MatrixXd ibb_inverse = PseudoInverse(info_scaled.topLeftCorner(nb, nb), &rank_b);
    const Eigen::MatrixXd iab = info_scaled.bottomLeftCorner(na, nb);
    const Eigen::MatrixXd c =
        info_scaled.bottomRightCorner(na, na) - iab * ibb_inverse * iab.transpose();
    const Eigen::VectorXd efficient = g.tail(na) - iab * ibb_inverse * g.head(nb);
    OmittedTermTest test;
    test.experiment = problem.experiments()[e].name;
    test.samples = score.samples;
    const Eigen::MatrixXd c_inverse = PseudoInverse(c, &test.rank);
    if (test.rank == 0) continue;  // every candidate is one the model has
    test.statistic = efficient.dot(c_inverse * efficient);
    test.p_value = ChiSquareTail(test.statistic, test.rank);
    for (int j = 0; j < na; ++j) {
      if (!(c(j, j) > kScoreRankTolerance)) continue;
      const double alone = efficient[j] * efficient[j] / c(j, j);
      if (!(alone <= test.strongest_statistic)) {
        test.strongest_statistic = alone;
        test.strongest = Label(info, terms[j]);
      }
    }
    tests.push_back(test);
  }
  return tests;
}

void AddOmittedTermFindings(const std::string& stage, const std::vector<OmittedTermTest>& tests,
                            std::vector<std::string>* notes, std::vector<Finding>* findings) {
  if (tests.empty()) return;
  int scored = 0;
  for (const OmittedTermTest& t : tests) scored += t.rank > 0;
  const double level = kInnovationStructureLevel / std::max(scored, 1);
  std::vector<const OmittedTermTest*> failed;
  for (const OmittedTermTest& t : tests) {
    if (t.rank == 0) {
      notes->push_back("omitted terms: " + t.experiment + ": not scored (" +
                       (t.memory ? "the derivatives over " + std::to_string(t.samples) +
                                       " samples would exceed the test's memory"
                                 : std::string("the filter diverged with the candidates")) +
                       "): a free run that drifts is not excused");
      continue;
    }
    char text[400];
    std::snprintf(text, sizeof(text),
                  "omitted terms: %s: score statistic %.1f on %d candidate terms through the "
                  "filter (p %.2g); strongest %s (%.1f)",
                  t.experiment.c_str(), t.statistic, t.rank, t.p_value, t.strongest.c_str(),
                  t.strongest_statistic);
    notes->push_back(text);
    if (t.p_value < level) failed.push_back(&t);
  }
  if (failed.empty()) return;
  const OmittedTermTest* worst = failed.front();
  std::string which;
  for (const OmittedTermTest* t : failed) {
    char part[200];
    std::snprintf(part, sizeof(part), "%s%s (%.1f on %d, p %.2g, strongest %s)",
                  which.empty() ? "" : ", ", t->experiment.c_str(), t->statistic, t->rank,
                  t->p_value, t->strongest.c_str());
    which += part;
    if (t->p_value < worst->p_value) worst = t;
  }
  Finding f = MakeFinding(
      FindingKind::kDisturbanceAbsorbsStructure,
      "the filter-error likelihood asks for terms the ship model lacks in " +
          std::to_string(failed.size()) + " of " + std::to_string(scored) +
          " experiment(s): " + which +
          "; the process noise stands in for them (a rudder dead band or rate limit, a missing "
          "damping term), and a free run that drifts is not the gusts' doing alone");
  f.stage = stage;
  f.experiment = failed.size() == 1 ? worst->experiment : "";
  f.value = worst->p_value;
  f.threshold = level;
  findings->push_back(std::move(f));
}

}  // namespace vesselid
