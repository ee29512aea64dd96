#include "engine/base/memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>

namespace vesselid {
namespace {

std::atomic<std::uint64_t> budget_in_force{0};  // 0: the default
std::atomic<bool> budget_held{false};  // the configured budget was above the machine's

// The machine's physical memory (4 GiB where sysconf cannot tell).
std::uint64_t PhysicalMemory() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::uint64_t{4} << 30;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page);
}

}  // namespace

std::uint64_t DefaultMemoryBudget() {
  return std::max(std::uint64_t{1} << 30, PhysicalMemory() / 2);
}

std::uint64_t MemoryBudget() {
  const std::uint64_t bytes = budget_in_force.load();
  return bytes > 0 ? bytes : DefaultMemoryBudget();
}

// A configured budget above 90 % of the machine's memory is held there: what it admits would
// end in std::bad_alloc or the kernel's out-of-memory killer, not in a refusal.
ScopedMemoryBudget::ScopedMemoryBudget(std::uint64_t bytes)
    : previous_(budget_in_force.load()), previous_held_(budget_held.load()) {
  const std::uint64_t most = PhysicalMemory() / 10 * 9;
  budget_held.store(bytes > most);
  budget_in_force.store(std::min(bytes, most));
}

ScopedMemoryBudget::~ScopedMemoryBudget() {
  budget_in_force.store(previous_);
  budget_held.store(previous_held_);
}

std::string FormatBytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1023.5 && u < 6) {
    bytes /= 1024.0;
    ++u;
  }
  char text[48];
  std::snprintf(text, sizeof(text), u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return text;
}

std::string OverBudget(const std::string& what, double bytes) {
  return what + " need " + FormatBytes(bytes) + ", more than the memory budget of " +
         FormatBytes(static_cast<double>(MemoryBudget())) +
         (budget_held.load() ? " (limits.memory_mb, held to 90 % of this machine's memory)"
                             : " (limits.memory_mb)");
}

}  // namespace vesselid
