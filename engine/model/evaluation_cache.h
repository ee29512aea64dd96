// The last evaluation of one residual block, so that Ceres asking again at bit-identical
// parameter values copies the result instead of simulating the experiment again.
//
// Ceres 2.1's bounded trust region evaluates each candidate three times: the projected line
// search asks for the gradient there (cubic interpolation: residuals and Jacobian, a Jet
// simulation), the candidate's cost is evaluated again (residuals only), and an accepted step
// asks for residuals and Jacobian at the same point once more. The cache holds the last
// residual-only evaluation (on doubles) and the last two with a Jacobian (on Jets). A Jacobian
// request is answered only from an evaluation on Jets with the same constant blocks; a
// residual-only request from the last evaluation of either kind at those values, the Jet one first.
// So an accepted candidate costs one Jet simulation, not a Jet and a double one. Residuals on Jets
// may differ from those on doubles in the last bits (a Jet divides as a * (1 / b)), so a solve with
// the cache ends within rounding of one without it, not bit for bit; with the cache, every solve is
// reproducible bit for bit. The Jet slot answers first because only a solve's own Jacobian requests
// fill it, while the double slot may hold an evaluation made for another purpose (a multistart
// screens points on whichever of its problems a thread borrows), whose answer is bit-identical to a
// new double simulation: what a solve is answered then never depends on threads or timing.
//
// An entry is keyed by the values of every parameter block (bit patterns) and a revision of
// the data the residuals depend on (Experiment::weights_revision). Lookups and stores lock a
// mutex (never held during a simulation), so that a cost function evaluated from several
// threads at once stays correct; as each block has its own cache, results do not depend on
// the order of those threads.
#pragma once

#include <atomic>
#include <cstring>
#include <mutex>
#include <utility>
#include <vector>

namespace vesselid {

// Counts of one problem's residual-block evaluations (shared by its experiments' costs).
struct EvaluationCounts {
  std::atomic<long> simulations{0};      // residuals only, on doubles
  std::atomic<long> jet_simulations{0};  // residuals and Jacobian, on Jets
  std::atomic<long> hits{0};             // answered from the cache
};

class EvaluationCache {
 public:
  // A block of `num_residuals` residuals over `num_blocks` parameter blocks of size 1.
  EvaluationCache(int num_residuals, int num_blocks)
      : num_residuals_(num_residuals), num_blocks_(num_blocks) {}

  int num_residuals() const { return num_residuals_; }
  int num_blocks() const { return num_blocks_; }

  // Copies a stored evaluation matching the request into `residuals` (and `jacobians`, whose
  // non-null entries say which columns are asked for); false if there is none. Residuals
  // alone come from the Jet slot or, failing that, from the residual-only one.
  bool Lookup(double const* const* parameters, long revision, double* residuals,
              double** jacobians) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const Slot* match = nullptr;
    for (int k : {1, 2, 0}) {  // the Jet slots, newest first, then (residuals only) doubles
      if (match != nullptr || (k == 0 && jacobians != nullptr)) continue;
      if (Matches(slots_[k], parameters, revision, jacobians)) match = &slots_[k];
    }
    if (match == nullptr) return false;
    const Slot& slot = *match;
    std::memcpy(residuals, slot.residuals.data(), sizeof(double) * num_residuals_);
    if (jacobians == nullptr) return true;
    const double* column = slot.jacobian.data();
    for (int b = 0; b < num_blocks_; ++b) {
      if (jacobians[b] == nullptr) continue;
      std::memcpy(jacobians[b], column, sizeof(double) * num_residuals_);
      column += num_residuals_;
    }
    return true;
  }

  // Keeps a successful evaluation (the arguments as Lookup's): a residual-only one replaces
  // the previous residual-only one, a Jet one the older of the two Jet ones (whose memory it
  // reuses).
  void Store(double const* const* parameters, long revision, const double* residuals,
             double** jacobians) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (jacobians != nullptr) std::swap(slots_[1], slots_[2]);
    Slot& slot = slots_[jacobians != nullptr];
    slot.valid = true;
    slot.revision = revision;
    slot.key.resize(num_blocks_);
    slot.asked.assign(num_blocks_, false);
    for (int b = 0; b < num_blocks_; ++b) slot.key[b] = parameters[b][0];
    slot.residuals.assign(residuals, residuals + num_residuals_);
    slot.jacobian.clear();
    if (jacobians == nullptr) return;
    for (int b = 0; b < num_blocks_; ++b) {
      if (jacobians[b] == nullptr) continue;
      slot.asked[b] = true;
      slot.jacobian.insert(slot.jacobian.end(), jacobians[b], jacobians[b] + num_residuals_);
    }
  }

  // Frees every slot (their memory too).
  void Clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    for (Slot& slot : slots_) slot = Slot();
  }

 private:
  struct Slot {
    bool valid = false;
    long revision = 0;
    std::vector<double> key;  // parameter block values
    std::vector<bool> asked;  // blocks whose Jacobian column was computed
    std::vector<double> residuals;
    std::vector<double> jacobian;  // the asked columns, in block order
  };

  bool Matches(const Slot& slot, double const* const* parameters, long revision,
               double** jacobians) const {
    if (!slot.valid || slot.revision != revision) return false;
    for (int b = 0; b < num_blocks_; ++b) {
      // Bit patterns: -0.0 and 0.0 are different keys, as a simulation may tell them apart.
      if (std::memcmp(&slot.key[b], parameters[b], sizeof(double)) != 0) return false;
      if (jacobians != nullptr && slot.asked[b] != (jacobians[b] != nullptr)) return false;
    }
    return true;
  }

  const int num_residuals_, num_blocks_;
  mutable std::mutex mutex_;
  // [0]: residuals only; [1], [2]: with Jacobian, the newest first. The second Jet slot was
  // added for the stage's uncertainty analysis, asked after a solve that stopped on a rejected
  // candidate; the miss there turned out to be Variable::set_value rewriting the blocks (fixed
  // since), and whether the second slot still saves simulations is not measured: a candidate
  // for removal (it holds one more Jacobian per experiment).
  Slot slots_[3];
};

}  // namespace vesselid
