// #K compact spline data through the codec and the spline store: the same spline as #D and
// as #K is stored bit for bit the same and walks to the same points; malformed #K frames are
// refused with their code and leave the store as it was.
#include <gtest/gtest.h>

#include <algorithm>  // std::max, std::min
#include <cstdint>    // INT32_MIN, INT32_MAX
#include <cstdlib>    // std::abs
#include <random>     // std::mt19937
#include <vector>     // std::vector

#include "firmware/app/spline_store.h"
#include "firmware/core/curve_walker.h"
#include "firmware/protocol/codec.h"
#include "firmware/protocol/compact_spline.h"
#include "host_tests/app/through_wire.h"
#include "host_tests/core/spline_equality.h"

namespace {

const int32_t kTravel[2] = {1000000, 1000000};

proto::SplineHeaderCmd header_of(const core::Spline& s) {
  proto::SplineHeaderCmd h{};
  h.degree = s.degree;
  h.rational = s.rational;
  h.control_count = s.control_count;
  h.knot_count = s.knot_count;
  h.feed_um_per_s = 5000;
  return h;
}

// #K frames for s, each with at most `room` data bytes, as the host encoder packs them.
std::vector<proto::SplineCompactCmd> compact_frames(const core::Spline& s, unsigned room = 60) {
  std::vector<proto::SplineCompactCmd> out;
  unsigned c = 0, k = 0;
  uint8_t value[proto::kMaxCompactPointBytes];
  while (c < s.control_count || k < s.knot_count) {
    proto::SplineCompactCmd d{};
    d.control_index = uint8_t(c);
    d.knot_index = uint8_t(k);
    while (c < s.control_count) {
      core::ControlPoint prev = {0, 0, core::kWeightOneQ14};
      if (c > 0) prev = s.control[c - 1];
      const uint8_t n = proto::put_compact_point(prev, s.control[c], s.rational, value);
      if (d.data_n + n > room) break;
      for (uint8_t i = 0; i < n; ++i) d.data[d.data_n++] = value[i];
      ++d.control_n;
      ++c;
    }
    while (c == s.control_count && k < s.knot_count) {
      const bool repeat = k > 0 && k + 1 < s.knot_count && s.knot[k + 1] == s.knot[k];
      const uint8_t n =
          proto::put_compact_knot(k > 0 ? s.knot[k - 1] : 0, s.knot[k], k == 0, repeat, value);
      EXPECT_GT(n, 0) << "knots must not decrease";
      if (d.data_n + n > room) break;
      for (uint8_t i = 0; i < n; ++i) d.data[d.data_n++] = value[i];
      d.knot_n = uint8_t(d.knot_n + (repeat ? 2 : 1));
      k += repeat ? 2 : 1;
    }
    out.push_back(d);
  }
  return out;
}

// The same spline as #D frames (6 points, then 15 knots a frame).
std::vector<proto::SplineDataCmd> full_frames(const core::Spline& s) {
  std::vector<proto::SplineDataCmd> out;
  unsigned c = 0, k = 0;
  while (c < s.control_count || k < s.knot_count) {
    proto::SplineDataCmd d{};
    d.control_index = uint8_t(c);
    d.knot_index = uint8_t(k);
    while (c < s.control_count && d.control_n < 6) d.control[d.control_n++] = s.control[c++];
    while (c == s.control_count && k < s.knot_count && 10 * d.control_n + 4 * (d.knot_n + 1) <= 60)
      d.knot[d.knot_n++] = s.knot[k++];
    out.push_back(d);
  }
  return out;
}

// A spline with n points on a random walk of steps up to `step` um (clamped to +-1 m),
// degree p, uniform-ish increasing knots; rational with random weights when asked.
core::Spline random_spline(std::mt19937* rng, uint16_t n, uint8_t p, bool rational, int32_t step) {
  core::Spline s{};
  s.degree = p;
  s.rational = rational;
  s.control_count = n;
  s.knot_count = uint16_t(n + p + 1);
  int32_t x = int32_t((*rng)() % 2000001) - 1000000, y = int32_t((*rng)() % 2000001) - 1000000;
  for (uint16_t i = 0; i < n; ++i) {
    x += int32_t((*rng)() % (2 * uint32_t(step) + 1)) - step;
    y += int32_t((*rng)() % (2 * uint32_t(step) + 1)) - step;
    x = std::max<int32_t>(-1000000, std::min<int32_t>(1000000, x));
    y = std::max<int32_t>(-1000000, std::min<int32_t>(1000000, y));
    const uint16_t w = rational ? uint16_t(1 + (*rng)() % 65535) : core::kWeightOneQ14;
    s.control[i] = {x, y, w};
  }
  int32_t k = -int32_t((*rng)() % 100000);
  for (uint16_t i = 0; i < s.knot_count; ++i) {
    if (i > p && i < n) k += int32_t((*rng)() % 5000000);
    if (i == n) k += 1 + int32_t((*rng)() % 5000000);
    s.knot[i] = k;
  }
  return s;
}

// Stores s with #K frames (through the codec) and returns the stored spline.
core::Spline store_compact(const core::Spline& s, unsigned room = 60) {
  app::SplineStore store;
  uint8_t slot = 0, detail = 0;
  bool done = false;
  EXPECT_EQ(store.begin(header_of(s), &slot), proto::ErrorCode::kOk);
  for (const proto::SplineCompactCmd& d : compact_frames(s, room)) {
    EXPECT_EQ(store.add_compact(test::through_wire(d), kTravel, &detail, &done),
              proto::ErrorCode::kOk);
  }
  EXPECT_TRUE(done);
  EXPECT_EQ(store.state(slot), app::SlotState::kReady);
  return *store.spline(slot);
}

core::Spline store_full(const core::Spline& s) {
  app::SplineStore store;
  uint8_t slot = 0, detail = 0;
  bool done = false;
  EXPECT_EQ(store.begin(header_of(s), &slot), proto::ErrorCode::kOk);
  for (const proto::SplineDataCmd& d : full_frames(s)) {
    EXPECT_EQ(store.add(test::through_wire(d), kTravel, &detail, &done), proto::ErrorCode::kOk);
  }
  EXPECT_TRUE(done);
  return *store.spline(slot);
}

std::vector<core::PointUm> walk(const core::Spline& s) {
  core::CurveWalker w;
  std::vector<core::PointUm> out;
  EXPECT_EQ(w.begin(&s, core::default_step_settings()), core::GeometryError::kOk);
  core::PointUm p;
  while (w.next(&p)) out.push_back(p);
  EXPECT_EQ(w.error(), core::GeometryError::kOk);
  return out;
}

TEST(SplineCompact, RandomSplinesStoreExactlyAsWithFullFrames) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 300; ++trial) {
    const uint8_t p = uint8_t(1 + trial % 3);
    const uint16_t n = uint16_t(p + 1 + rng() % (64 - p));
    const int32_t step = trial % 4 == 0 ? 2000000 : trial % 4 == 1 ? 60 : 20000;
    const core::Spline s = random_spline(&rng, n, p, trial % 2 == 0, step);
    SCOPED_TRACE(trial);
    const core::Spline full = store_full(s);
    const core::Spline compact = store_compact(s);
    test::expect_same_spline(full, compact);
    test::expect_same_spline(s, compact);
  }
}

