// Residual analysis statistics (residual_analysis.h, chi_square.h): the chi-square tail
// against closed forms and table quantiles; the whiteness test on AR(1) series, a random walk
// and white Gaussian noise over a fixed set of seeds; the cross-correlation on a residual
// that follows a delayed input and on one independent of a smooth input.
#include "engine/solve/residual_analysis.h"

#include <cmath>
#include <random>

#include "engine/base/chi_square.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace residual_analysis_test {

// Standard normal samples by Box-Muller on mt19937 (the same on every standard library).
class Gaussian {
 public:
  explicit Gaussian(unsigned seed) : engine_(seed) {}
  double operator()() {
    const double u1 = (engine_() + 1.0) / 4294967297.0, u2 = engine_() / 4294967296.0;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::mt19937 engine_;
};

std::vector<double> Ar1(double rho, int n, unsigned seed) {
  Gaussian g(seed);
  std::vector<double> x(n);
  double state = g() / std::sqrt(1.0 - rho * rho);
  for (int t = 0; t < n; ++t) {
    x[t] = state;
    state = rho * state + g();
  }
  return x;
}

// Q(m, x) for an integer m: e^-x sum_{j<m} x^j / j!.
double UpperGammaInteger(int m, double x) {
  double term = 1.0, sum = 0.0;
  for (int j = 0; j < m; ++j) {
    sum += term;
    term *= x / (j + 1);
  }
  return std::exp(-x) * sum;
}

TEST(ChiSquare, MatchesClosedForms) {
  for (double q : {0.01, 0.3, 1.0, 2.5, 7.0, 20.0, 60.0, 150.0, 400.0}) {
    const double one = std::erfc(std::sqrt(q / 2));
    EXPECT_NEAR(ChiSquareUpperTail(q, 1), one, 1e-12 + 1e-10 * one) << q;
    EXPECT_NEAR(ChiSquareUpperTail(q, 2), std::exp(-q / 2), 1e-300 + 1e-10 * std::exp(-q / 2));
    const double three = one + std::sqrt(2 * q / M_PI) * std::exp(-q / 2);
    EXPECT_NEAR(ChiSquareUpperTail(q, 3), three, 1e-12 + 1e-10 * three) << q;
    for (int dof : {10, 26, 50, 120}) {  // both branches: series below a + 1, fraction above
      const double expected = UpperGammaInteger(dof / 2, q / 2);
      EXPECT_NEAR(ChiSquareUpperTail(q, dof), expected, 1e-300 + 1e-9 * expected)
          << "q " << q << " dof " << dof;
    }
  }
  EXPECT_EQ(ChiSquareUpperTail(0.0, 25), 1.0);
  EXPECT_TRUE(std::isnan(RegularizedUpperGamma(0.0, 1.0)));
  EXPECT_TRUE(std::isnan(RegularizedUpperGamma(1.0, -1.0)));
}

TEST(ChiSquare, MatchesTableQuantiles) {
  struct Quantile {
    double dof, q, tail;
  };
  for (const Quantile& c : {Quantile{1, 3.841458820694124, 0.05},
                            {1, 6.634896601021214, 0.01},
                            {10, 23.209251158954356, 0.01},
                            {25, 37.65248413348277, 0.05},
                            {25, 44.31410489621915, 0.01},
                            {100, 124.34211340400407, 0.05},
                            {100, 135.80672317102676, 0.01}}) {
    EXPECT_NEAR(ChiSquareUpperTail(c.q, c.dof), c.tail, 1e-9) << c.dof << " " << c.q;
  }
  // Far in the tail the value stays positive and decreasing until it underflows.
  const double far = ChiSquareUpperTail(700.0, 25);
  EXPECT_GT(far, 0.0);
  EXPECT_LT(far, 1e-100);
  EXPECT_LT(ChiSquareUpperTail(800.0, 25), far);
}

TEST(ResidualLags, ShortRecordsHaveFewerOrNone) {
  EXPECT_EQ(ResidualLags(9), 0);
  EXPECT_EQ(ResidualLags(10), 2);
  EXPECT_EQ(ResidualLags(60), 12);
  EXPECT_EQ(ResidualLags(300000), 25);
}

TEST(ResidualAnalysis, Ar1IsColouredWithItsCorrelations) {
  const std::vector<double> e = Ar1(0.9, 5000, 7);
  const ResidualAnalysis a = AnalyseResiduals("run", "psi", {}, e, {}, {});
  ASSERT_EQ(a.lags, 25);
  EXPECT_FALSE(a.white);
  EXPECT_NEAR(a.lag1, 0.9, 0.03);
  EXPECT_NEAR(a.autocorrelation[5], std::pow(0.9, 5), 0.08);
  EXPECT_LT(a.ljung_box_p, 1e-16);
  EXPECT_DOUBLE_EQ(a.autocorrelation[0], 1.0);
  EXPECT_NEAR(a.band_99, 2.5758 / std::sqrt(5000.0), 1e-5);
  EXPECT_NEAR(a.band_95, 1.9600 / std::sqrt(5000.0), 1e-5);
}

TEST(ResidualAnalysis, WeakAr1IsFoundInALongRecord) {
  // rho 0.1: r_1 ~ 0.1 against a band of 0.012 at N = 45000 (heading residuals with a
  // little integrated rudder noise look like this).
  const ResidualAnalysis a = AnalyseResiduals("run", "psi", {}, Ar1(0.1, 45000, 3), {}, {});
  EXPECT_FALSE(a.white);
  EXPECT_NEAR(a.lag1, 0.1, 0.02);
}

TEST(ResidualAnalysis, RandomWalkIsColoured) {
  Gaussian g(5);
  std::vector<double> e(3000);
  double walk = 0.0;
  for (double& v : e) v = walk += g();
  const ResidualAnalysis a = AnalyseResiduals("run", "psi", {}, e, {}, {});
  EXPECT_FALSE(a.white);
  EXPECT_GT(a.lag1, 0.95);
}

// White Gaussian residuals: white in about 99 % of records, Q ~ chi2_L (mean L, variance 2L).
// Over 200 fixed seeds the expected number flagged is 2; more than 10 has probability ~1e-5,
// and the mean of Q lies within 4 of its standard errors (sqrt(2 L / 200) = 0.5) of L.
TEST(ResidualAnalysis, WhiteNoisePassesAtTheNominalRate) {
  int coloured = 0;
  double q_sum = 0.0;
  constexpr int kSeeds = 200;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    Gaussian g(1000 + seed);
    std::vector<double> e(2000);
    for (double& v : e) v = 0.3 + 0.01 * g();  // an offset is not colour
    const ResidualAnalysis a = AnalyseResiduals("run", "psi", {}, e, {}, {});
    ASSERT_EQ(a.lags, 25);
    coloured += !a.white;
    q_sum += a.ljung_box_q;
  }
  EXPECT_LE(coloured, 10);
  EXPECT_NEAR(q_sum / kSeeds, 25.0, 2.0);
}

