// On-target measurement of the application's 1 ms work: one path-controller tick (read
// position, vector to the target, isqrt, velocity out) and one planner push (background),
// driving a small integer model of the TMC428's velocity ramp; plus the RAM of the objects.
#include "firmware/app/application.h"      // Application (sizeof only)
#include "firmware/app/axis_scaling.h"     // AxisScaling, build_axis_scaling, um_to_usteps
#include "firmware/app/coordinate_ring.h"  // CoordinateRing
#include "firmware/app/dispatcher.h"       // Dispatcher (sizeof only)
#include "firmware/app/path_controller.h"  // PathController
#include "firmware/app/planner.h"          // Planner
#include "firmware/app/point_generator.h"  // PointGenerator (sizeof only)
#include "firmware/app/spline_store.h"     // SplineStore
#include "firmware/app/vector3.h"          // normalise3, length3 (tick parts)
#include "firmware/config/machine_config.h"
#include "firmware/core/height_map.h"          // HeightMap
#include "firmware/core/isqrt.h"               // isqrt32 (tick parts)
#include "firmware/protocol/codec.h"           // write_frame, decode_frame
#include "firmware/protocol/compact_spline.h"  // put_compact_point, put_compact_knot
#include "firmware/protocol/parser.h"          // Parser
#include "hal/interfaces/motion_axes.h"        // MotionAxes

#include "host_tests/target_proxy/proxy_check.h"
#include "host_tests/target_proxy/proxy_checks.h"

namespace proxy {

namespace {

// Velocity-mode axes in integer arithmetic: each ms the actual velocity ramps toward the
// commanded one by a fixed step and the position advances by the mean velocity.
class ProxyPlant : public hal::MotionAxes {
 public:
  enum { kUstepsPerSPerUnitQ16 = 2500000L, kMaxUnits = 2047, kAccelUnitsPerMs = 13 };

  ProxyPlant() {
    for (uint8_t i = 0; i < config::kAxisCount; ++i) {
      pos_q8_[i] = 0;
      v_actual_[i] = 0;
      v_target_[i] = 0;
    }
  }

  // Advances the model by one millisecond.
  void step_1ms() {
    for (uint8_t i = 0; i < config::kAxisCount; ++i) {
      int16_t v = v_actual_[i];
      const int16_t goal = v_target_[i];
      if (v < goal) v = (int16_t)(goal - v > kAccelUnitsPerMs ? v + kAccelUnitsPerMs : goal);
      if (v > goal) v = (int16_t)(v - goal > kAccelUnitsPerMs ? v - kAccelUnitsPerMs : goal);
      const int32_t mean = (int32_t)v + v_actual_[i];  // 2x mean velocity, units
      v_actual_[i] = v;
      // usteps per ms in Q8: mean/2 * (q16 / 1000) / 2^16 * 2^8.
      pos_q8_[i] += (mean * (kUstepsPerSPerUnitQ16 / 1000L)) >> 9;
    }
  }

  bool read_actual_usteps(int32_t out[config::kAxisCount]) {
    for (uint8_t i = 0; i < config::kAxisCount; ++i) out[i] = pos_q8_[i] >> 8;
    return true;
  }
  bool write_velocity_units(const int16_t v[config::kAxisCount]) {
    for (uint8_t i = 0; i < config::kAxisCount; ++i) {
      int16_t c = v[i];
      if (c > kMaxUnits) c = kMaxUnits;
      if (c < -kMaxUnits) c = -kMaxUnits;
      v_target_[i] = c;
    }
    return true;
  }
  bool read_velocity_units(int16_t out[config::kAxisCount]) {
    for (uint8_t i = 0; i < config::kAxisCount; ++i) out[i] = v_actual_[i];
    return true;
  }
  bool set_actual_usteps(const int32_t usteps[config::kAxisCount]) {
    for (uint8_t i = 0; i < config::kAxisCount; ++i) pos_q8_[i] = usteps[i] * 256L;
    return true;
  }
  bool read_limits(uint8_t* bits) {
    *bits = 0;
    return true;
  }
  uint32_t usteps_per_s_per_unit_q16(uint8_t) const { return kUstepsPerSPerUnitQ16; }
  int16_t max_velocity_units(uint8_t) const { return kMaxUnits; }
  uint16_t accel_units_per_ms(uint8_t) const { return kAccelUnitsPerMs; }

