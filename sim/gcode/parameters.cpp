#include "sim/gcode/parameters.h"

#include <algorithm>
#include <stdexcept>

namespace mdhd::gcode {
namespace {

bool isGlobalName(std::string_view name) {
  return !name.empty() && name.front() == '_';
}

}  // namespace

ParameterStore::ParameterStore() : numbered_(kMaxNumber + 1, 0.0), frames_(1) {
  numbered_[kDebugEnable] = 1.0;
}

double ParameterStore::get(int number) const {
  if (!validNumber(number)) throw std::out_of_range("parameter number out of range");
  return numbered_[static_cast<std::size_t>(number)];
}

void ParameterStore::set(int number, double value) {
  if (!validNumber(number)) throw std::out_of_range("parameter number out of range");
  numbered_[static_cast<std::size_t>(number)] = value;
}

std::optional<double> ParameterStore::findNamed(std::string_view name) const {
  if (isGlobalName(name)) {
    if (name == "_value") return return_value_;
    if (name == "_value_returned") return value_returned_ ? 1.0 : 0.0;
    if (predefined_) {
      if (auto v = predefined_(name)) return v;
    }
    const auto it = globals_.find(name);
    if (it == globals_.end()) return std::nullopt;
    return it->second;
  }
  const NameMap& locals = frames_.back().locals;
  const auto it = locals.find(name);
  if (it == locals.end()) return std::nullopt;
  return it->second;
}

bool ParameterStore::isReadOnly(std::string_view name) const {
  if (!isGlobalName(name)) return false;
  if (name == "_value" || name == "_value_returned") return true;
  return predefined_ && predefined_(name).has_value();
}

void ParameterStore::setNamed(std::string_view name, double value) {
  NameMap& map = isGlobalName(name) ? globals_ : frames_.back().locals;
  const auto it = map.find(name);
  if (it != map.end()) {
    it->second = value;
  } else {
    map.emplace(std::string(name), value);
  }
}

void ParameterStore::enterCall(const double* args, int count) {
  Frame& frame = frames_.emplace_back();
  for (int i = 0; i < kLocalCount; ++i) {
    double& slot = numbered_[static_cast<std::size_t>(i + 1)];
    frame.saved[static_cast<std::size_t>(i)] = slot;
    slot = i < count ? args[i] : 0.0;
  }
}

void ParameterStore::leaveCall() {
  if (frames_.size() <= 1) return;
  const Frame& frame = frames_.back();
  std::copy(frame.saved.begin(), frame.saved.end(), numbered_.begin() + 1);
  frames_.pop_back();
}

void ParameterStore::setReturnValue(std::optional<double> value) {
  value_returned_ = value.has_value();
  return_value_ = value.value_or(0.0);
}

}  // namespace mdhd::gcode
