#include "engine/base/memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>

namespace vesselid {
namespace {

std::atomic<std::uint64_t> budget_in_force{0};  // 0: the default

}  // namespace

std::uint64_t DefaultMemoryBudget() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page = sysconf(_SC_PAGE_SIZE);
  const std::uint64_t gib = std::uint64_t{1} << 30;
  if (pages <= 0 || page <= 0) return 4 * gib;
  return std::max(gib, static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) / 2);
}

std::uint64_t MemoryBudget() {
  const std::uint64_t bytes = budget_in_force.load();
  return bytes > 0 ? bytes : DefaultMemoryBudget();
}

ScopedMemoryBudget::ScopedMemoryBudget(std::uint64_t bytes)
    : previous_(budget_in_force.exchange(bytes)) {}

ScopedMemoryBudget::~ScopedMemoryBudget() { budget_in_force.store(previous_); }

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
         FormatBytes(static_cast<double>(MemoryBudget())) + " (limits.memory_mb)";
}

}  // namespace vesselid
