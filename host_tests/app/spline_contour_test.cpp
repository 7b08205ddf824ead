// #Q contour frames through the codec and the spline store: lines and arcs become the
// rational quadratic the host planned (middle points, weights, knots made on the chip), arcs
// of every size stay on their circle, and malformed frames are refused leaving the store
// as it was.
#include <gtest/gtest.h>

#include <cmath>   // std::hypot, std::sqrt, std::cos, std::sin, std::llround
#include <random>  // std::mt19937
#include <vector>  // std::vector

#include "firmware/app/spline_store.h"
#include "firmware/core/spline.h"
#include "firmware/protocol/codec.h"
#include "firmware/protocol/contour_spline.h"
#include "host_tests/app/through_wire.h"
#include "host_tests/core/spline_equality.h"

namespace {

const int32_t kTravel[2] = {1000000, 1000000};

proto::SplineHeaderCmd contour_header(uint16_t elements) {
  proto::SplineHeaderCmd h{};
  h.degree = 2;
  h.rational = true;
  h.control_count = uint16_t(2 * elements + 1);
  h.knot_count = uint16_t(h.control_count + 3);
  h.feed_um_per_s = 5000;
  return h;
}

// #Q frames from the first point and the elements, each with at most `room` data bytes
// (every element in a frame of its own when room is 0).
std::vector<proto::SplineContourCmd> contour_frames(core::PointUm start,
                                                    const std::vector<proto::ContourElement>& els,
                                                    unsigned room = 62) {
  std::vector<proto::SplineContourCmd> out;
  proto::SplineContourCmd d{};
  d.control_n = 1;
  d.data_n = proto::put_contour_start(start.x_um, start.y_um, d.data);
  uint8_t value[proto::kMaxContourElementBytes];
  for (size_t i = 0; i < els.size(); ++i) {
    const uint8_t n = proto::put_contour_element(els[i], value);
    if (d.data_n + n > room && d.control_n > 1) {
      out.push_back(d);
      d = proto::SplineContourCmd{};
      d.control_index = uint8_t(1 + 2 * i);
    }
    for (uint8_t k = 0; k < n; ++k) d.data[d.data_n++] = value[k];
    d.control_n = uint8_t(d.control_n + 2);
  }
  out.push_back(d);
  return out;
}

// The spline the store holds after the frames (each must be accepted).
core::Spline store_contour(core::PointUm start, const std::vector<proto::ContourElement>& els,
                           unsigned room = 62) {
  app::SplineStore store;
  uint8_t slot = 0, detail = 0;
  bool done = false;
  EXPECT_EQ(store.begin(contour_header(uint16_t(els.size())), &slot), proto::ErrorCode::kOk);
  for (const proto::SplineContourCmd& d : contour_frames(start, els, room)) {
    EXPECT_FALSE(done);
    EXPECT_EQ(store.add_contour(test::through_wire(d), kTravel, &detail, &done),
              proto::ErrorCode::kOk);
  }
  EXPECT_TRUE(done);
  EXPECT_EQ(store.state(slot), app::SlotState::kReady);
  return *store.spline(slot);
}

// A point of the rational quadratic piece p0, m, p1 at t, um.
void piece_point(const core::ControlPoint& p0, const core::ControlPoint& m,
                 const core::ControlPoint& p1, double t, double* x, double* y) {
  const double b0 = (1 - t) * (1 - t) * p0.weight_q14, b1 = 2 * t * (1 - t) * m.weight_q14,
               b2 = t * t * p1.weight_q14;
  *x = (b0 * p0.x_um + b1 * m.x_um + b2 * p1.x_um) / (b0 + b1 + b2);
  *y = (b0 * p0.y_um + b1 * m.y_um + b2 * p1.y_um) / (b0 + b1 + b2);
}

TEST(SplineContour, TheProtocolDocumentsExampleIsAQuarterCircle) {
  // docs/protocol.md: from (10, 5) mm a line by (+10, 0), then an arc by (+5, +5), height
  // -3.536 mm: the quarter circle about (20, 10) mm.
  const core::Spline s =
      store_contour({10000, 5000}, {{10000, 0, false, 0}, {5000, 5000, true, -3536}});
  ASSERT_EQ(s.control_count, 5);
  const core::ControlPoint want[5] = {{10000, 5000, 16384},
                                      {15000, 5000, 16384},
                                      {20000, 5000, 16384},
                                      {25000, 5000, 11585},  // cos 45 degrees
                                      {25000, 10000, 16384}};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(s.control[i].x_um, want[i].x_um) << i;
    EXPECT_EQ(s.control[i].y_um, want[i].y_um) << i;
    EXPECT_EQ(s.control[i].weight_q14, want[i].weight_q14) << i;
  }
  const int32_t knots[8] = {0, 0, 0, 1, 1, 2, 2, 2};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(s.knot[i], knots[i]) << i;
  EXPECT_EQ(core::validate_spline(s), core::GeometryError::kOk);
  for (int i = 0; i <= 32; ++i) {
    double x = 0, y = 0;
    piece_point(s.control[2], s.control[3], s.control[4], i / 32.0, &x, &y);
    EXPECT_NEAR(std::hypot(x - 20000, y - 10000), 5000, 0.1) << i;
  }
}

