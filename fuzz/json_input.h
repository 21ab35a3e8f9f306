#pragma once
// The JSON fuzz targets' first step: the bytes as a document, or nothing when they are
// not JSON (a FieldError with its place: the answer such bytes must get).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "protocol/job_json.h"

namespace mdhd::fuzz {

inline std::optional<nlohmann::json> jsonInput(const std::uint8_t* data, std::size_t size) {
  try {
    return protocol::parseJsonText(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const protocol::FieldError&) {
    return std::nullopt;
  }
}

}  // namespace mdhd::fuzz
