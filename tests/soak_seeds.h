#pragma once
// Seeds of the randomised suites. CI runs 1..count; MDHD_SOAK_SEEDS=N runs 1..N
// instead, a soak for rare cases outside CI, e.g.
//   MDHD_SOAK_SEEDS=500 build/bin/mdh_tests --gtest_filter='Seeds/*'
// A value that is not a positive number is an error, not a silent default.
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace mdhd::soak {

inline std::vector<std::uint32_t> seeds(std::uint32_t count) {
  if (const char* env = std::getenv("MDHD_SOAK_SEEDS")) {
    char* end = nullptr;
    const unsigned long n = std::strtoul(env, &end, 10);
    if (end == env || *end != '\0' || n == 0 || n > 1000000)
      throw std::invalid_argument("MDHD_SOAK_SEEDS must be a number of seeds, got '" +
                                  std::string(env) + "'");
    count = static_cast<std::uint32_t>(n);
  }
  std::vector<std::uint32_t> out;
  for (std::uint32_t s = 1; s <= count; ++s) out.push_back(s);
  return out;
}

}  // namespace mdhd::soak
