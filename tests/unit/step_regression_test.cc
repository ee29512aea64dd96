// Seed 004's regression pipeline (step_samples.h, step_regression.h) on a step campaign of the
// 2-DOF model itself, where the damping and inertia terms are known exactly: the damping
// surface is recovered, the inertia roughly (first-order fits of a nonlinear response), the
// mirrored samples make the symmetry-breaking coefficients vanish, and the normalised
// polynomial is expanded into the model's basis exactly.
#include <cmath>
#include <random>

#include "engine/config/config.h"
#include "engine/run/pipeline.h"
#include "engine/run/records.h"
#include "engine/step_regression/step_regression.h"
#include "gtest/gtest.h"
#include "problems/eriksen2dof/handles.h"
#include "tests/support/eriksen_data.h"

namespace vesselid {
namespace step_regression_test {

TEST(ExpandToModelBasis, IsExact) {
  std::mt19937 random(2);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd b(15);
  for (int k = 0; k < 15; ++k) b[k] = uniform(random);
  const double scale[2] = {10.0, 0.5}, mean[2] = {7.0, 0.05}, sd[2] = {4.0, 0.2};
  const double mean_y = 0.3, sd_y = 0.2;
  const std::vector<double> c = ExpandToModelBasis(4, scale, mean, sd, mean_y, sd_y, b);
  for (int trial = 0; trial < 20; ++trial) {
    const double x0 = 7.0 + 8.0 * uniform(random), x1 = 0.4 * uniform(random);
    double phi[15], normalised = mean_y, model = 0.0;
    Monomials(4, (x0 - mean[0]) / sd[0], (x1 - mean[1]) / sd[1], phi);
    for (int k = 0; k < 15; ++k) normalised += sd_y * b[k] * phi[k];
    Monomials(4, x0 / scale[0], x1 / scale[1], phi);
    for (int k = 0; k < 15; ++k) model += c[k] * phi[k];
    EXPECT_NEAR(model, normalised, 1e-9 * (1.0 + std::abs(normalised)));
  }
}

class StepRegression : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::vector<double> truth = testing::ReferenceCraft(model_->info());
    truth_ = truth;
    // Throttle 0 -> 0.6 -> 0 at four rudder settings, rudder 0 -> 1 -> 0 at two throttles.
    const auto runs = testing::StepCampaign({0.0, 0.3, 0.6, 1.0}, {0.2, 0.45}, 0.6, 0.1, 60.0);
    const Trajectory data = testing::SimulateRuns(*model_, truth, runs, 0.2, 0.01,
                                                  0.05 * M_PI / 180.0, 11);
    ExperimentSpec spec;
    spec.name = "steps";
    spec.inputs = {{"tau_m", "throttle"}, {"tau_delta", "rudder"}};
    spec.outputs = {{"U", "sog"}, {"r", "rot"}};
    spec.segments.column = "run";
    std::vector<ExperimentSpec> specs;
    std::string error;
    ASSERT_TRUE(RecordSpecs(spec, data, 0.0, &specs, &error)) << error;
    ASSERT_EQ(specs.size(), runs.size());
    RegressionDataOptions options;
    options.grid_output = "U";
    options.smoothing = {2, 2, 0};
    for (const ExperimentSpec& s : specs) {
      RegressionRecord record;
      ASSERT_TRUE(BuildRegressionRecord(s, data, *model_, options, &record, &error)) << error;
      records_.push_back(std::move(record));
    }
    options_.samples.steady.tolerance = {0.02, 0.002};
    options_.samples.input_lower = {0.0, -1.0};
    options_.samples.input_upper = {0.6, 1.0};
    options_.samples.min_change = {0.1, 0.005};
    options_.asymptote_a = {0.5, 1.0, 2.0};
    options_.asymptote_b_points = 9;
    options_.lasso.path_points = 30;
  }

  std::unique_ptr<ModelHandle> model_ = eriksen2dof::MakeHandle(eriksen2dof::Model());
  std::vector<double> truth_;
  std::vector<RegressionRecord> records_;
  StepRegressionOptions options_;
};