TEST(SplineCompact, LargestSplineAndLargestDifferencesFitTheFrames) {
  // 64 points jumping between opposite corners of the +-1 m square, weights 1 <-> 65535,
  // knots from int32 min to int32 max: every value takes its longest form.
  core::Spline s{};
  s.degree = 3;
  s.rational = true;
  s.control_count = core::kMaxControlPoints;
  s.knot_count = core::kMaxKnots;
  for (uint16_t i = 0; i < s.control_count; ++i) {
    const int32_t v = i % 2 ? 1000000 : -1000000;
    s.control[i] = {v, -v, uint16_t(i % 2 ? 65535 : 1)};
  }
  for (uint16_t i = 0; i < s.knot_count; ++i) {
    const int64_t k = i < 4 ? INT32_MIN : int64_t(INT32_MIN) + int64_t(i - 3) * 65000000;
    s.knot[i] = i >= s.knot_count - 4 ? INT32_MAX : int32_t(k);
  }
  uint8_t value[proto::kMaxCompactPointBytes];
  EXPECT_EQ(proto::put_compact_point(s.control[0], s.control[1], true, value), 11);
  EXPECT_EQ(proto::put_compact_knot(0, INT32_MIN, true, false, value), 5);
  // A span of 2^31 or more does not fit a #K frame (the encoder sends #D for it).
  EXPECT_EQ(proto::put_compact_knot(-1, INT32_MAX, false, false, value), 0);
  EXPECT_EQ(proto::put_compact_knot(0, INT32_MAX, false, true, value), 5);
  test::expect_same_spline(s, store_compact(s));
  // The smallest payload a controller may announce (16 bytes: 12 of data) still carries it.
  test::expect_same_spline(s, store_compact(s, 12));
}

