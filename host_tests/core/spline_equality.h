// gtest check that two firmware splines hold the same values, field by field (what a
// codec or store round trip must keep exactly).
#ifndef HOST_TESTS_CORE_SPLINE_EQUALITY_H
#define HOST_TESTS_CORE_SPLINE_EQUALITY_H

#include <gtest/gtest.h>

#include "firmware/core/spline.h"

namespace test {

inline void expect_same_spline(const core::Spline& a, const core::Spline& b) {
  ASSERT_EQ(a.degree, b.degree);
  ASSERT_EQ(a.rational, b.rational);
  ASSERT_EQ(a.control_count, b.control_count);
  ASSERT_EQ(a.knot_count, b.knot_count);
  for (int i = 0; i < a.control_count; ++i) {
    EXPECT_EQ(a.control[i].x_um, b.control[i].x_um) << i;
    EXPECT_EQ(a.control[i].y_um, b.control[i].y_um) << i;
    EXPECT_EQ(a.control[i].weight_q14, b.control[i].weight_q14) << i;
  }
  for (int k = 0; k < a.knot_count; ++k) EXPECT_EQ(a.knot[k], b.knot[k]) << k;
}

}  // namespace test

#endif  // HOST_TESTS_CORE_SPLINE_EQUALITY_H
