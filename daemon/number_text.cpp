#include "daemon/number_text.h"

#include <stdexcept>

namespace mdhd::service {

std::optional<long long> integerInRange(const std::string& text, long long lo, long long hi) {
  // Digits with an optional '-', nothing else: std::stoll alone also takes leading
  // spaces and a '+' ("?limit=+2", "--port ' 80'").
  const std::size_t digits = !text.empty() && text[0] == '-' ? 1 : 0;
  if (text.size() == digits) return std::nullopt;
  for (std::size_t i = digits; i < text.size(); ++i) {
    if (text[i] < '0' || text[i] > '9') return std::nullopt;
  }
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