TEST(SplineCompact, SameSplineWalksToTheSamePointsFromBothEncodings) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 20; ++trial) {
    const uint8_t p = uint8_t(1 + trial % 3);
    core::Spline s = random_spline(&rng, uint16_t(p + 1 + rng() % 20), p, trial % 2 == 0, 3000);
    for (uint16_t i = 0; i < s.control_count; ++i) {
      s.control[i].x_um = s.control[i].x_um / 20;  // keep it on a small table
      s.control[i].y_um = s.control[i].y_um / 20;
      if (s.rational) s.control[i].weight_q14 = uint16_t(8192 + s.control[i].weight_q14 / 4);
    }
    const std::vector<core::PointUm> a = walk(store_full(s)), b = walk(store_compact(s));
    ASSERT_EQ(a.size(), b.size()) << trial;
    ASSERT_GT(a.size(), 1u);
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].x_um, b[i].x_um) << trial << " point " << i;
      EXPECT_EQ(a[i].y_um, b[i].y_um) << trial << " point " << i;
    }
  }
}

proto::ErrorCode decode_bytes(const std::vector<uint8_t>& payload) {
  proto::SplineCompactCmd m;
  return proto::decode(payload.data(), uint8_t(payload.size()), &m);
}

TEST(SplineCompact, CodecRefusesMalformedFrames) {
  // control_index, control_n, knot_index, knot_n, data...
  EXPECT_EQ(decode_bytes({0, 1, 0, 0, 0x02, 0x04}), proto::ErrorCode::kOk);       // (-1, +2)
  EXPECT_EQ(decode_bytes({0, 0, 0, 0, 0x00}), proto::ErrorCode::kFieldRange);     // nothing in it
  EXPECT_EQ(decode_bytes({0, 1, 0, 0}), proto::ErrorCode::kFieldRange);           // no data
  EXPECT_EQ(decode_bytes({0, 1, 0, 0, 0x02}), proto::ErrorCode::kPayloadLength);  // no y
  EXPECT_EQ(decode_bytes({0, 1, 0, 0, 0x82}), proto::ErrorCode::kPayloadLength);  // x cut
  EXPECT_EQ(decode_bytes({0, 1, 0, 0, 0x03, 0x04}),  // weight announced, missing
            proto::ErrorCode::kPayloadLength);
  EXPECT_EQ(decode_bytes({0, 1, 0, 0, 0x02, 0x04, 0x00}),  // a byte left over
            proto::ErrorCode::kPayloadLength);
  EXPECT_EQ(decode_bytes({0, 1, 0, 0, 0x82, 0x80, 0x80, 0x80, 0x10, 0x00}),  // x over 32 bits
            proto::ErrorCode::kFieldRange);
  EXPECT_EQ(decode_bytes({0, 1, 0, 0, 0x82, 0x80, 0x80, 0x80, 0x0F, 0x00}),  // 32 bits: fine
            proto::ErrorCode::kOk);
  EXPECT_EQ(decode_bytes({0, 0, 0, 1, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x01}),  // six bytes
            proto::ErrorCode::kFieldRange);
  // Knots 5 and 6: span 3 with the repeat flag stands for both; as the frame's last knot the
  // repeat is one too many.
  EXPECT_EQ(decode_bytes({0, 0, 5, 2, 0x07}), proto::ErrorCode::kOk);
  EXPECT_EQ(decode_bytes({0, 0, 5, 1, 0x07}), proto::ErrorCode::kPayloadLength);
  EXPECT_EQ(decode_bytes({0, 0, 5, 2, 0x06}), proto::ErrorCode::kPayloadLength);  // one knot
  // The spline's first knot has no repeat flag: 0x07 is knot -4, and 2 knots need 2 codes.
  EXPECT_EQ(decode_bytes({0, 0, 0, 2, 0x07}), proto::ErrorCode::kPayloadLength);
  EXPECT_EQ(decode_bytes({0, 0, 0, 2, 0x07, 0x00}), proto::ErrorCode::kOk);
  EXPECT_EQ(decode_bytes({64, 1, 0, 0, 0x02, 0x04}), proto::ErrorCode::kFieldRange);  // 65th
  EXPECT_EQ(decode_bytes({0, 0, 68, 1, 0x00}), proto::ErrorCode::kFieldRange);        // 69th
  EXPECT_EQ(decode_bytes({0, 31, 0, 0, 0x00}), proto::ErrorCode::kFieldRange);        // > 30 points
  std::vector<uint8_t> too_long(65, 0);
  too_long[3] = 61;
  EXPECT_EQ(decode_bytes(too_long), proto::ErrorCode::kPayloadLength);
  // Encoding checks the same.
  proto::SplineCompactCmd bad{};
  bad.control_n = 1;
  bad.data_n = 1;
  bad.data[0] = 0x02;
  proto::Payload p;
  EXPECT_EQ(proto::encode(bad, &p), proto::ErrorCode::kPayloadLength);
  EXPECT_EQ(p.length, 0);
}

