// On-target checks of core::SpscRing: FIFO order, full/empty edges, peek, and indices that
// wrap past 65535 (the 16-bit counters the ISR sharing relies on).
#include "firmware/core/spline.h"     // PointUm
#include "firmware/core/spsc_ring.h"  // SpscRing

#include "host_tests/target_proxy/proxy_check.h"
#include "host_tests/target_proxy/proxy_checks.h"

namespace proxy {

namespace {

// Fills an 8-slot ring, overfills it, and empties it in order.
void check_fill_and_drain() {
  core::SpscRing<uint16_t, 8> ring;
  PROXY_CHECK(ring.empty());
  PROXY_CHECK_EQ(ring.capacity(), 8);
  uint16_t out = 0;
  PROXY_CHECK(!ring.pop(&out));
  for (uint16_t i = 0; i < 8; ++i) PROXY_CHECK(ring.push((uint16_t)(100 + i)));
  PROXY_CHECK(ring.full());
  PROXY_CHECK_EQ(ring.size(), 8);
  PROXY_CHECK_EQ(ring.free_space(), 0);
  PROXY_CHECK(!ring.push(999));  // full: refused, nothing overwritten
  PROXY_CHECK(ring.peek(0) != 0 && *ring.peek(0) == 100);
  PROXY_CHECK(ring.peek(7) != 0 && *ring.peek(7) == 107);
  PROXY_CHECK(ring.peek(8) == 0);
  for (uint16_t i = 0; i < 8; ++i) {
    PROXY_CHECK(ring.pop(&out));
    PROXY_CHECK_EQ(out, 100 + i);
  }
  PROXY_CHECK(ring.empty());
  PROXY_CHECK(!ring.pop(&out));
}

// Runs the ring's counters past 65535 with the ring kept partly full: order and size hold.
void check_index_wrap() {
  core::SpscRing<uint16_t, 4> ring;
  uint16_t next_in = 0;
  uint16_t next_out = 0;
  uint16_t wrong_order = 0;
  uint16_t wrong_size = 0;
  uint32_t popped = 0;
  for (uint32_t round = 0; round < 140000UL; ++round) {
    if (ring.size() < 3) ring.push(next_in++);
    uint16_t v = 0;
    if ((round & 1U) && ring.pop(&v)) {
      if (v != next_out) ++wrong_order;
      ++next_out;
      ++popped;
    }
    if (ring.size() != (uint16_t)(next_in - next_out)) ++wrong_size;
  }
  PROXY_CHECK_EQ(wrong_order, 0);
  PROXY_CHECK_EQ(wrong_size, 0);
  PROXY_CHECK(popped > 65536UL);  // the counters really wrapped
}

// A ring of 2-D points (the coordinate ring's element) keeps both coordinates.
void check_point_ring() {
  core::SpscRing<core::PointUm, 2> ring;
  core::PointUm a = {-1000000L, 1000000L};
  core::PointUm b = {123456L, -654321L};
  PROXY_CHECK(ring.push(a));
  PROXY_CHECK(ring.push(b));
  PROXY_CHECK(!ring.push(a));
  core::PointUm out = {0, 0};
  PROXY_CHECK(ring.pop(&out));
  PROXY_CHECK_EQ(out.x_um, -1000000L);
  PROXY_CHECK_EQ(out.y_um, 1000000L);
  PROXY_CHECK(ring.pop(&out));
  PROXY_CHECK_EQ(out.x_um, 123456L);
  PROXY_CHECK_EQ(out.y_um, -654321L);
}

}  // namespace

void run_ring_checks() {
  begin_group(PROXY_STR("spsc_ring"));
  check_fill_and_drain();
  check_index_wrap();
  check_point_ring();
  end_group();
}

}  // namespace proxy
