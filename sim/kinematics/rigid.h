#pragma once
// A rigid transform (rotation + translation) in doubles: the kinematics compose
// dozens of these per simulation step, and a 3x3 + 3 is cheaper than a 4x4 and
// keeps its inverse exact (the transpose).
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace mdhd::kin {

struct Rigid {
  glm::dmat3 rotation{1.0};
  glm::dvec3 translation{0.0};

  glm::dvec3 point(const glm::dvec3& p) const { return rotation * p + translation; }
  glm::dvec3 vector(const glm::dvec3& v) const { return rotation * v; }

  // (*this) * other: first other, then this.
  Rigid operator*(const Rigid& other) const {
    return {rotation * other.rotation, rotation * other.translation + translation};
  }

  Rigid inverse() const {
    const glm::dmat3 rt = glm::transpose(rotation);
    return {rt, -(rt * translation)};
  }

  glm::dmat4 matrix() const {
    glm::dmat4 m(rotation);
    m[3] = glm::dvec4(translation, 1.0);
    return m;
  }
};

}  // namespace mdhd::kin