// A store with a rational cubic of 8 points open and its first 3 points in.
struct OpenStore {
  app::SplineStore store;
  core::Spline s;
  uint8_t slot = 0, detail = 0;
  bool done = false;
  OpenStore() {
    std::mt19937 rng(3);
    s = random_spline(&rng, 8, 3, true, 5000);
    EXPECT_EQ(store.begin(header_of(s), &slot), proto::ErrorCode::kOk);
    proto::SplineCompactCmd first{};
    uint8_t value[proto::kMaxCompactPointBytes];
    for (int i = 0; i < 3; ++i) {
      core::ControlPoint prev = {0, 0, core::kWeightOneQ14};
      if (i > 0) prev = s.control[i - 1];
      const uint8_t n = proto::put_compact_point(prev, s.control[i], true, value);
      for (uint8_t b = 0; b < n; ++b) first.data[first.data_n++] = value[b];
      ++first.control_n;
    }
    EXPECT_EQ(store.add_compact(test::through_wire(first), kTravel, &detail, &done),
              proto::ErrorCode::kOk);
  }
  // The rest as #K frames: the spline then stores complete and exactly s.
  void finish() {
    proto::SplineCompactCmd d{};
    d.control_index = 3;
    uint8_t value[proto::kMaxCompactPointBytes];
    for (uint16_t i = 3; i < s.control_count; ++i) {
      const uint8_t n = proto::put_compact_point(s.control[i - 1], s.control[i], true, value);
      for (uint8_t b = 0; b < n; ++b) d.data[d.data_n++] = value[b];
      ++d.control_n;
    }
    ASSERT_EQ(store.add_compact(test::through_wire(d), kTravel, &detail, &done),
              proto::ErrorCode::kOk);
    proto::SplineCompactCmd k{};
    k.control_index = uint8_t(s.control_count);
    for (uint16_t i = 0; i < s.knot_count; ++i) {
      const uint8_t n =
          proto::put_compact_knot(i ? s.knot[i - 1] : 0, s.knot[i], i == 0, false, value);
      for (uint8_t b = 0; b < n; ++b) k.data[k.data_n++] = value[b];
      ++k.knot_n;
    }
    ASSERT_EQ(store.add_compact(test::through_wire(k), kTravel, &detail, &done),
              proto::ErrorCode::kOk);
    EXPECT_TRUE(done);
    test::expect_same_spline(s, *store.spline(slot));
  }
};

void append_varint(std::vector<uint8_t>* out, uint32_t v) {
  for (; v >= 0x80; v >>= 7) out->push_back(uint8_t((v & 0x7F) | 0x80));
  out->push_back(uint8_t(v));
}

// One point after point 2 written by hand: x varint (with the weight flag), y, weight.
proto::SplineCompactCmd one_point(std::vector<uint8_t> data) {
  proto::SplineCompactCmd d{};
  d.control_index = 3;
  d.control_n = 1;
  for (uint8_t b : data) d.data[d.data_n++] = b;
  return d;
}

