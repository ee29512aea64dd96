// The Eriksen-Breivik 2-DOF model beyond the model battery (model_battery_test.cc): the
// polynomial basis it is built on and the inadmissible inertia that fails a simulation.
#include <cmath>

#include "engine/model/polynomial_basis.h"
#include "gtest/gtest.h"
#include "problems/eriksen2dof/handles.h"
#include "tests/support/eriksen_data.h"

namespace vesselid {
namespace eriksen_model_test {

class EriksenModel : public ::testing::Test {
 protected:
  std::unique_ptr<ModelHandle> model_ = eriksen2dof::MakeHandle(eriksen2dof::Model());
  std::vector<double> truth_ = testing::ReferenceCraft(model_->info());
};

TEST(PolynomialBasis, OrderAndNames) {
  double phi[15];
  Monomials(4, 2.0, 3.0, phi);
  const std::vector<std::string> names = MonomialNames(4, "U", "r");
  const double expected[15] = {1, 2, 3, 4, 6, 9, 8, 12, 18, 27, 16, 24, 36, 54, 81};
  ASSERT_EQ(names.size(), 15u);
  for (int k = 0; k < 15; ++k) EXPECT_EQ(phi[k], expected[k]) << names[k];
  EXPECT_EQ(names[7], "U2r");
  EXPECT_EQ(names[12], "U2r2");
  EXPECT_EQ(MonomialPowerOfB(4, 12), 2);
  EXPECT_EQ(MonomialPowerOfB(4, 14), 4);
}

TEST_F(EriksenModel, InadmissibleInertiaFailsTheSimulation) {
  std::vector<double> p = truth_;
  p[model_->info().ParameterIndex("m_U.1")] = -0.5;
  const double x[5] = {0, 0, 0, 3.0, 0.1}, u[2] = {0.3, 0.2};
  double xdot[5];
  EXPECT_FALSE(model_->Derivative(x, u, p.data(), xdot));
  EXPECT_TRUE(model_->Derivative(x, u, truth_.data(), xdot));
}

}  // namespace eriksen_model_test
}  // namespace vesselid
