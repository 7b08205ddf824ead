// Spline store: header checks, data order and counts, two slots, validation at the end.
#include <gtest/gtest.h>

#include "firmware/app/spline_store.h"

namespace {

proto::SplineHeaderCmd header(uint16_t controls) {
  return proto::SplineHeaderCmd{3, false, controls, uint16_t(controls + 4), 10000};
}

proto::SplineDataCmd controls(uint8_t index, uint8_t n, int32_t y_um = 0) {
  proto::SplineDataCmd d{};
  d.control_index = index;
  d.control_n = n;
  d.knot_index = 0;
  d.knot_n = 0;
  for (uint8_t i = 0; i < n; ++i) d.control[i] = {int32_t(1000 * (index + i)), y_um, 16384};
  return d;
}

proto::SplineDataCmd knots(uint8_t control_count, uint8_t index, uint8_t n) {
  proto::SplineDataCmd d{};
  d.control_index = control_count;
  d.knot_index = index;
  d.knot_n = n;
  const int32_t k[8] = {0, 0, 0, 0, 1, 1, 1, 1};
  for (uint8_t i = 0; i < n; ++i) d.knot[i] = k[index + i];
  return d;
}

const int32_t kTravel[2] = {297000, 210000};

TEST(SplineStore, KnotCountNotMatchingTheHeaderIsAFieldRangeError) {
  app::SplineStore store;
  proto::SplineHeaderCmd h = header(4);
  h.knot_count = 9;
  uint8_t slot;
  EXPECT_EQ(store.begin(h, &slot), proto::ErrorCode::kFieldRange);
}

TEST(SplineStore, TwoSlotsThenNoFreeSlot) {
  app::SplineStore store;
  uint8_t slot;
  EXPECT_EQ(store.begin(header(4), &slot), proto::ErrorCode::kOk);
  EXPECT_EQ(store.begin(header(4), &slot), proto::ErrorCode::kOk);
  EXPECT_FALSE(store.has_free_slot());
  EXPECT_EQ(store.begin(header(4), &slot), proto::ErrorCode::kBusy);
}

TEST(SplineStore, DataMustContinueWhereThePreviousFrameStopped) {
  app::SplineStore store;
  uint8_t slot, detail;
  bool done;
  ASSERT_EQ(store.begin(header(4), &slot), proto::ErrorCode::kOk);
  EXPECT_EQ(store.add(controls(0, 2), kTravel, &detail, &done), proto::ErrorCode::kOk);
  EXPECT_EQ(store.add(controls(3, 1), kTravel, &detail, &done), proto::ErrorCode::kSplineSequence);
  EXPECT_EQ(store.add(controls(2, 3), kTravel, &detail, &done),  // 5 > 4 announced
            proto::ErrorCode::kSplineSequence);
  EXPECT_EQ(store.add(controls(2, 2), kTravel, &detail, &done), proto::ErrorCode::kOk);
  EXPECT_FALSE(done);
  EXPECT_EQ(store.add(knots(4, 0, 8), kTravel, &detail, &done), proto::ErrorCode::kOk);
  EXPECT_TRUE(done);
  EXPECT_EQ(store.state(slot), app::SlotState::kReady);
}

TEST(SplineStore, DataWithoutAHeaderIsASequenceError) {
  app::SplineStore store;
  uint8_t detail;
  bool done;
  EXPECT_EQ(store.add(controls(0, 1), kTravel, &detail, &done), proto::ErrorCode::kSplineSequence);
}

TEST(SplineStore, ControlPointOutsideTheTravelIsRefusedAndNotStored) {
  app::SplineStore store;
  uint8_t slot, detail;
  bool done;
  ASSERT_EQ(store.begin(header(4), &slot), proto::ErrorCode::kOk);
  EXPECT_EQ(store.add(controls(0, 2, 210001), kTravel, &detail, &done),
            proto::ErrorCode::kOutOfTravel);
  EXPECT_EQ(store.add(controls(0, 2), kTravel, &detail, &done), proto::ErrorCode::kOk);
}

TEST(SplineStore, InvalidSplineIsCancelledWithItsGeometryCode) {
  app::SplineStore store;
  uint8_t slot, detail;
  bool done;
  ASSERT_EQ(store.begin(header(4), &slot), proto::ErrorCode::kOk);
  ASSERT_EQ(store.add(controls(0, 4), kTravel, &detail, &done), proto::ErrorCode::kOk);
  proto::SplineDataCmd k = knots(4, 0, 8);
  k.knot[6] = -1;  // decreasing
  EXPECT_EQ(store.add(k, kTravel, &detail, &done), proto::ErrorCode::kGeometry);
  EXPECT_EQ(detail, uint8_t(core::GeometryError::kKnotsDecreasing));
  EXPECT_EQ(store.state(slot), app::SlotState::kCancelled);
}

}  // namespace
