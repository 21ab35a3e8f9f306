#pragma once
// A heightmap's direction of representation: +a means the solid runs from the
// cell's low face along a up to the stored height, -a from the high face down.
#include <string_view>

namespace mdhd::mdh {

struct Direction {
  int axis = 2;
  int sign = 1;
  int index() const { return axis * 2 + (sign < 0 ? 1 : 0); }  // +x -x +y -y +z -z
  bool operator==(const Direction&) const = default;
};

inline std::string_view directionName(Direction d) {
  static constexpr std::string_view kNames[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  return kNames[d.index()];
}

inline Direction directionFromIndex(int index) {
  return Direction{index / 2, (index % 2) ? -1 : 1};
}

}  // namespace mdhd::mdh
