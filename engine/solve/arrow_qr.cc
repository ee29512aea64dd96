#include "engine/solve/arrow_qr.h"

#include <algorithm>
#include <numeric>

namespace vesselid {
namespace {

// R of the rows added so far: [R; chunk] is reduced by Householder QR whenever the chunk
// fills (tall-skinny QR), so that at most one chunk is held.
class RowReducer {
 public:
  explicit RowReducer(int width)
      : width_(width), chunk_(std::max(512, 8 * width)), buffer_(chunk_ + width, width) {
    buffer_.setZero();
  }

  // A zeroed row to fill.
  Eigen::Block<Eigen::MatrixXd, 1, Eigen::Dynamic> NextRow() {
    if (filled_ == chunk_ + width_) Reduce();
    buffer_.row(filled_).setZero();
    return buffer_.row(filled_++);
  }

  // Upper triangular width x width (zero rows where fewer rows than columns were added).
  Eigen::MatrixXd R() {
    Reduce();
    return buffer_.topRows(width_);
  }

 private:
  void Reduce() {
    if (filled_ <= width_ && reduced_) return;
    const int rows = filled_;
    if (rows == 0) {
      buffer_.topRows(width_).setZero();
      filled_ = width_;
      reduced_ = true;
      return;
    }
    Eigen::Ref<Eigen::MatrixXd> top = buffer_.topRows(rows);
    Eigen::HouseholderQR<Eigen::Ref<Eigen::MatrixXd>> qr(top);  // in place: R above the diagonal
    const int kept = std::min(rows, width_);
    Eigen::MatrixXd r = Eigen::MatrixXd::Zero(width_, width_);
    r.topRows(kept) = buffer_.topRows(kept).triangularView<Eigen::Upper>();
    buffer_.topRows(width_) = r;
    filled_ = width_;
    reduced_ = true;
  }

  int width_, chunk_;
  Eigen::MatrixXd buffer_;
  int filled_ = 0;
  bool reduced_ = false;
};

int Root(std::vector<int>* parent, int g) {
  while ((*parent)[g] != g) g = (*parent)[g] = (*parent)[(*parent)[g]];
  return g;
}

}  // namespace

ArrowBlocks ArrowQrBlocks(const ceres::CRSMatrix& jacobian, const std::vector<int>& group,
                          int rows) {
  const int n = jacobian.num_cols;
  if (rows < 0) rows = jacobian.num_rows;
  // Dense group ids, merged where a row joins two.
  std::vector<int> ids;
  for (int g : group) {
    if (g >= 0) ids.push_back(g);
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::vector<int> dense(n, -1);
  for (int c = 0; c < n; ++c) {
    if (group[c] >= 0) dense[c] = int(std::lower_bound(ids.begin(), ids.end(), group[c]) - ids.begin());
  }
  std::vector<int> parent(ids.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<int> row_group(rows, -1);
  for (int r = 0; r < rows; ++r) {
    for (int k = jacobian.rows[r]; k < jacobian.rows[r + 1]; ++k) {
      const int g = dense[jacobian.cols[k]];
      if (g < 0) continue;
      if (row_group[r] < 0) {
        row_group[r] = g;
      } else {
        parent[Root(&parent, g)] = Root(&parent, row_group[r]);
      }
    }
  }
  // Columns in R's order: each block's (by smallest group id) own columns, then the shared.
  const int num_blocks_max = static_cast<int>(ids.size());
  std::vector<std::vector<int>> block_columns(num_blocks_max), block_rows(num_blocks_max);
  std::vector<int> shared_columns;
  for (int c = 0; c < n; ++c) {
    if (dense[c] < 0) {
      shared_columns.push_back(c);
    } else {
      block_columns[Root(&parent, dense[c])].push_back(c);
    }
  }
  std::vector<int> shared_rows;
  for (int r = 0; r < rows; ++r) {
    if (row_group[r] < 0) {
      shared_rows.push_back(r);
    } else {
      block_rows[Root(&parent, row_group[r])].push_back(r);
    }
  }
  const int ns = static_cast<int>(shared_columns.size());
  // position[c]: column c's place in its block's [own, shared] row, or in the shared row.
  std::vector<int> position(n, -1);
  for (int i = 0; i < ns; ++i) position[shared_columns[i]] = i;

  ArrowBlocks out;
  RowReducer shared(ns);
  for (int b = 0; b < num_blocks_max; ++b) {
    const std::vector<int>& own = block_columns[b];
    if (own.empty()) continue;
    const int nl = static_cast<int>(own.size()), width = nl + ns;
    for (int i = 0; i < nl; ++i) position[own[i]] = i;
    RowReducer reducer(width);
    for (int r : block_rows[b]) {
      auto row = reducer.NextRow();
      for (int k = jacobian.rows[r]; k < jacobian.rows[r + 1]; ++k) {
        const int c = jacobian.cols[k];
        row(dense[c] < 0 ? nl + position[c] : position[c]) = jacobian.values[k];
      }
    }
    const Eigen::MatrixXd rb = reducer.R();
    out.blocks.push_back({own, rb.topLeftCorner(nl, nl), rb.topRightCorner(nl, ns)});
    for (int i = 0; i < ns; ++i) shared.NextRow() = rb.row(nl + i).tail(ns);
    for (int i = 0; i < nl; ++i) position[own[i]] = -1;
  }
  for (int r : shared_rows) {
    auto row = shared.NextRow();
    for (int k = jacobian.rows[r]; k < jacobian.rows[r + 1]; ++k) {
      row(position[jacobian.cols[k]]) = jacobian.values[k];
    }
  }
  out.shared_columns = shared_columns;
  out.shared = ns > 0 ? shared.R() : Eigen::MatrixXd(0, 0);
  return out;
}

ArrowR ArrowQr(const ceres::CRSMatrix& jacobian, const std::vector<int>& group, int rows) {
  const ArrowBlocks blocks = ArrowQrBlocks(jacobian, group, rows);
  const int n = jacobian.num_cols, ns = static_cast<int>(blocks.shared_columns.size());
  ArrowR out;
  out.r = Eigen::MatrixXd::Zero(n, n);
  int at = 0;  // R's next row/column
  for (const ArrowBlocks::Block& b : blocks.blocks) {
    const int nl = static_cast<int>(b.columns.size());
    out.r.block(at, at, nl, nl) = b.own;
    out.r.block(at, n - ns, nl, ns) = b.shared;
    for (int c : b.columns) out.order.push_back(c);
    at += nl;
  }
  if (ns > 0) out.r.bottomRightCorner(ns, ns) = blocks.shared;
  for (int c : blocks.shared_columns) out.order.push_back(c);
  return out;
}

}  // namespace vesselid
