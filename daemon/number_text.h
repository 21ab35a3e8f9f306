#pragma once
// Numbers given as text (flags, environment, query parameters): the whole text must
// be the number, in range, or there is none.
#include <optional>
#include <string>

namespace mdhd::service {

std::optional<long long> integerInRange(const std::string& text, long long lo, long long hi);
std::optional<double> numberInRange(const std::string& text, double lo, double hi);

}  // namespace mdhd::service
