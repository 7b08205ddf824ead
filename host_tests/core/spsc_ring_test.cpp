// SpscRing: capacity, wrap-around of slots and of the 16-bit indices, full/empty, peek,
// newest, reserve/commit, clear, and a two-thread producer/consumer stress run.
#include "firmware/core/spsc_ring.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <thread>

namespace {

typedef core::SpscRing<uint32_t, 8> Ring8;

TEST(SpscRing, StartsEmptyWithFullFreeSpace) {
  Ring8 r;
  EXPECT_TRUE(r.empty());
  EXPECT_FALSE(r.full());
  EXPECT_EQ(r.size(), 0u);
  EXPECT_EQ(r.free_space(), 8u);
  EXPECT_EQ(Ring8::capacity(), 8u);
  uint32_t v = 99;
  EXPECT_FALSE(r.pop(&v));
  EXPECT_EQ(v, 99u);  // untouched
}

TEST(SpscRing, HoldsExactlyCapacityElementsThenRefuses) {
  Ring8 r;
  for (uint32_t i = 0; i < 8; ++i) EXPECT_TRUE(r.push(i));
  EXPECT_TRUE(r.full());
  EXPECT_EQ(r.free_space(), 0u);
  EXPECT_FALSE(r.push(100));
  uint32_t v = 0;
  for (uint32_t i = 0; i < 8; ++i) {
    ASSERT_TRUE(r.pop(&v));
    EXPECT_EQ(v, i);  // the refused 100 never appears
  }
  EXPECT_TRUE(r.empty());
}

TEST(SpscRing, ReservedSlotIsSeenOnlyAfterCommitAndNoneWhenFull) {
  Ring8 r;
  uint32_t v = 0;
  for (uint32_t round = 0; round < 20; ++round) {  // the slots wrap: reserve follows head
    uint32_t* slot = r.reserve();
    ASSERT_NE(slot, nullptr);
    *slot = 1000 + round;
    EXPECT_TRUE(r.empty());  // written, not published
    EXPECT_FALSE(r.pop(&v));
    EXPECT_EQ(r.reserve(), slot);  // reserving again gives the same slot
    r.commit();
    ASSERT_TRUE(r.pop(&v));
    EXPECT_EQ(v, 1000 + round);
  }
  for (uint32_t i = 0; i < 8; ++i) {
    uint32_t* slot = r.reserve();
    ASSERT_NE(slot, nullptr);
    *slot = i;
    r.commit();
  }
  EXPECT_TRUE(r.full());
  EXPECT_EQ(r.reserve(), nullptr);  // full: nothing to write into
  for (uint32_t i = 0; i < 8; ++i) {
    ASSERT_TRUE(r.pop(&v));
    EXPECT_EQ(v, i);  // FIFO, as push() gives
  }
  EXPECT_TRUE(r.empty());
}

TEST(SpscRing, KeepsFifoOrderAcrossSlotWrapAndIndexOverflow) {
  Ring8 r;
  uint32_t next_in = 0, next_out = 0, v = 0;
  // 70000 > 65536 operations: the free-running 16-bit indices wrap as well.
  for (int round = 0; round < 70000 / 5; ++round) {
    for (int k = 0; k < 5; ++k) ASSERT_TRUE(r.push(next_in++));
    for (int k = 0; k < 5; ++k) {
      ASSERT_TRUE(r.pop(&v));
      ASSERT_EQ(v, next_out++);
    }
  }
  EXPECT_TRUE(r.empty());
}

TEST(SpscRing, FullAndEmptyAreToldApartWhenIndicesWrap) {
  Ring8 r;
  uint32_t v = 0;
  for (uint32_t i = 0; i < 65533; ++i) {  // park the indices just below 2^16
    r.push(i);
    r.pop(&v);
  }
  for (uint32_t i = 0; i < 8; ++i) ASSERT_TRUE(r.push(i));
  EXPECT_TRUE(r.full());
  EXPECT_EQ(r.size(), 8u);
  for (uint32_t i = 0; i < 8; ++i) ASSERT_TRUE(r.pop(&v));
  EXPECT_TRUE(r.empty());
  EXPECT_EQ(r.size(), 0u);
}

TEST(SpscRing, PeekSeesOldestFirstAndNothingPastTheEnd) {
  Ring8 r;
  r.push(10);
  r.push(11);
  r.push(12);
  ASSERT_NE(r.peek(0), nullptr);
  EXPECT_EQ(*r.peek(0), 10u);
  EXPECT_EQ(*r.peek(2), 12u);
  EXPECT_EQ(r.peek(3), nullptr);
  EXPECT_EQ(r.size(), 3u);  // peek removes nothing
}

// The producer's view for in-place updates (the planner's backward pass over the coordinate
// ring): newest first, only what is not consumed, across the slot wrap.
TEST(SpscRing, NewestCountsBackFromTheLastPushAndStopsAtTheOldest) {
  Ring8 r;
  EXPECT_EQ(r.newest(0), nullptr);
  uint32_t v = 0;
  for (uint32_t i = 0; i < 8; ++i) ASSERT_TRUE(r.push(i));
  for (uint32_t i = 0; i < 5; ++i) ASSERT_TRUE(r.pop(&v));
  for (uint32_t i = 8; i < 11; ++i) ASSERT_TRUE(r.push(i));  // the slots wrap: 5..10 stored
  ASSERT_EQ(r.size(), 6u);
  for (uint16_t k = 0; k < 6; ++k) {
    ASSERT_NE(r.newest(k), nullptr);
    EXPECT_EQ(*r.newest(k), 10u - k);
  }
  EXPECT_EQ(r.newest(6), nullptr);  // 4 was consumed
  *r.newest(4) = 100;               // 6 updated in place, seen by the consumer
  ASSERT_TRUE(r.pop(&v));
  EXPECT_EQ(v, 5u);
  ASSERT_TRUE(r.pop(&v));
  EXPECT_EQ(v, 100u);
}

TEST(SpscRing, ClearDropsEverythingAndTheRingStaysUsable) {
  Ring8 r;
  for (uint32_t i = 0; i < 6; ++i) r.push(i);
  r.clear();
  EXPECT_TRUE(r.empty());
  EXPECT_EQ(r.free_space(), 8u);
  EXPECT_TRUE(r.push(42));
  uint32_t v = 0;
  ASSERT_TRUE(r.pop(&v));
  EXPECT_EQ(v, 42u);
}

TEST(SpscRing, TwoThreadsLoseDoubleOrReorderNothing) {
  // 300000 elements through a 16-slot ring: every one must come out once, in order.
  const uint32_t kCount = 300000;
  core::SpscRing<uint32_t, 16> ring;
  std::thread producer([&ring]() {
    for (uint32_t i = 0; i < kCount;) {
      if (ring.push(i)) {
        ++i;
      } else {
        std::this_thread::yield();
      }
    }
  });
  uint32_t expected = 0, mismatches = 0, v = 0;
  while (expected < kCount) {
    if (ring.pop(&v)) {
      if (v != expected) ++mismatches;
      expected = v + 1;  // resynchronise so one fault is counted once
    } else {
      std::this_thread::yield();
    }
  }
  producer.join();
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(expected, kCount);
  EXPECT_TRUE(ring.empty());
}

}  // namespace
