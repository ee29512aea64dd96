// The memory a run may use (limits.memory_mb), against which the parts of a run that grow
// with the campaign are counted before they are allocated: the records' input caches and
// samples (run/work_size.h) and the covariance of the free variables (solve/covariance.h).
// A run over it is refused, or the part left out, with the number, what it is made of and
// the key to change, instead of meeting the kernel's out-of-memory killer hours in.
#pragma once

#include <cstdint>
#include <string>

namespace vesselid {

// Half the machine's physical memory (sysconf), at least 1 GiB.
std::uint64_t DefaultMemoryBudget();

// The budget in force: the innermost ScopedMemoryBudget's, else DefaultMemoryBudget().
std::uint64_t MemoryBudget();

// Sets the budget for the scope of a run (0: the default; at most 90 % of the machine's
// memory), restoring the previous one.
class ScopedMemoryBudget {
 public:
  explicit ScopedMemoryBudget(std::uint64_t bytes);
  ~ScopedMemoryBudget();
  ScopedMemoryBudget(const ScopedMemoryBudget&) = delete;
  ScopedMemoryBudget& operator=(const ScopedMemoryBudget&) = delete;

 private:
  std::uint64_t previous_;
  bool previous_held_;
};

// "812 MiB", "57.6 GiB" (the binary units of limits.memory_mb and file_mb, three digits).
std::string FormatBytes(double bytes);

// "<what> need <bytes>, more than the memory budget of <budget> (limits.memory_mb)".
std::string OverBudget(const std::string& what, double bytes);

}  // namespace vesselid