TEST(ResidualAnalysis, ResidualFollowingADelayedInputIsInputCorrelated) {
  Gaussian g(11);
  const int n = 4000;
  std::vector<double> u(n), e(n);
  for (double& v : u) v = g();
  for (int t = 0; t < n; ++t) e[t] = (t >= 3 ? 0.3 * u[t - 3] : 0.0) + g();
  const ResidualAnalysis a = AnalyseResiduals("run", "psi", {}, e, {"delta"}, {u});
  ASSERT_EQ(a.cross_correlation.size(), 1u);
  const ResidualCrossCorrelation& c = a.cross_correlation[0];
  EXPECT_TRUE(c.correlated);
  EXPECT_TRUE(a.input_correlated);
  EXPECT_EQ(c.values.size(), 51u);
  int peak = 0;
  for (int k = -25; k <= 25; ++k) {
    if (std::abs(c.values[k + 25]) > std::abs(c.values[peak + 25])) peak = k;
  }
  EXPECT_EQ(peak, 3);  // e follows u by three samples: a past input
  EXPECT_NEAR(c.values[28], 0.3 / std::sqrt(1.09), 0.05);
  EXPECT_NEAR(c.band_99, a.band_99, 0.3 * a.band_99);  // e nearly white: the plain band
}

// A residual that leads the input (u follows e: feedback) is correlated at negative lags only
// and is not flagged.
TEST(ResidualAnalysis, FeedbackAtNegativeLagsIsNotFlagged) {
  Gaussian g(13);
  const int n = 4000;
  std::vector<double> u(n), e(n);
  for (double& v : e) v = g();
  for (int t = 0; t < n; ++t) u[t] = (t >= 4 ? 0.5 * e[t - 4] : 0.0) + g();
  const ResidualAnalysis a = AnalyseResiduals("run", "psi", {}, e, {"delta"}, {u});
  EXPECT_FALSE(a.input_correlated);
  EXPECT_GT(std::abs(a.cross_correlation[0].values[25 - 4]), 5 * a.band_99);
}