TEST_F(StepRegression, RecoversTheDampingSurfaceAndTheInertiaScale) {
  const DampingInertiaForm& form = *model_->damping_inertia_form();
  StepRegressionReport report;
  std::string error;
  ASSERT_TRUE(RunStepRegression(form, records_, options_, &report, &error)) << error;
  const StepSamples& s = report.samples;
  // 4 runs of 13 levels and 2 of 21, every level steady; mirrored copies of all but the
  // straight ones (r = 0 and tau_delta = 0).
  EXPECT_EQ(s.intervals, 4 * 13 + 2 * 21);
  EXPECT_EQ(s.steady, s.intervals);
  const int straight = 13 + 2 * 2;
  EXPECT_EQ(static_cast<int>(s.damping.size()), 2 * s.intervals - straight);
  EXPECT_GT(s.inertia[0].size(), 60u);
  EXPECT_GT(s.inertia[1].size(), 50u);

  std::vector<double> p = truth_;
  StoreStepRegression(form, report, &p);
  const ModelInfo& info = model_->info();
  // Symmetry: sigma_U, m_U, m_r even in r, sigma_r odd, from the mirrored samples alone.
  for (int k = 0; k < form.num_basis(); ++k) {
    const bool odd = MonomialPowerOfB(form.degree, k) % 2 == 1;
    for (int i = 0; i < 2; ++i) {
      const double damping = p[form.damping[i][k]];
      if (odd == (i == 0)) {
        EXPECT_NEAR(damping, 0.0, 1e-9) << info.parameters[form.damping[i][k]];
      }
      if (odd) {
        EXPECT_NEAR(p[form.inertia[i][k]], 0.0, 1e-9) << info.parameters[form.inertia[i][k]];
      }
    }
  }
  // Damping: sigma(x) = tau at every steady state, and the true surface inside the samples.
  double worst = 0.0;
  for (const DampingSample& d : s.damping) {
    double sigma[2], m[2], sigma_true[2], m_true[2];
    EvaluateDampingInertia(form, p.data(), d.x, sigma, m);
    EvaluateDampingInertia(form, truth_.data(), d.x, sigma_true, m_true);
    for (int i = 0; i < 2; ++i) worst = std::max(worst, std::abs(sigma[i] - sigma_true[i]));
  }
  EXPECT_LT(worst, 0.01);
  // Inertia: first-order fits of a nonlinear response, within 25 % at the median.
  for (int i = 0; i < 2; ++i) {
    std::vector<double> relative;
    for (const InertiaSample& m : s.inertia[i]) {
      double sigma[2], mass[2];
      EvaluateDampingInertia(form, truth_.data(), m.x, sigma, mass);
      relative.push_back(std::abs(m.inertia / mass[i] - 1.0));
    }
    std::nth_element(relative.begin(), relative.begin() + relative.size() / 2, relative.end());
    EXPECT_LT(relative[relative.size() / 2], 0.25) << form.term_names[2 + i];
  }
  // Every term: a cross-validated lambda inside its path and a fit that explains the samples.
  for (const TermRegression& t : report.terms) {
    EXPECT_GE(t.path.best, 0) << t.name;
    EXPECT_EQ(t.lambda, t.path.lambda[t.path.best]) << t.name;
    EXPECT_GT(t.r2, t.name[0] == 's' ? 0.999 : 0.5) << t.name;
  }
  EXPECT_EQ(report.terms[2].asymptote_grid.size(), 3u * 9u);
}

TEST_F(StepRegression, TooFewStepsIsAClearError) {
  options_.samples.min_change = {100.0, 100.0};  // no step qualifies
  StepRegressionReport report;
  std::string error;
  EXPECT_FALSE(RunStepRegression(*model_->damping_inertia_form(), records_, options_, &report,
                                 &error));
  EXPECT_NE(error.find("m_U: 0 samples"), std::string::npos) << error;
}

TEST_F(StepRegression, InvalidOptionsAreRejected) {
  options_.asymptote_a = {-1.0};
  StepRegressionReport report;
  std::string error;
  EXPECT_FALSE(RunStepRegression(*model_->damping_inertia_form(), records_, options_, &report,
                                 &error));
  EXPECT_NE(error.find("asymptote"), std::string::npos) << error;
}

}  // namespace step_regression_test
}  // namespace vesselid