 private:
  int32_t pos_q8_[config::kAxisCount];
  int16_t v_actual_[config::kAxisCount];
  int16_t v_target_[config::kAxisCount];
};

// The path: a 10 mm square, then a 36-gon of radius 5 mm approximated by integer steps.
const uint8_t kPathPoints = 24;
const int32_t kPathUm[kPathPoints][2] = {
    {10000, 0},   {10000, 10000}, {0, 10000},   {0, 0},       {5000, 1000},  {8000, 2000},
    {9500, 4000}, {10000, 6000},  {9500, 8000}, {8000, 9500}, {6000, 10000}, {4000, 9500},
    {2000, 8000}, {1000, 6000},   {1500, 4000}, {3000, 2500}, {5000, 2000},  {7000, 2500},
    {8000, 4000}, {8000, 6000},   {7000, 7500}, {5000, 8000}, {3000, 7000},  {2500, 5000}};

ProxyPlant g_plant;
app::AxisScaling g_scaling;
app::Planner g_planner;
app::CoordinateRing g_ring;
app::PathController g_controller;

struct Series {
  uint32_t min;
  uint32_t max;
  uint32_t sum;
  uint16_t n;
};

void series_add(Series* s, uint32_t a, uint32_t b) {
  uint32_t c = b - a;
  c = c > cycles_overhead() ? c - cycles_overhead() : 0;
  if (c < s->min) s->min = c;
  if (c > s->max) s->max = c;
  s->sum += c;
  ++s->n;
}

void series_print(const char* name, const Series& s) {
  PROXY_PRINTF("measure ");
  PROXY_PRINT_STR(name);
  PROXY_PRINTF(": min %lu avg %lu max %lu %s (n = %u)\n", (unsigned long)s.min,
               (unsigned long)(s.n ? s.sum / s.n : 0), (unsigned long)s.max, counter_unit(),
               (unsigned)s.n);
}

core::HeightMap g_map;

// A 16 x 16 map, 1.4 mm apart from (-1, -1) mm over the measured path: a tilted blank
// (0.5 %, 0.3 %) with +-5 um of pseudo-random probe noise.
void build_map() {
  PROXY_CHECK(g_map.begin(16, 16, -1000, -1000, 1400, 1400));
  uint32_t state = 0x2545F491UL;
  for (uint16_t i = 0; i < 256; ++i) {
    const int16_t tilt = (int16_t)((i % 16U) * 7U) - (int16_t)((i / 16U) * 4U);
    PROXY_CHECK(g_map.set(i, (int16_t)(tilt + (int16_t)(next_random(&state) % 11U) - 5)));
  }
  g_map.complete();
}

// The measured path, cut into points at most 0.8 mm apart (a spline's points: none of them
// is split again for the map), at a cutting depth; every planner push timed, with or without
// the map, and HeightMap::offset_um alone at each point.
void measure_map_path(bool with_map, Series* push, Series* offset) {
  g_planner.init(g_scaling, app::default_planner_settings(10));
  g_planner.set_height_map(with_map ? &g_map : 0);
  g_controller.init(g_scaling);
  g_controller.flush(&g_ring);
  int32_t pos[3];
  g_plant.read_actual_usteps(pos);
  const int32_t at[3] = {0, 0, 0};
  g_plant.set_actual_usteps(at);
  g_planner.set_origin(at);
  uint8_t next = 0;
  uint8_t piece = 0;
  for (uint16_t ms = 0; ms < 30000; ++ms) {
    for (uint8_t k = 0; k < 2 && next < kPathPoints; ++k) {
      const int32_t* from = next == 0 ? at : kPathUm[next - 1];
      const int32_t* to = kPathUm[next];
      const int32_t dx = to[0] - from[0], dy = to[1] - from[1];
      const int32_t span =
          (dx < 0 ? -dx : dx) > (dy < 0 ? -dy : dy) ? (dx < 0 ? -dx : dx) : (dy < 0 ? -dy : dy);
      const uint8_t pieces = (uint8_t)((span + 799) / 800);
      const uint8_t k1 = (uint8_t)(piece + 1);
      const int32_t um[3] = {from[0] + dx * k1 / pieces, from[1] + dy * k1 / pieces, -100};
      const uint32_t a = cycles_now();
      const bool ok = g_planner.push(&g_ring, um, 10000, 0, 1);
      const uint32_t b = cycles_now();
      if (!ok) break;
      series_add(push, a, b);
      if (with_map) {
        const uint32_t c = cycles_now();
        const int16_t h = g_map.offset_um(um[0], um[1]);
        const uint32_t d = cycles_now();
        PROXY_CHECK(h >= g_map.lowest_um() && h <= g_map.highest_um());
        series_add(offset, c, d);
      }
      if (++piece == pieces) {
        piece = 0;
        ++next;
      }
    }
    g_plant.read_actual_usteps(pos);
    int16_t v[3];
    g_controller.tick(pos, &g_ring, v);
    g_plant.write_velocity_units(v);
    g_plant.step_1ms();
    if (next == kPathPoints && g_ring.empty() && g_controller.at_rest()) break;
  }
  PROXY_CHECK(next == kPathPoints);
}

void measure_height_map() {
  build_map();
  Series plain = {0xFFFFFFFFUL, 0, 0, 0};
  Series mapped = {0xFFFFFFFFUL, 0, 0, 0};
  Series offset = {0xFFFFFFFFUL, 0, 0, 0};
  measure_map_path(false, &plain, &offset);
  measure_map_path(true, &mapped, &offset);
  series_print(PROXY_STR("planner push, points <= 0.8 mm apart, no map"), plain);
  series_print(PROXY_STR("planner push, the same points, 16 x 16 height map on"), mapped);
  series_print(PROXY_STR("height map offset alone (HeightMap::offset_um)"), offset);
  PROXY_PRINTF("memory sizeof HeightMap %u bytes\n", (unsigned)sizeof(core::HeightMap));
}

app::SplineStore g_store;
proto::Parser g_parser(proto::kCommandStart);

// One full #D frame (6 control points) after its #B: parse byte by byte, decode, store.
void measure_spline_data_frame() {
  proto::SplineHeaderCmd header;
  header.degree = 3;
  header.rational = false;
  header.control_count = 6;
  header.knot_count = 10;
  header.feed_um_per_s = 10000;
  uint8_t slot = 0;
  PROXY_CHECK_EQ((int)g_store.begin(header, &slot), (int)proto::ErrorCode::kOk);

  proto::SplineDataCmd data;
  data.control_index = 0;
  data.control_n = proto::kMaxDataControls;
  data.knot_index = 0;
  data.knot_n = 0;
  for (uint8_t i = 0; i < data.control_n; ++i) {
    data.control[i].x_um = 10000L * i;
    data.control[i].y_um = (i & 1) ? 5000L : -5000L;
    data.control[i].weight_q14 = core::kWeightOneQ14;
  }
  static uint8_t bytes[80];
  uint8_t size = 0;
  PROXY_CHECK_EQ((int)proto::write_frame(data, 7, bytes, sizeof(bytes), &size),
                 (int)proto::ErrorCode::kOk);

  const int32_t travel_um[2] = {300000L, 210000L};
  const uint32_t a = cycles_now();
  bool framed = false;
  for (uint8_t i = 0; i < size; ++i) {
    if (g_parser.feed(bytes[i]) == proto::ParseEvent::kFrame) framed = true;
  }
  const uint32_t b = cycles_now();
  static proto::SplineDataCmd decoded;
  const proto::ErrorCode decode_error = proto::decode_frame(g_parser.frame(), &decoded);
  const uint32_t c = cycles_now();
  uint8_t detail = 0;
  bool completed = false;
  const proto::ErrorCode store_error = g_store.add(decoded, travel_um, &detail, &completed);
  const uint32_t d = cycles_now();
  PROXY_CHECK(framed);
  PROXY_CHECK_EQ((int)decode_error, (int)proto::ErrorCode::kOk);
  PROXY_CHECK_EQ((int)store_error, (int)proto::ErrorCode::kOk);
  const uint32_t overhead = cycles_overhead();
  PROXY_PRINTF(
      "measure #D frame (%u bytes, 6 control points): parse+CRC %lu, decode %lu, "
      "store %lu %s\n",
      (unsigned)size, (unsigned long)(b - a - overhead), (unsigned long)(c - b - overhead),
      (unsigned long)(d - c - overhead), counter_unit());
}

// A rational quadratic with far-apart points, weight jumps and wide knot spans as #K frames
// written, parsed, decoded and stored here (16-bit int: the varint and zigzag arithmetic
// on the target); the store must hold exactly the values sent.
void check_compact_spline_frames() {
  static const core::ControlPoint kPoints[7] = {
      {-1000000L, 1000000L, 1},  {1000000L, -1000000L, 65535U},
      {12345L, -678L, 65535U},   {12346L, -679L, 40000U},
      {-5L, 7L, 40000U},         {300000L, 200000L, 16384U},
      {300001L, 200000L, 16383U}};
  static const int32_t kKnots[10] = {-5L,    -5L,         -5L,         0L,          0L,
                                     70000L, 2000000000L, 2000000000L, 2000000000L, 2000000000L};
  proto::SplineHeaderCmd header;
  header.degree = 2;
  header.rational = true;
  header.control_count = 7;
  header.knot_count = 10;
  header.feed_um_per_s = 10000;
  header.tool_offset_um = 0;
  uint8_t slot = 0;
  PROXY_CHECK_EQ((int)g_store.begin(header, &slot), (int)proto::ErrorCode::kOk);
  const int32_t travel_um[2] = {1000000L, 1000000L};
  // Two frames: the points, then the knots (repeats folded into the code before them).
  static proto::SplineCompactCmd frame;
  static proto::SplineCompactCmd decoded;
  static uint8_t bytes[80];
  bool completed = false;
  for (uint8_t part = 0; part < 2; ++part) {
    frame.control_index = part == 0 ? 0 : 7;
    frame.control_n = 0;
    frame.knot_index = 0;
    frame.knot_n = 0;
    frame.data_n = 0;
    if (part == 0) {
      core::ControlPoint prev = {0, 0, core::kWeightOneQ14};
      for (uint8_t i = 0; i < 7; ++i) {
        frame.data_n =
            (uint8_t)(frame.data_n +
                      proto::put_compact_point(prev, kPoints[i], true, frame.data + frame.data_n));
        prev = kPoints[i];
        ++frame.control_n;
      }
    } else {
      for (uint8_t i = 0; i < 10;) {
        const bool repeat = i > 0 && i + 1 < 10 && kKnots[i + 1] == kKnots[i];
        frame.data_n = (uint8_t)(frame.data_n + proto::put_compact_knot(i ? kKnots[i - 1] : 0,
                                                                        kKnots[i], i == 0, repeat,
                                                                        frame.data + frame.data_n));
        const uint8_t n = repeat ? 2 : 1;
        frame.knot_n = (uint8_t)(frame.knot_n + n);
        i = (uint8_t)(i + n);
      }
    }
    uint8_t size = 0;
    PROXY_CHECK_EQ((int)proto::write_frame(frame, (uint8_t)(8 + part), bytes, sizeof(bytes), &size),
                   (int)proto::ErrorCode::kOk);
    bool framed = false;
    for (uint8_t i = 0; i < size; ++i) {
      if (g_parser.feed(bytes[i]) == proto::ParseEvent::kFrame) framed = true;
    }
    PROXY_CHECK(framed);
    PROXY_CHECK_EQ((int)proto::decode_frame(g_parser.frame(), &decoded),
                   (int)proto::ErrorCode::kOk);
    uint8_t detail = 0;
    PROXY_CHECK_EQ((int)g_store.add_compact(decoded, travel_um, &detail, &completed),
                   (int)proto::ErrorCode::kOk);
  }
  PROXY_CHECK(completed);
  PROXY_CHECK_EQ((int)g_store.state(slot), (int)app::SlotState::kReady);
  const core::Spline* s = g_store.spline(slot);
  for (uint8_t i = 0; i < 7; ++i) {
    PROXY_CHECK_EQ(s->control[i].x_um, kPoints[i].x_um);
    PROXY_CHECK_EQ(s->control[i].y_um, kPoints[i].y_um);
    PROXY_CHECK_EQ(s->control[i].weight_q14, kPoints[i].weight_q14);
  }
  for (uint8_t i = 0; i < 10; ++i) PROXY_CHECK_EQ(s->knot[i], kKnots[i]);
  g_store.release(slot);
}

// The tick's parts, each on inputs of the measured path (1 mm segments, 2560 usteps/mm):
// where its cycles go, for the dsPIC translation in docs/performance.md.
volatile int32_t g_part_sink;
volatile int32_t g_part_in[4];  // inputs pass through here so no % lands in a timed span

void measure_tick_parts() {
  Series norm = {0xFFFFFFFFUL, 0, 0, 0};
  Series len = {0xFFFFFFFFUL, 0, 0, 0};
  Series conv = {0xFFFFFFFFUL, 0, 0, 0};
  Series reach = {0xFFFFFFFFUL, 0, 0, 0};
  Series root = {0xFFFFFFFFUL, 0, 0, 0};
  uint32_t state = 0x2545F491UL;
  for (uint8_t k = 0; k < 32; ++k) {
    const uint32_t r = next_random(&state);
    g_part_in[0] = (int32_t)(r % 5121U) - 2560;
    g_part_in[1] = (int32_t)((r >> 13) % 5121U) - 2560;
    g_part_in[2] = (int32_t)(r % 600001UL) - 300000L;
    g_part_in[3] = (int32_t)(r % 2000U);
    const int32_t d[3] = {g_part_in[0], g_part_in[1], 0};
    const int32_t um = g_part_in[2];
    const uint32_t length_um = (uint32_t)g_part_in[3];
    const uint16_t exit_um_s = (uint16_t)(length_um * 5U);
    int16_t n[3];
    int8_t shift = 0;
    uint32_t a = cycles_now();
    app::normalise3(d, n, &shift);
    uint32_t b = cycles_now();
    series_add(&norm, a, b);
    a = cycles_now();
    const uint16_t l = app::length3(n);
    b = cycles_now();
    series_add(&len, a, b);
    const uint32_t sum_sq = app::sum_squares3(n);
    a = cycles_now();
    const uint16_t l1 = core::isqrt32(sum_sq);
    b = cycles_now();
    series_add(&root, a, b);
    PROXY_CHECK_EQ(l1, l);
    a = cycles_now();
    const int32_t us = app::um_to_usteps(g_scaling, 0, um);
    b = cycles_now();
    series_add(&conv, a, b);
    a = cycles_now();
    const uint16_t v = app::reach_speed_capped_um_s(exit_um_s, 300, length_um, 10000);
    b = cycles_now();
    series_add(&reach, a, b);
    g_part_sink = l + us + v + shift;
  }
  series_print(PROXY_STR("tick part normalise3"), norm);
  series_print(PROXY_STR("tick part length3 (isqrt32)"), len);
  series_print(PROXY_STR("tick part isqrt32 alone"), root);
  series_print(PROXY_STR("tick part um_to_usteps (per axis, on taking a target)"), conv);
  series_print(PROXY_STR("tick part reach_speed_capped_um_s"), reach);
}

}  // namespace

void run_app_measurements() {
  begin_group(PROXY_STR("app_path_tick"));
  const config::MachineConfig cfg = config::default_machine_config();
  PROXY_CHECK(app::build_axis_scaling(cfg, g_plant, &g_scaling));
  g_planner.init(g_scaling, app::default_planner_settings(cfg.capture_radius_um));
  g_controller.init(g_scaling);
  const int32_t origin[3] = {0, 0, 0};
  g_planner.set_origin(origin);

  Series tick = {0xFFFFFFFFUL, 0, 0, 0};
  Series push = {0xFFFFFFFFUL, 0, 0, 0};
  uint8_t next = 0;
  uint16_t ms = 0;
  const uint16_t kMaxMs = 20000;
  for (; ms < kMaxMs; ++ms) {
    // Background loop: up to 2 points per ms, like the point generator.
    for (uint8_t k = 0; k < 2 && next < kPathPoints; ++k) {
      const int32_t um[3] = {kPathUm[next][0], kPathUm[next][1], 0};
      const uint8_t flags = next + 1 == kPathPoints ? (uint8_t)app::kPointEndOfItem : 0;
      const uint32_t a = cycles_now();
      const bool ok = g_planner.push(&g_ring, um, 10000, flags, 1);
      const uint32_t b = cycles_now();
      if (!ok) break;
      series_add(&push, a, b);
      ++next;
    }
    // The 1 ms interrupt.
    int32_t pos[3];
    g_plant.read_actual_usteps(pos);
    int16_t v[3];
    const uint32_t a = cycles_now();
    g_controller.tick(pos, &g_ring, v);
    const uint32_t b = cycles_now();
    series_add(&tick, a, b);
    g_plant.write_velocity_units(v);
    g_plant.step_1ms();
    if (next == kPathPoints && g_controller.finished() && g_controller.at_rest()) break;
  }
  PROXY_CHECK(ms < kMaxMs);  // the path was completed
  int32_t pos[3];
  g_plant.read_actual_usteps(pos);
  const int32_t want_x = app::um_to_usteps(g_scaling, 0, kPathUm[kPathPoints - 1][0]);
  const int32_t want_y = app::um_to_usteps(g_scaling, 1, kPathUm[kPathPoints - 1][1]);
  // Ends within 0.1 mm of the last point (the host tests check the real tolerances).
  PROXY_CHECK_NEAR(pos[0], want_x, app::um_to_usteps(g_scaling, 0, 100));
  PROXY_CHECK_NEAR(pos[1], want_y, app::um_to_usteps(g_scaling, 1, 100));
  PROXY_PRINTF("measure path run: %u ms for %u points at 10 mm/s\n", (unsigned)ms,
               (unsigned)kPathPoints);
  series_print(PROXY_STR("path controller tick (PathController::tick)"), tick);
  series_print(PROXY_STR("planner push of one point (background)"), push);
  measure_tick_parts();
  measure_height_map();
  measure_spline_data_frame();
  check_compact_spline_frames();
  PROXY_PRINTF(
      "memory sizeof CoordinateRing %u, PathController %u, Planner %u, AxisScaling %u bytes\n",
      (unsigned)sizeof(app::CoordinateRing), (unsigned)sizeof(app::PathController),
      (unsigned)sizeof(app::Planner), (unsigned)sizeof(app::AxisScaling));
  PROXY_PRINTF(
      "memory sizeof SplineStore %u, PointGenerator %u, Dispatcher %u, "
      "Parser %u, Application (all of it) %u bytes\n",
      (unsigned)sizeof(app::SplineStore), (unsigned)sizeof(app::PointGenerator),
      (unsigned)sizeof(app::Dispatcher), (unsigned)sizeof(proto::Parser),
      (unsigned)sizeof(app::Application));
  end_group();
}

}  // namespace proxy
