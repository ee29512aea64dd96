// The triangular factor of a block-arrow Jacobian: R^T R equals J^T J (columns permuted
// group by group, shared last) for groups of different sizes, rows touching only shared
// columns, a row that joins two groups (merged into one block), a group with fewer rows than
// columns, and a chunked reduction (more rows than one chunk).
#include "engine/solve/arrow_qr.h"

#include <random>

#include "gtest/gtest.h"

namespace vesselid {
namespace arrow_qr_test {

ceres::CRSMatrix ToCrs(const Eigen::MatrixXd& dense) {
  ceres::CRSMatrix crs;
  crs.num_rows = static_cast<int>(dense.rows());
  crs.num_cols = static_cast<int>(dense.cols());
  crs.rows.push_back(0);
  for (int r = 0; r < crs.num_rows; ++r) {
    for (int c = 0; c < crs.num_cols; ++c) {
      if (dense(r, c) == 0.0) continue;
      crs.cols.push_back(c);
      crs.values.push_back(dense(r, c));
    }
    crs.rows.push_back(static_cast<int>(crs.cols.size()));
  }
  return crs;
}

TEST(ArrowQrTest, FactorReproducesTheNormalMatrix) {
  // Columns: shared 0, 3, 6, 7; group 5: {1, 2}; group 2: {4}; group 9: {5, 8, 9}; group 4: {10}.
  const std::vector<int> group = {-1, 5, 5, -1, 2, 9, -1, -1, 9, 9, 4};
  const int n = static_cast<int>(group.size());
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::vector<Eigen::RowVectorXd> rows;
  auto add = [&](const std::vector<int>& columns, double scale) {
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(n);
    for (int c : columns) row[c] = scale * normal(rng);
    rows.push_back(row);
  };
  for (int i = 0; i < 1500; ++i) add({0, 3, 6, 7, 1, 2}, 1.0);      // more than one chunk
  for (int i = 0; i < 40; ++i) add({0, 3, 6, 7, 4}, 1e3);           // large column scale
  for (int i = 0; i < 30; ++i) add({0, 3, 6, 7, 5, 8, 9}, 1e-2);
  add({10, 0}, 1.0);                                                // fewer rows than columns
  add({4, 10}, 1.0);                                                // joins groups 2 and 4
  for (int i = 0; i < 5; ++i) add({0, 6}, 1.0);                     // shared only
  Eigen::MatrixXd j(rows.size(), n);
  for (size_t r = 0; r < rows.size(); ++r) j.row(r) = rows[r];

  const ArrowR arrow = ArrowQr(ToCrs(j), group);
  ASSERT_EQ(arrow.r.rows(), n);
  ASSERT_EQ(static_cast<int>(arrow.order.size()), n);
  // Shared columns last, in order; each group's columns together.
  EXPECT_EQ(std::vector<int>(arrow.order.end() - 4, arrow.order.end()),
            (std::vector<int>{0, 3, 6, 7}));
  std::vector<bool> seen(n, false);
  for (int c : arrow.order) seen[c] = true;
  for (int c = 0; c < n; ++c) EXPECT_TRUE(seen[c]) << c;
  EXPECT_EQ(arrow.r.triangularView<Eigen::StrictlyLower>().toDenseMatrix().norm(), 0.0);

  Eigen::MatrixXd permuted(j.rows(), n);
  for (int k = 0; k < n; ++k) permuted.col(k) = j.col(arrow.order[k]);
  const Eigen::MatrixXd expected = permuted.transpose() * permuted;
  const Eigen::MatrixXd actual = arrow.r.transpose() * arrow.r;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      const double size = std::sqrt(expected(a, a) * expected(b, b));
      EXPECT_NEAR(actual(a, b), expected(a, b), 1e-12 * size) << a << "," << b;
    }
  }
  // The merged groups 2 and 4 share a block: no structural zero between them in R.
  int at4 = -1, at10 = -1;
  for (int k = 0; k < n; ++k) {
    if (arrow.order[k] == 4) at4 = k;
    if (arrow.order[k] == 10) at10 = k;
  }
  EXPECT_EQ(std::abs(at4 - at10), 1);
}

TEST(ArrowQrTest, RowsOnlyPrefixAndNoSharedColumns) {
  const std::vector<int> group = {0, 0, 1};
  Eigen::MatrixXd j(4, 3);
  j << 1, 2, 0,  //
      3, 4, 0,   //
      0, 0, 5,   //
      9, 9, 9;   // beyond `rows`: ignored
  const ArrowR arrow = ArrowQr(ToCrs(j), group, 3);
  const Eigen::MatrixXd top = j.topRows(3);
  Eigen::MatrixXd permuted(3, 3);
  for (int k = 0; k < 3; ++k) permuted.col(k) = top.col(arrow.order[k]);
  EXPECT_LT((arrow.r.transpose() * arrow.r - permuted.transpose() * permuted).norm(), 1e-12);
}

}  // namespace arrow_qr_test
}  // namespace vesselid
