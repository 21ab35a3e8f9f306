#include "daemon/number_text.h"

#include <stdexcept>

namespace mdhd::service {

std::optional<long long> integerInRange(const std::string& text, long long lo, long long hi) {
  std::size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != text.size() || v < lo || v > hi) return std::nullopt;
  return v;
}

std::optional<double> numberInRange(const std::string& text, double lo, double hi) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != text.size() || !(v >= lo) || !(v <= hi)) return std::nullopt;
  return v;
}

}  // namespace mdhd::service
