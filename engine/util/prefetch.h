// Hints to the processor that memory is about to be read: each cache line of a range is requested ahead,
// so that a later pass over it finds it in cache. Pure hints: no value changes, and an address is never
// dereferenced by the hint itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace prep {

constexpr std::size_t kCacheLine = 64;

// The cache lines a range of `bytes` bytes from `data` touches: `count` lines from the one holding its
// first byte.
struct CacheLines {
  std::uintptr_t first = 0;
  std::size_t count = 0;
};
inline CacheLines cache_lines(const void* data, std::size_t bytes) {
  if (bytes == 0) return {};
  const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = begin & ~static_cast<std::uintptr_t>(kCacheLine - 1);
  const std::uintptr_t last = (begin + bytes - 1) & ~static_cast<std::uintptr_t>(kCacheLine - 1);
  return {first, (last - first) / kCacheLine + 1};
}

// How close to the core a prefetched line is brought: into the second-level cache (prefetcht1 on x86),
// not the first. A crowd asks for about 110 lines a world, up to six worlds ahead, while the world in
// between steps; brought into the first-level cache (32-48 KB) they pushed out that world's own working
// set and held the cache's few outstanding-miss slots its loads were waiting for. A line in the second
// level is a dozen cycles away, which out-of-order execution covers. Measured on this 2-core machine, a
// crowd of 20,000 in three alternating pairs: 23.6-24.2 ms a frame against 30.2-31.6 ms into the first
// level (33-34 ms with no prefetch at all).
constexpr int kPrefetchLocality = 2;

// GCC counts __builtin_prefetch as free of side effects: a function made only of them is found to be
// `const`, and calls to it, returning nothing, are dropped as dead. The empty volatile asm is a side
// effect the optimizer must keep, and with it the prefetches.
inline void prefetch_range(const void* data, std::size_t bytes) {
  const CacheLines lines = cache_lines(data, bytes);
  for (std::size_t k = 0; k < lines.count; ++k)
    __builtin_prefetch(reinterpret_cast<const void*>(lines.first + k * kCacheLine), 0, kPrefetchLocality);
  asm volatile("");
}

template <class T>
inline void prefetch_object(const T& object) { prefetch_range(&object, sizeof(T)); }

template <class T>
inline void prefetch_vector(const std::vector<T>& v) { prefetch_range(v.data(), v.size() * sizeof(T)); }

}  // namespace prep
