#pragma once
// The path of one of the shared example jobs, for the cli tests.
#include <string>

namespace mdhd::cli::test_support {

inline std::string example(const char* name) {
  return std::string(MDHD_SHARED_DIR) + "/examples/" + name;
}

}  // namespace mdhd::cli::test_support
