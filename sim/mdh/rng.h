#pragma once
// The Random-Selection rule's generator: a pure function of (seed, cell, step,
// depth), so results never depend on which thread cut which cell first.
#include <cstdint>

namespace mdhd::mdh {

inline std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

inline std::uint64_t mixHash(std::uint64_t a, std::uint64_t b) {
  return splitMix64(a ^ (splitMix64(b) + 0x632be59bd9b4e019ULL));
}

}  // namespace mdhd::mdh