// Coloured residuals independent of a smooth input: the Bartlett band widens with the colour
// of both, so that they are rarely flagged (the plain band would flag most of them).
TEST(ResidualAnalysis, ColouredResidualsIndependentOfASmoothInputAreRarelyFlagged) {
  int flagged = 0, plain_flagged = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    const std::vector<double> e = Ar1(0.9, 3000, 100 + seed), u = Ar1(0.95, 3000, 500 + seed);
    const ResidualAnalysis a = AnalyseResiduals("run", "psi", {}, e, {"delta"}, {u});
    EXPECT_FALSE(a.white);
    EXPECT_GT(a.cross_correlation[0].band_99, 2.5 * a.band_99);
    flagged += a.input_correlated;
    for (int k = 0; k <= a.lags; ++k) {
      if (std::abs(a.cross_correlation[0].values[a.lags + k]) > a.band_99) {
        ++plain_flagged;
        break;
      }
    }
  }
  EXPECT_LE(flagged, 6);
  EXPECT_GE(plain_flagged, 15);
}

TEST(ResidualAnalysis, IrregularSamplingIsNoted) {
  Gaussian g(17);
  std::vector<double> t, e;
  for (int k = 0; k < 400; ++k) {
    t.push_back(0.1 * k + (k % 3 == 0 ? 0.04 : 0.0));  // intervals 0.14, 0.1, 0.06 s
    e.push_back(g());
  }
  const ResidualAnalysis jittered = AnalyseResiduals("run", "psi", t, e, {}, {});
  EXPECT_TRUE(jittered.irregular());
  EXPECT_NEAR(jittered.interval_spread, 0.4, 1e-9);
  for (int k = 0; k < 400; ++k) t[k] = 0.1 * k;
  EXPECT_FALSE(AnalyseResiduals("run", "psi", t, e, {}, {}).irregular());
}

TEST(ResidualAnalysis, ShortOrConstantResidualsAreNotTested) {
  const ResidualAnalysis short_record =
      AnalyseResiduals("run", "psi", {}, {0.1, -0.2, 0.3, 0.0, 0.1}, {}, {});
  EXPECT_FALSE(short_record.tested());
  EXPECT_TRUE(short_record.white);
  const ResidualAnalysis constant =
      AnalyseResiduals("run", "psi", {}, std::vector<double>(100, 0.5), {}, {});
  EXPECT_FALSE(constant.tested());
  EXPECT_TRUE(constant.autocorrelation.empty());
}

TEST(ResidualAnalysis, ConstantInputHasNoCorrelation) {
  Gaussian g(19);
  std::vector<double> e(500);
  for (double& v : e) v = g();
  const ResidualAnalysis a =
      AnalyseResiduals("run", "psi", {}, e, {"n"}, {std::vector<double>(500, 2.0)});
  ASSERT_EQ(a.cross_correlation.size(), 1u);
  EXPECT_TRUE(std::isnan(a.cross_correlation[0].values[25]));
  EXPECT_FALSE(a.input_correlated);
}

}  // namespace residual_analysis_test
}  // namespace vesselid
