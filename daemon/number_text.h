#pragma once
// Numbers given as text (flags, environment, query parameters): the whole text must
// be the number, in range, or there is none.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace mdhd::service {

// Digits only (no sign, no spaces), at most `maxDigits` (<= 19, so it fits), as a
// number: Content-Length, byte-range positions, and the digits of integerInRange.
std::optional<std::uint64_t> decimalDigits(std::string_view text, std::size_t maxDigits);

// An optional '-' and digits, within [lo, hi].
std::optional<long long> integerInRange(const std::string& text, long long lo, long long hi);
std::optional<double> numberInRange(const std::string& text, double lo, double hi);

}  // namespace mdhd::service