TEST(SplineContour, ArcsOfEverySizeAndAngleStayOnTheirCircle) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 20000; ++trial) {
    SCOPED_TRACE(trial);
    const double r = 20 + u(rng) * 8000;  // 20 um .. 8 mm
    const double a0 = u(rng) * 6.2832;
    const double sweep = (u(rng) < 0.5 ? -1 : 1) * (0.02 + u(rng) * 1.55);  // up to 90 degrees
    const double cx = -500000 + u(rng) * 1000000, cy = -500000 + u(rng) * 1000000;
    const core::ControlPoint p0 = {int32_t(std::llround(cx + r * std::cos(a0))),
                                   int32_t(std::llround(cy + r * std::sin(a0))), 16384};
    const core::ControlPoint p1 = {int32_t(std::llround(cx + r * std::cos(a0 + sweep))),
                                   int32_t(std::llround(cy + r * std::sin(a0 + sweep))), 16384};
    // The ideal middle control point: on the bisector at r / cos(half sweep) from the centre.
    const double am = a0 + sweep / 2, rm = r / std::cos(sweep / 2);
    const double mx = cx + rm * std::cos(am) - p0.x_um, my = cy + rm * std::sin(am) - p0.y_um;
    const double dx = p1.x_um - p0.x_um, dy = p1.y_um - p0.y_um;
    const double chord = std::hypot(dx, dy);
    if (chord < 4) continue;  // a few micrometres of arc: a line
    const proto::ContourElement e = {int32_t(dx), int32_t(dy), true,
                                     int32_t(std::llround((dx * my - dy * mx) / chord))};
    core::ControlPoint m;
    ASSERT_EQ(proto::contour_middle(p0, e, &m), proto::ErrorCode::kOk);
    // The middle: half the chord (toward p0) plus the height along the normal, rounded.
    const double c_int = std::floor(std::sqrt(dx * dx + dy * dy));
    EXPECT_LE(std::fabs(m.x_um - (p0.x_um + e.dx_um / 2 - e.height_um * dy / c_int)), 0.5 + 1e-9);
    EXPECT_LE(std::fabs(m.y_um - (p0.y_um + e.dy_um / 2 + e.height_um * dx / c_int)), 0.5 + 1e-9);
    // The weight is the rounded exact cos(half angle) of the integer middle point.
    const double lx = m.x_um - p0.x_um, ly = m.y_um - p0.y_um;
    const double w = std::min(1.0, std::sqrt((dx * dx + dy * dy) / (4 * (lx * lx + ly * ly))));
    EXPECT_LE(std::fabs(m.weight_q14 - 16384 * w), 0.5 + 1e-9);
    // The curve: within a micrometre of the circle (its ends and middle are rounded).
    double worst = 0;
    for (int i = 0; i <= 16; ++i) {
      double x = 0, y = 0;
      piece_point(p0, m, p1, i / 16.0, &x, &y);
      worst = std::max(worst, std::fabs(std::hypot(x - cx, y - cy) - r));
    }
    EXPECT_LT(worst, 1.0);
  }
}

