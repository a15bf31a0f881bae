#include "engine/util/huge_pages.h"

#include <cstdio>
#include <cstring>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace prep {
namespace {

constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;

#if defined(__linux__) && !defined(MADV_COLLAPSE)
constexpr int MADV_COLLAPSE = 25;  // Linux 6.1's value, for older headers; older kernels answer EINVAL
#endif

}  // namespace

HugePageReport back_heap_with_huge_pages() {
  HugePageReport report;
#if defined(__linux__)
  std::FILE* maps = std::fopen("/proc/self/maps", "r");
  if (!maps) return report;
  // The heap may be listed in pieces (advice given earlier splits it from what the break added since):
  // from the first piece's start to the last one's end.
  char line[512];
  unsigned long low = 0, high = 0, piece_low = 0, piece_high = 0;
  bool found = false;
  while (std::fgets(line, sizeof line, maps)) {
    if (!std::strstr(line, "[heap]") || std::sscanf(line, "%lx-%lx", &piece_low, &piece_high) != 2) continue;
    if (!found) low = piece_low;
    high = piece_high;
    found = true;
  }
  std::fclose(maps);
  if (!found) return report;
  // Whole huge pages inside the heap only: advice on a partial one would split the mapping for nothing.
  report.begin = (static_cast<std::uintptr_t>(low) + kHugePage - 1) & ~(kHugePage - 1);
  report.end = static_cast<std::uintptr_t>(high) & ~(kHugePage - 1);
  if (report.end <= report.begin) {
    report.begin = report.end = 0;
    return report;
  }
  void* start = reinterpret_cast<void*>(report.begin);
  const size_t length = report.end - report.begin;
  report.advised = madvise(start, length, MADV_HUGEPAGE) == 0;
  report.collapsed = report.advised && madvise(start, length, MADV_COLLAPSE) == 0;
#endif
  return report;
}

long huge_page_kb() {
#if defined(__linux__)
  std::FILE* rollup = std::fopen("/proc/self/smaps_rollup", "r");
  if (!rollup) return 0;
  char line[256];
  long kb = 0;
  while (std::fgets(line, sizeof line, rollup)) {
    if (std::sscanf(line, "AnonHugePages: %ld kB", &kb) == 1) break;
  }
  std::fclose(rollup);
  return kb;
#else
  return 0;
#endif
}

}  // namespace prep
