#pragma once
// Shared by the kinematics tests: compare vectors component by component.
#include <gtest/gtest.h>

#include <glm/vec3.hpp>

#define EXPECT_VEC_NEAR(actual, expected, tol)       \
  do {                                               \
    const glm::dvec3 a_ = (actual);                  \
    const glm::dvec3 e_ = (expected);                \
    EXPECT_NEAR(a_.x, e_.x, tol) << "x of " #actual; \
    EXPECT_NEAR(a_.y, e_.y, tol) << "y of " #actual; \
    EXPECT_NEAR(a_.z, e_.z, tol) << "z of " #actual; \
  } while (0)
