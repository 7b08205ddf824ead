// validate_spline: every GeometryError it can return, on a minimal malformed spline each.
#include <gtest/gtest.h>

#include <cstring>

#include "firmware/core/spline.h"

namespace {

using core::GeometryError;

// A valid clamped cubic with 4 control points: knots 0 0 0 0 1 1 1 1.
core::Spline valid_cubic() {
  core::Spline s;
  std::memset(&s, 0, sizeof s);
  s.degree = 3;
  s.rational = false;
  s.control_count = 4;
  s.knot_count = 8;
  for (int i = 0; i < 4; ++i) {
    s.control[i].x_um = i * 1000;
    s.control[i].y_um = (i % 2) * 500;
    s.control[i].weight_q14 = core::kWeightOneQ14;
  }
  const int32_t knots[8] = {0, 0, 0, 0, 1, 1, 1, 1};
  for (int i = 0; i < 8; ++i) s.knot[i] = knots[i];
  return s;
}

TEST(ValidateSpline, AcceptsAValidClampedCubic) {
  EXPECT_EQ(core::validate_spline(valid_cubic()), GeometryError::kOk);
}

TEST(ValidateSpline, RejectsDegreeZeroAndDegreeFour) {
  core::Spline s = valid_cubic();
  s.degree = 0;
  EXPECT_EQ(core::validate_spline(s), GeometryError::kDegreeUnsupported);
  s.degree = 4;
  EXPECT_EQ(core::validate_spline(s), GeometryError::kDegreeUnsupported);
}

TEST(ValidateSpline, RejectsMoreControlPointsThanCapacity) {
  core::Spline s = valid_cubic();
  s.control_count = core::kMaxControlPoints + 1;
  s.knot_count = s.control_count + 4;
  EXPECT_EQ(core::validate_spline(s), GeometryError::kTooManyControlPoints);
}

TEST(ValidateSpline, RejectsFewerControlPointsThanDegreePlusOne) {
  core::Spline s = valid_cubic();
  s.control_count = 3;
  s.knot_count = 7;
  EXPECT_EQ(core::validate_spline(s), GeometryError::kTooFewControlPoints);
}

TEST(ValidateSpline, RejectsAKnotCountOtherThanControlsPlusDegreePlusOne) {
  core::Spline s = valid_cubic();
  s.knot_count = 7;
  EXPECT_EQ(core::validate_spline(s), GeometryError::kKnotCountMismatch);
  s.knot_count = 0xFFFF;  // huge count must not be read past the array
  EXPECT_EQ(core::validate_spline(s), GeometryError::kKnotCountMismatch);
}

TEST(ValidateSpline, RejectsDecreasingKnots) {
  core::Spline s = valid_cubic();
  s.knot[5] = 0;  // 0 0 0 0 1 0 1 1
  EXPECT_EQ(core::validate_spline(s), GeometryError::kKnotsDecreasing);
}

TEST(ValidateSpline, RejectsAZeroLengthCurveDomain) {
  core::Spline s = valid_cubic();
  for (int i = 0; i < 8; ++i) s.knot[i] = 5;  // all knots equal
  EXPECT_EQ(core::validate_spline(s), GeometryError::kKnotRangeEmpty);
}

TEST(ValidateSpline, RejectsADomainEmptyEvenIfOuterKnotsDiffer) {
  core::Spline s = valid_cubic();
  const int32_t knots[8] = {-3, -2, -1, 0, 0, 1, 2, 3};  // knot[3] == knot[4]: empty
  for (int i = 0; i < 8; ++i) s.knot[i] = knots[i];
  EXPECT_EQ(core::validate_spline(s), GeometryError::kKnotRangeEmpty);
}

TEST(ValidateSpline, NeverReturnsSpanTooLongEvenForTheFullInt32KnotRange) {
  // kKnotSpanTooLong is reserved: normalisation handles any int32 knot range.
  core::Spline s = valid_cubic();
  const int32_t knots[8] = {INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN,
                            INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX};
  for (int i = 0; i < 8; ++i) s.knot[i] = knots[i];
  EXPECT_EQ(core::validate_spline(s), GeometryError::kOk);
}

TEST(ValidateSpline, RejectsACoordinateJustOutsideOneMetre) {
  core::Spline s = valid_cubic();
  s.control[2].y_um = core::kMaxCoordinateUm + 1;
  EXPECT_EQ(core::validate_spline(s), GeometryError::kCoordinateOutOfRange);
  s.control[2].y_um = -core::kMaxCoordinateUm;  // the limit itself is fine
  EXPECT_EQ(core::validate_spline(s), GeometryError::kOk);
  s.control[0].x_um = -core::kMaxCoordinateUm - 1;
  EXPECT_EQ(core::validate_spline(s), GeometryError::kCoordinateOutOfRange);
}

TEST(ValidateSpline, RejectsAZeroWeightOnlyWhenRational) {
  core::Spline s = valid_cubic();
  s.control[1].weight_q14 = 0;
  EXPECT_EQ(core::validate_spline(s), GeometryError::kOk);  // weights unused
  s.rational = true;
  EXPECT_EQ(core::validate_spline(s), GeometryError::kZeroWeight);
}

}  // namespace