// A contour of n elements, lines and arcs by turns, winding across the board.
std::vector<proto::ContourElement> mixed_contour(std::mt19937* rng, int n) {
  std::vector<proto::ContourElement> els;
  for (int i = 0; i < n; ++i) {
    const int32_t dx = int32_t((*rng)() % 8001) - 4000, dy = int32_t((*rng)() % 8001) - 4000;
    const int32_t chord = int32_t(std::hypot(dx, dy));
    const bool arc = i % 2 == 1 && chord > 10;
    els.push_back({dx, dy, arc, arc ? int32_t((*rng)() % (chord + 1)) - chord / 2 : 0});
  }
  return els;
}

TEST(SplineContour, FramesCutAnywhereStoreTheSameSpline) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE(trial);
    const int n = 1 + int(rng() % 31);
    const std::vector<proto::ContourElement> els = mixed_contour(&rng, n);
    const core::Spline one = store_contour({1000, -2000}, els);
    test::expect_same_spline(one, store_contour({1000, -2000}, els, 0));   // one element a frame
    test::expect_same_spline(one, store_contour({1000, -2000}, els, 12));  // a 14-byte payload
    EXPECT_EQ(core::validate_spline(one), core::GeometryError::kOk);
    // Corners where the elements end; knots 0 0 0 1 1 .. n n n.
    int32_t x = 1000, y = -2000;
    for (int i = 0; i < n; ++i) {
      x += els[size_t(i)].dx_um;
      y += els[size_t(i)].dy_um;
      EXPECT_EQ(one.control[2 * i + 2].x_um, x);
      EXPECT_EQ(one.control[2 * i + 2].y_um, y);
      EXPECT_EQ(one.control[2 * i + 2].weight_q14, core::kWeightOneQ14);
    }
    for (int j = 0; j < one.knot_count; ++j)
      EXPECT_EQ(one.knot[j], j < 3 ? 0 : j + 3 >= one.knot_count ? n : (j - 1) / 2);
  }
}

TEST(SplineContour, MalformedFramesAreRefusedWithTheirCode) {
  proto::SplineContourCmd d{};
  d.control_n = 3;
  d.data_n = proto::put_contour_start(0, 0, d.data);
  const proto::ContourElement line = {100, 0, false, 0};
  d.data_n = uint8_t(d.data_n + proto::put_contour_element(line, d.data + d.data_n));
  // The payload as the wire carries it (the encoder would refuse the bad ones).
  auto decode = [](const proto::SplineContourCmd& m) {
    std::vector<uint8_t> bytes = {m.control_index, m.control_n};
    bytes.insert(bytes.end(), m.data, m.data + m.data_n);
    proto::SplineContourCmd back;
    return proto::decode(bytes.data(), uint8_t(bytes.size()), &back);
  };
  EXPECT_EQ(decode(d), proto::ErrorCode::kOk);
  proto::SplineContourCmd bad = d;
  bad.control_n = 2;  // the first frame carries the first point: an odd count
  EXPECT_EQ(decode(bad), proto::ErrorCode::kFieldRange);
  bad = d;
  bad.control_index = 2;  // a later frame starts at a corner: an odd index
  bad.control_n = 2;
  EXPECT_EQ(decode(bad), proto::ErrorCode::kFieldRange);
  bad = d;
  bad.control_n = 5;  // a second element announced, not sent
  EXPECT_EQ(decode(bad), proto::ErrorCode::kPayloadLength);
  bad = d;
  bad.data[bad.data_n++] = 0;  // a byte left over
  EXPECT_EQ(decode(bad), proto::ErrorCode::kPayloadLength);
  bad = d;
  bad.data_n = 0;
  for (int i = 0; i < 6; ++i) bad.data[bad.data_n++] = 0x80;  // a number over 32 bits
  bad.data[bad.data_n++] = 0;
  EXPECT_EQ(decode(bad), proto::ErrorCode::kFieldRange);

  core::ControlPoint m;
  const core::ControlPoint origin = {0, 0, 16384};
  const proto::ContourElement wide = {16384, 0, true, 100};
  EXPECT_EQ(proto::contour_middle(origin, wide, &m), proto::ErrorCode::kFieldRange);
  const proto::ContourElement high = {1000, 0, true, 1001};
  EXPECT_EQ(proto::contour_middle(origin, high, &m), proto::ErrorCode::kFieldRange);
  const proto::ContourElement empty = {0, 0, true, 0};
  EXPECT_EQ(proto::contour_middle(origin, empty, &m), proto::ErrorCode::kFieldRange);
  const proto::ContourElement widest = {16383, -16383, true, 23169};
  EXPECT_EQ(proto::contour_middle(origin, widest, &m), proto::ErrorCode::kOk);
}

