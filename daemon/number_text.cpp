#include "daemon/number_text.h"

#include <stdexcept>

namespace mdhd::service {

std::optional<std::uint64_t> decimalDigits(std::string_view text, std::size_t maxDigits) {
  if (text.empty() || text.size() > maxDigits || maxDigits > 19) return std::nullopt;
  std::uint64_t v = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    v = v * 10 + static_cast<std::uint64_t>(c - '0');
  }
  return v;
}

std::optional<long long> integerInRange(const std::string& text, long long lo, long long hi) {
  // Digits with an optional '-', nothing else (std::stoll also took leading spaces and
  // a '+': "?limit=+2", "--port ' 80'"). 18 digits always fit a long long.
  const bool negative = !text.empty() && text[0] == '-';
  const auto digits = decimalDigits(std::string_view(text).substr(negative ? 1 : 0), 18);
  if (!digits) return std::nullopt;
  const long long v = negative ? -static_cast<long long>(*digits) : static_cast<long long>(*digits);
  if (v < lo || v > hi) return std::nullopt;
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