TEST(SplineCompact, ValuesTheStoredPointsMakeInvalidAreRefusedAndChangeNothing) {
  {
    OpenStore o;  // weight 0: the previous weight minus itself
    const int32_t w = o.s.control[2].weight_q14;
    std::vector<uint8_t> data = {0x01, 0x00};   // x +0 with the weight flag, y +0
    append_varint(&data, uint32_t(2 * w - 1));  // zigzag(-w)
    EXPECT_EQ(o.store.add_compact(one_point(data), kTravel, &o.detail, &o.done),
              proto::ErrorCode::kFieldRange);
    o.finish();
  }
  {
    OpenStore o;  // x 2 m away from point 2: beyond +-1 m
    std::vector<uint8_t> data;
    append_varint(&data, o.s.control[2].x_um >= 0 ? 2u * 4000000u : 2u * 3999999u);
    data.push_back(0x00);
    EXPECT_EQ(o.store.add_compact(one_point(data), kTravel, &o.detail, &o.done),
              proto::ErrorCode::kFieldRange);
    o.finish();
  }
  {
    OpenStore o;  // outside a smaller travel
    const int32_t small[2] = {std::abs(o.s.control[2].x_um) + 5, 1000000};
    const uint32_t zx = o.s.control[2].x_um >= 0 ? 2u * 20u : 2u * 19u;  // 10 um further out
    EXPECT_EQ(o.store.add_compact(one_point({uint8_t(zx), 0x00}), small, &o.detail, &o.done),
              proto::ErrorCode::kOutOfTravel);
    o.finish();
  }
  {
    OpenStore o;  // wrong index
    proto::SplineCompactCmd d = one_point({0x02, 0x02});
    d.control_index = 4;
    EXPECT_EQ(o.store.add_compact(d, kTravel, &o.detail, &o.done),
              proto::ErrorCode::kSplineSequence);
    o.finish();
  }
}

TEST(SplineCompact, WeightInAPolynomialSplineIsRefused) {
  app::SplineStore store;
  core::Spline s{};
  s.degree = 1;
  s.control_count = 2;
  s.knot_count = 4;
  uint8_t slot = 0, detail = 0;
  bool done = false;
  ASSERT_EQ(store.begin(header_of(s), &slot), proto::ErrorCode::kOk);
  proto::SplineCompactCmd d{};
  d.control_n = 1;
  const uint8_t data[] = {0x03, 0x00, 0x02};  // x -1 with the weight flag, y 0, weight +1
  for (uint8_t b : data) d.data[d.data_n++] = b;
  EXPECT_EQ(store.add_compact(d, kTravel, &detail, &done), proto::ErrorCode::kFieldRange);
  d.data[0] = 0x02;  // the same without the weight
  d.data_n = 2;
  EXPECT_EQ(store.add_compact(d, kTravel, &detail, &done), proto::ErrorCode::kOk);
  EXPECT_EQ(store.spline(slot)->control[0].weight_q14, core::kWeightOneQ14);
}

TEST(SplineCompact, KnotBeyondInt32IsRefused) {
  core::Spline s{};
  s.degree = 1;
  s.control_count = 2;
  s.knot_count = 4;
  s.control[0] = {0, 0, core::kWeightOneQ14};
  s.control[1] = {1000, 0, core::kWeightOneQ14};
  app::SplineStore store;
  uint8_t slot = 0, detail = 0;
  bool done = false;
  ASSERT_EQ(store.begin(header_of(s), &slot), proto::ErrorCode::kOk);
  proto::SplineCompactCmd d{};
  d.control_n = 2;
  const uint8_t pts[] = {0x00, 0x00, 0xA0, 0x1F, 0x00};  // (0,0), then x +1000
  for (uint8_t b : pts) d.data[d.data_n++] = b;
  ASSERT_EQ(store.add_compact(d, kTravel, &detail, &done), proto::ErrorCode::kOk);
  proto::SplineCompactCmd k{};
  k.control_index = 2;
  k.knot_n = 2;
  // First knot 2^31 - 1 (zigzag 2^32 - 2), then a span of 1 (code 2): over int32.
  const uint8_t knots[] = {0xFE, 0xFF, 0xFF, 0xFF, 0x0F, 0x02};
  for (uint8_t b : knots) k.data[k.data_n++] = b;
  EXPECT_EQ(store.add_compact(k, kTravel, &detail, &done), proto::ErrorCode::kFieldRange);
  // The same with a span of 0 and a proper end is accepted (the first two knots were not kept).
  k.knot_n = 4;
  const uint8_t good[] = {0x00, 0x00, 0xD1, 0x0F};  // 0, +0, +1000 and repeated
  k.data_n = 0;
  for (uint8_t b : good) k.data[k.data_n++] = b;
  EXPECT_EQ(store.add_compact(k, kTravel, &detail, &done), proto::ErrorCode::kOk);
  EXPECT_TRUE(done);
  EXPECT_EQ(store.spline(slot)->knot[3], 1000);
}

}  // namespace
