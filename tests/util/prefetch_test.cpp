// Prefetch hints: the cache lines a range covers, whatever its alignment.
#include "engine/util/prefetch.h"

#include <doctest/doctest.h>

#include <cstdint>

using namespace prep;

TEST_CASE("prefetch: a range covers every cache line it touches, and no other") {
  alignas(64) static unsigned char block[4 * 64];
  const auto line_of = [&](int byte) { return reinterpret_cast<std::uintptr_t>(block + byte) & ~std::uintptr_t{63}; };
  struct Case {
    int offset, bytes;
    std::size_t lines;
  };
  for (const Case c : {Case{0, 0, 0}, Case{0, 1, 1}, Case{0, 64, 1}, Case{0, 65, 2}, Case{63, 1, 1}, Case{63, 2, 2},
                       Case{1, 128, 3}, Case{32, 192, 4}, Case{17, 100, 2}}) {
    CAPTURE(c.offset);
    CAPTURE(c.bytes);
    const CacheLines l = cache_lines(block + c.offset, static_cast<std::size_t>(c.bytes));
    CHECK(l.count == c.lines);
    if (c.bytes > 0) {
      CHECK(l.first == line_of(c.offset));  // the first byte's line ...
      CHECK(l.first + (l.count - 1) * kCacheLine == line_of(c.offset + c.bytes - 1));  // ... to the last byte's
    }
  }
}
