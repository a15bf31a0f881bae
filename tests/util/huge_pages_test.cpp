// Huge pages for the heap: the range asked for is whole 2 MB pages of the heap, it covers what the heap
// holds, and what it holds is unchanged.
#include "engine/util/huge_pages.h"

#include <doctest/doctest.h>

#include <cstdint>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

using namespace prep;

namespace {

// AddressSanitizer's allocator keeps blocks in its own mappings. GCC says it is on by a macro, clang by
// __has_feature.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitizerHeap = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitizerHeap = true;
#else
constexpr bool kSanitizerHeap = false;
#endif
#else
constexpr bool kSanitizerHeap = false;
#endif

// Transparent huge pages off for the whole machine ("[never]"): the kernel may take no advice.
bool huge_pages_never() {
  std::ifstream setting("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string text;
  std::getline(setting, text);
  return !setting || text.find("[never]") != std::string::npos;
}

}  // namespace

TEST_CASE("huge pages: the heap's whole 2 MB pages are asked for, covering its blocks, whose contents stay") {
  // 12 MB of small blocks (below malloc's mmap threshold: they come from the heap), each with its own pattern.
  constexpr size_t kBlocks = 3000, kBytes = 4000;
  std::vector<std::unique_ptr<unsigned char[]>> blocks;
  for (size_t b = 0; b < kBlocks; ++b) {
    blocks.emplace_back(new unsigned char[kBytes]);
    for (size_t i = 0; i < kBytes; ++i) blocks.back()[i] = static_cast<unsigned char>(b * 7 + i);
  }
  const HugePageReport report = back_heap_with_huge_pages();
  const std::uintptr_t huge = std::uintptr_t{2} << 20;
  CHECK(report.begin % huge == 0);
  CHECK(report.end % huge == 0);
  CHECK(report.begin <= report.end);
  if (!kSanitizerHeap) {
    // All but the blocks in the heap's partial first and last huge pages lie in the range.
    size_t inside = 0;
    for (const auto& block : blocks) {
      const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(block.get());
      inside += at >= report.begin && at + kBytes <= report.end;
    }
    CHECK(inside * kBytes >= kBlocks * kBytes - 2 * huge);
    if (!huge_pages_never()) {
      CHECK(report.advised);
      if (report.collapsed) CHECK(huge_page_kb() >= 2048);
    }
  }
  bool same = true;
  for (size_t b = 0; b < kBlocks; ++b)
    for (size_t i = 0; i < kBytes; ++i) same = same && blocks[b][i] == static_cast<unsigned char>(b * 7 + i);
  CHECK(same);
}