TEST(SplineContour, TheStoreTakesContourFramesOnlyIntoAContourSplineAndARefusalKeepsNothing) {
  const std::vector<proto::ContourElement> els = {{2000, 0, false, 0}, {1000, 1000, true, -707}};
  const std::vector<proto::SplineContourCmd> frames = contour_frames({0, 0}, els, 0);
  ASSERT_EQ(frames.size(), 2u);
  uint8_t slot = 0, detail = 0;
  bool done = false;
  {
    // Not a contour spline: a cubic, or a quadratic whose counts are not whole elements.
    app::SplineStore store;
    proto::SplineHeaderCmd cubic = contour_header(2);
    cubic.degree = 3;
    cubic.knot_count = uint16_t(cubic.control_count + 4);
    ASSERT_EQ(store.begin(cubic, &slot), proto::ErrorCode::kOk);
    EXPECT_EQ(store.add_contour(frames[0], kTravel, &detail, &done),
              proto::ErrorCode::kSplineSequence);
  }
  {
    app::SplineStore store;
    proto::SplineHeaderCmd polynomial = contour_header(2);
    polynomial.rational = false;
    ASSERT_EQ(store.begin(polynomial, &slot), proto::ErrorCode::kOk);
    EXPECT_EQ(store.add_contour(frames[0], kTravel, &detail, &done),
              proto::ErrorCode::kSplineSequence);
  }
  app::SplineStore store;
  ASSERT_EQ(store.begin(contour_header(2), &slot), proto::ErrorCode::kOk);
  // The second frame first: not the next index.
  EXPECT_EQ(store.add_contour(frames[1], kTravel, &detail, &done),
            proto::ErrorCode::kSplineSequence);
  // Outside a 1.5 mm travel: refused, nothing stored.
  const int32_t small[2] = {1500, 1500};
  EXPECT_EQ(store.add_contour(frames[0], small, &detail, &done), proto::ErrorCode::kOutOfTravel);
  // An arc the controller cannot make: refused, nothing stored.
  proto::SplineContourCmd too_high = frames[1];
  too_high.data_n = proto::put_contour_element({1000, 1000, true, 1500}, too_high.data);
  EXPECT_EQ(store.add_contour(frames[0], kTravel, &detail, &done), proto::ErrorCode::kOk);
  EXPECT_FALSE(done);
  EXPECT_EQ(store.add_contour(too_high, kTravel, &detail, &done), proto::ErrorCode::kFieldRange);
  EXPECT_EQ(store.add_contour(frames[1], kTravel, &detail, &done), proto::ErrorCode::kOk);
  EXPECT_TRUE(done);
  EXPECT_EQ(store.state(slot), app::SlotState::kReady);
  test::expect_same_spline(*store.spline(slot), store_contour({0, 0}, els));
}

TEST(SplineContour, AContourFrameAfterAPointOfAnotherWeightIsRefused) {
  // A sender mixing #K and #Q: #Q elements start from a corner of weight 1.0 only.
  app::SplineStore store;
  uint8_t slot = 0, detail = 0;
  bool done = false;
  ASSERT_EQ(store.begin(contour_header(1), &slot), proto::ErrorCode::kOk);
  proto::SplineDataCmd first{};
  first.control_n = 1;
  first.control[0] = {0, 0, 8192};
  ASSERT_EQ(store.add(first, kTravel, &detail, &done), proto::ErrorCode::kOk);
  proto::SplineContourCmd rest{};
  rest.control_index = 1;
  rest.control_n = 2;
  rest.data_n = proto::put_contour_element({1000, 0, false, 0}, rest.data);
  EXPECT_EQ(store.add_contour(rest, kTravel, &detail, &done), proto::ErrorCode::kSplineSequence);
}

}  // namespace
