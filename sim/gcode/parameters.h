#pragma once
// The parameter table of RS274/NGC: numbered #1..#5601 (#1..#30 local to a
// subroutine call level), named #<name> (local to the call level) and
// #<_name> (global), plus read-only predefined names the interpreter supplies
// through a hook. Shared by the reader (expressions, assignments, calls) and
// the interpreter (offsets, tool, position).
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace mdhd::gcode {

class ParameterStore {
 public:
  static constexpr int kMaxNumber = 5601;    // LinuxCNC: RS274NGC_MAX_PARAMETERS 5602, exclusive
  static constexpr int kDebugEnable = 5599;  // (DEBUG,...) messages shown while > 0; starts at 1
  static constexpr int kLocalCount = 30;     // #1..#30 are per call level
  using PredefinedHook = std::function<std::optional<double>(std::string_view name)>;

  ParameterStore();

  static bool validNumber(int number) { return number >= 1 && number <= kMaxNumber; }
  // Numbered parameters. Out of range is the caller's error to report (with its
  // position): here it throws std::out_of_range.
  double get(int number) const;
  void set(int number, double value);

  // Predefined read-only named parameters (#<_x>, #<_metric>, ...). The hook
  // gets the lower-case name without '#<' '>' and answers nullopt if unknown.
  void setPredefined(PredefinedHook hook) { predefined_ = std::move(hook); }

  // Named parameters, names lower case without blanks (as the reader gives
  // them). Lookup order: #<_value>/#<_value_returned>, the predefined hook,
  // then globals (leading '_') or the current level's locals.
  std::optional<double> findNamed(std::string_view name) const;
  bool isReadOnly(std::string_view name) const;
  void setNamed(std::string_view name, double value);  // caller checks isReadOnly first

  // Subroutine call levels: entering saves #1..#30 and starts a fresh set of
  // locals with #1..#n = args (the rest 0); leaving restores the caller's.
  void enterCall(const double* args, int count);
  void leaveCall();
  int callLevel() const { return static_cast<int>(frames_.size()) - 1; }

  // What the last return/endsub gave, read as #<_value> and #<_value_returned>.
  void setReturnValue(std::optional<double> value);

 private:
  struct NameHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  using NameMap = std::unordered_map<std::string, double, NameHash, std::equal_to<>>;
  struct Frame {
    std::array<double, kLocalCount> saved{};  // the caller's #1..#30
    NameMap locals;
  };

  std::vector<double> numbered_;
  NameMap globals_;
  std::vector<Frame> frames_;  // frames_[0]: the main program
  PredefinedHook predefined_;
  double return_value_ = 0.0;
  bool value_returned_ = false;
};

}  // namespace mdhd::gcode
