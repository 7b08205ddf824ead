// The job encoder: each plan step becomes the right frame; splines are packed into #D
// frames that the controller's codec decodes back to exactly the same spline.
#include <gtest/gtest.h>

#include "firmware/protocol/codec.h"
#include "firmware/protocol/contour_spline.h"
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/spline_frames.h"
#include "host_tests/core/spline_equality.h"

namespace host {
namespace {

// A clamped cubic with n control points on a wavy line, optionally rational.
core::Spline wavy_spline(int n, bool rational) {
  core::Spline s{};
  s.degree = 3;
  s.rational = rational;
  s.control_count = static_cast<uint16_t>(n);
  s.knot_count = static_cast<uint16_t>(n + 4);
  for (int i = 0; i < n; ++i) {
    s.control[i].x_um = 1000 * i;
    s.control[i].y_um = (i % 2) ? 2500 : -1500;
    s.control[i].weight_q14 =
        rational ? static_cast<uint16_t>(8000 + 300 * i) : core::kWeightOneQ14;
  }
  for (int k = 0; k < n + 4; ++k) {
    s.knot[k] = k < 4 ? 0 : (k >= n ? (n - 3) * 100 : (k - 3) * 100);
  }
  return s;
}

JobPlan plan_with_spline(const core::Spline& spline) {
  JobPlan plan;
  PlanStep up;
  up.kind = PlanStep::kPenUp;
  up.z_um = 2000;
  PlanStep rapid;
  rapid.kind = PlanStep::kRapid;
  rapid.to = {spline.control[0].x_um, spline.control[0].y_um};
  PlanStep down;
  down.kind = PlanStep::kPenDown;
  down.z_um = -100;
  down.feed_um_per_s = 2000;
  PlanStep curve;
  curve.kind = PlanStep::kSpline;
  curve.set_spline(StepSpline(spline));
  curve.to = {spline.control[spline.control_count - 1].x_um,
              spline.control[spline.control_count - 1].y_um};
  curve.feed_um_per_s = 10000;
  curve.curve = 0;
  PlanStep line;
  line.kind = PlanStep::kFeed;
  line.to = {0, 0};
  line.feed_um_per_s = 10000;
  plan.steps = {up, rapid, down, curve, line, up};
  return plan;
}

// Rebuilds the spline from the encoded #B/#D/#K commands as the controller's store would.
core::Spline reassemble(const std::vector<QueuedCommand>& cmds) {
  core::Spline s{};
  for (const QueuedCommand& c : cmds) {
    if (c.letter == proto::kCmdSplineHeader) {
      proto::SplineHeaderCmd h;
      EXPECT_EQ(proto::decode(c.payload.data(), static_cast<uint8_t>(c.payload.size()), &h),
                proto::ErrorCode::kOk);
      s.degree = h.degree;
      s.rational = h.rational;
      s.control_count = h.control_count;
      s.knot_count = h.knot_count;
    } else if (is_spline_data(c.letter)) {
      EXPECT_TRUE(add_spline_data(c, &s));
    }
  }
  return s;
}

TEST(JobEncoder, StepsMapToTheirCommandLetters) {
  const auto cmds = encode_job(plan_with_spline(wavy_spline(4, false)), EncodeOptions{});
  std::string letters;
  for (const auto& c : cmds) letters += static_cast<char>(c.letter);
  // #J (job numbering) and #U first, then Z up, F rapid, Z down, B + D..., G, Z up.
  EXPECT_EQ(letters.substr(0, 5), "JUZFZ");
  EXPECT_EQ(letters.substr(5, 1), "B");
  EXPECT_EQ(letters.substr(letters.size() - 2), "GZ");
}

TEST(JobEncoder, TitleBecomesLcdRowZero) {
  EncodeOptions o;
  o.title = "a title longer than sixteen";
  const auto cmds = encode_job(plan_with_spline(wavy_spline(4, false)), o);
  ASSERT_EQ(cmds[0].letter, proto::kCmdJobMark);
  ASSERT_EQ(cmds[1].letter, proto::kCmdText);
  proto::TextCmd t;
  ASSERT_EQ(proto::decode(cmds[1].payload.data(), static_cast<uint8_t>(cmds[1].payload.size()), &t),
            proto::ErrorCode::kOk);
  EXPECT_EQ(t.row, 0);
  EXPECT_EQ(std::string(t.text, t.length), "a title longer t");
}

TEST(JobEncoder, SplineSurvivesPackingAtFullPayload) {
  const core::Spline spline = wavy_spline(40, true);
  const auto cmds = encode_job(plan_with_spline(spline), EncodeOptions{});
  test::expect_same_spline(spline, reassemble(cmds));
}

TEST(JobEncoder, SplineSurvivesPackingAtASmallPayload) {
  for (bool compact : {true, false}) {
    for (bool rational : {true, false}) {
      const core::Spline spline = wavy_spline(core::kMaxControlPoints, rational);
      EncodeOptions o;
      o.max_payload = 16;
      o.splines = compact ? SplineFrames::kCompact : SplineFrames::kFixed;
      const auto cmds = encode_job(plan_with_spline(spline), o);
      for (const auto& c : cmds) EXPECT_LE(c.payload.size(), 16u);
      test::expect_same_spline(spline, reassemble(cmds));
    }
  }
}

TEST(JobEncoder, SplineDataFramesAreKnownAndAMalformedOneIsNotAdded) {
  EXPECT_TRUE(is_spline_data(proto::kCmdSplineData));
  EXPECT_TRUE(is_spline_data(proto::kCmdSplineCompact));
  EXPECT_FALSE(is_spline_data(proto::kCmdSplineHeader));
  EXPECT_FALSE(is_spline_data(proto::kCmdFeedMove));
  core::Spline s{};
  s.degree = 1;
  s.control_count = 2;
  s.knot_count = 4;
  QueuedCommand c;
  c.letter = proto::kCmdSplineCompact;
  c.payload = {0, 1, 0, 0, 0x02};  // y of the point missing
  EXPECT_FALSE(add_spline_data(c, &s));
  c.payload = {0, 1, 0, 0, 0x02, 0x04};
  EXPECT_TRUE(add_spline_data(c, &s));
  EXPECT_EQ(s.control[0].x_um, -1);
  EXPECT_EQ(s.control[0].y_um, 2);
  c.letter = proto::kCmdFeedMove;
  EXPECT_FALSE(add_spline_data(c, &s));
}

TEST(JobEncoder, KnotSpanTooWideForACompactFrameGoesInAFullFrame) {
  core::Spline spline = wavy_spline(6, true);
  for (int k = 0; k < spline.knot_count; ++k) spline.knot[k] = k < 5 ? INT32_MIN : INT32_MAX;
  spline.knot[4] = -5;  // spans: 0 0 0 2^31-5 (fits), 2^31+4 (does not), 0 0 0 0
  const auto cmds = encode_job(plan_with_spline(spline), EncodeOptions{});
  int k_frames = 0, d_frames = 0;
  for (const auto& c : cmds) {
    k_frames += c.letter == proto::kCmdSplineCompact;
    d_frames += c.letter == proto::kCmdSplineData;
  }
  EXPECT_GE(k_frames, 1);
  EXPECT_EQ(d_frames, 1);
  test::expect_same_spline(spline, reassemble(cmds));
}

TEST(JobEncoder, StepSplineDataIsTheSameSplineInFewerBytes) {
  for (bool rational : {true, false}) {
    const core::Spline spline = wavy_spline(core::kMaxControlPoints, rational);
    EncodeOptions full;
    full.splines = SplineFrames::kFixed;
    const auto k = encode_job(plan_with_spline(spline), EncodeOptions{});
    const auto d = encode_job(plan_with_spline(spline), full);
    int k_frames = 0, d_frames = 0;
    size_t k_bytes = 0, d_bytes = 0;
    for (const auto& c : k) {
      if (c.letter == proto::kCmdSplineCompact) ++k_frames, k_bytes += frame_bytes(c);
    }
    for (const auto& c : d) {
      if (c.letter == proto::kCmdSplineData) ++d_frames, d_bytes += frame_bytes(c);
    }
    EXPECT_GT(k_frames, 0);
    EXPECT_GT(d_frames, 0);
    for (const auto& c : k) EXPECT_NE(c.letter, proto::kCmdSplineData);
    test::expect_same_spline(reassemble(d), reassemble(k));
    // Points 1 and 4 mm apart: x, y and a weight change two bytes each instead of 4, 4 and 2;
    // knot spans of 100 one byte instead of 4.
    EXPECT_LT(k_bytes * 10, d_bytes * (rational ? 6 : 5)) << rational;
  }
}

TEST(JobEncoder, SplineFramesCarryTheirCurveIndex) {
  const auto cmds = encode_job(plan_with_spline(wavy_spline(12, false)), EncodeOptions{});
  for (const auto& c : cmds) {
    if (c.letter == proto::kCmdSplineHeader || c.letter == proto::kCmdSplineData ||
        c.letter == proto::kCmdSplineCompact) {
      EXPECT_EQ(c.curve, 0);
      EXPECT_EQ(c.step, 3);
    }
  }
}

TEST(JobEncoder, FeedBeyondTheWireRangeIsRefused) {
  JobPlan plan = plan_with_spline(wavy_spline(4, false));
  plan.steps.edit(4, [](PlanStep& s) { s.feed_um_per_s = 70000; });
  EXPECT_THROW(encode_job(plan, EncodeOptions{}), PlanError);
}

TEST(JobEncoder, ToolOffsetTravelsInTheSplineHeader) {
  JobPlan plan = plan_with_spline(wavy_spline(4, false));
  plan.steps.edit(3, [](PlanStep& s) { s.tool_offset_um = -250; });
  const auto cmds = encode_job(plan, EncodeOptions{});
  int headers = 0;
  for (const auto& c : cmds) {
    if (c.letter != proto::kCmdSplineHeader) continue;
    proto::SplineHeaderCmd h;
    ASSERT_EQ(proto::decode(c.payload.data(), static_cast<uint8_t>(c.payload.size()), &h),
              proto::ErrorCode::kOk);
    EXPECT_EQ(h.tool_offset_um, -250);
    ++headers;
  }
  EXPECT_EQ(headers, 1);
  plan.steps.edit(
      3, [](PlanStep& s) { s.tool_offset_um = 100001; });  // beyond what the controller offsets
  EXPECT_THROW(encode_job(plan, EncodeOptions{}), PlanError);
}

TEST(JobEncoder, StraightFeedWithAnOffsetBecomesADegreeOneSplineFromTheToolPosition) {
  JobPlan plan = plan_with_spline(wavy_spline(4, false));
  plan.steps.edit(4, [](PlanStep& s) {
    s.tool_offset_um = 300;
  });  // the line back to (0, 0) from the spline's end
  const auto cmds = encode_job(plan, EncodeOptions{});
  std::vector<QueuedCommand> line;
  for (const auto& c : cmds) {
    if (c.step == 4) line.push_back(c);
  }
  const core::Spline s = reassemble(line);
  ASSERT_EQ(line.front().letter, proto::kCmdSplineHeader);
  EXPECT_EQ(s.degree, 1);
  ASSERT_EQ(s.control_count, 2);
  EXPECT_EQ(s.control[0].x_um, 3000);  // where the curve before it ended
  EXPECT_EQ(s.control[0].y_um, 2500);
  EXPECT_EQ(s.control[1].x_um, 0);
  EXPECT_EQ(s.control[1].y_um, 0);
}

// Decodes one encoded command as Msg (its letter must match).
template <typename Msg>
Msg decoded(const QueuedCommand& c) {
  EXPECT_EQ(c.letter, static_cast<uint8_t>(Msg::kLetter));
  Msg m{};
  EXPECT_EQ(proto::decode(c.payload.data(), static_cast<uint8_t>(c.payload.size()), &m),
            proto::ErrorCode::kOk);
  return m;
}

// Pause, dwell, spindle and drill steps after the #J and #U set-up frames.
std::vector<QueuedCommand> encode_machine_steps(const std::vector<PlanStep>& steps) {
  JobPlan plan;
  plan.steps = steps;
  auto cmds = encode_job(plan, EncodeOptions{});
  EXPECT_EQ(cmds.front().letter, proto::kCmdJobMark);
  cmds.erase(cmds.begin());
  EXPECT_EQ(cmds.front().letter, proto::kCmdResolution);
  cmds.erase(cmds.begin());
  return cmds;
}

TEST(JobEncoder, PauseCarriesItsTextCutToTheLcdRow) {
  PlanStep pause;
  pause.kind = PlanStep::kPause;
  pause.set_text("Tool\tchange: 0.8 mm drill");  // a tab is not printable on the LCD
  const auto cmds = encode_machine_steps({pause});
  ASSERT_EQ(cmds.size(), 1u);
  const auto p = decoded<proto::PauseCmd>(cmds[0]);
  EXPECT_EQ(std::string(p.text, p.length), "Tool?change: 0.8");
  EXPECT_EQ(cmds[0].step, 0);
}

TEST(JobEncoder, DwellLongerThanOneFrameIsSplitAndAddsUp) {
  PlanStep dwell;
  dwell.kind = PlanStep::kDwell;
  dwell.dwell_ms = 150000;
  const auto cmds = encode_machine_steps({dwell});
  ASSERT_EQ(cmds.size(), 3u);
  uint32_t total = 0;
  for (const auto& c : cmds) total += decoded<proto::DwellCmd>(c).dwell_ms;
  EXPECT_EQ(total, 150000u);
}

TEST(JobEncoder, SpindleOnAndOff) {
  PlanStep on;
  on.kind = PlanStep::kSpindle;
  on.spindle_on = true;
  PlanStep off = on;
  off.spindle_on = false;
  const auto cmds = encode_machine_steps({on, off});
  ASSERT_EQ(cmds.size(), 2u);
  EXPECT_EQ(decoded<proto::SpindleCmd>(cmds[0]).on, 1);
  EXPECT_EQ(decoded<proto::SpindleCmd>(cmds[1]).on, 0);
}

TEST(JobEncoder, DrillIsOneFrameWithEveryField) {
  PlanStep drill;
  drill.kind = PlanStep::kDrill;
  drill.to = {12000, 34000};
  drill.z_start_um = 1000;
  drill.z_um = -1800;
  drill.feed_um_per_s = 700;
  const auto cmds = encode_machine_steps({drill});
  ASSERT_EQ(cmds.size(), 1u);
  const auto d = decoded<proto::DrillCmd>(cmds[0]);
  EXPECT_EQ(d.x_um, 12000);
  EXPECT_EQ(d.y_um, 34000);
  EXPECT_EQ(d.z_start_um, 1000);
  EXPECT_EQ(d.z_bottom_um, -1800);
  EXPECT_EQ(d.feed_um_per_s, 700);
}

TEST(JobEncoder, DrillWhoseBottomIsNotBelowItsStartIsRefused) {
  PlanStep drill;
  drill.kind = PlanStep::kDrill;
  drill.z_start_um = 1000;
  drill.z_um = 1000;
  drill.feed_um_per_s = 700;
  EXPECT_THROW(encode_machine_steps({drill}), PlanError);
}

TEST(JobEncoder, JobLeavingTheControllersTravelIsRefusedNamingTheStep) {
  proto::SessionReply small{};
  small.travel_x_um = 30000;
  small.travel_y_um = 30000;
  small.travel_z_um = 5000;
  EncodeOptions o;
  o.controller = &small;
  JobPlan plan = plan_with_spline(wavy_spline(4, false));  // x up to 3 mm: fits
  EXPECT_NO_THROW(encode_job(plan, o));
  plan.steps.edit(1, [](PlanStep& s) { s.to.x_um = 30001; });  // the rapid
  try {
    encode_job(plan, o);
    FAIL() << "no PlanError";
  } catch (const PlanError& e) {
    EXPECT_NE(std::string(e.what()).find("step 1: X 30.001 mm"), std::string::npos) << e.what();
  }
  plan = plan_with_spline(wavy_spline(40, false));  // control points up to X 39 mm
  EXPECT_THROW(encode_job(plan, o), PlanError);
  plan = plan_with_spline(wavy_spline(4, false));
  plan.steps.edit(2, [](PlanStep& s) { s.z_um = -5001; });  // pen down too deep
  EXPECT_THROW(encode_job(plan, o), PlanError);
  o.controller = nullptr;
  EXPECT_NO_THROW(encode_job(plan, o));
}

// A contour of n elements (lines and quarter arcs by turns) as the controller holds it after
// #Q frames: corners of weight 1.0, the middles contour_middle makes, knots 0 0 0 .. n n n.
core::Spline contour_spline(int n) {
  core::Spline s{};
  s.degree = 2;
  s.rational = true;
  s.control_count = static_cast<uint16_t>(2 * n + 1);
  s.knot_count = static_cast<uint16_t>(2 * n + 4);
  s.control[0] = {1000, 1000, core::kWeightOneQ14};
  for (int i = 0; i < n; ++i) {
    const proto::ContourElement e = i % 2 ? proto::ContourElement{3000, 3000, true, -2121}
                                          : proto::ContourElement{5000, 0, false, 0};
    const core::ControlPoint& p0 = s.control[2 * i];
    proto::contour_middle(p0, e, &s.control[2 * i + 1]);
    s.control[2 * i + 2] = {p0.x_um + e.dx_um, p0.y_um + e.dy_um, core::kWeightOneQ14};
  }
  for (int j = 0; j < s.knot_count; ++j)
    s.knot[j] = j < 3 ? 0 : j + 3 >= s.knot_count ? n : (j - 1) / 2;
  return s;
}

TEST(JobEncoder, ALinesAndArcsSplineGoesAsContourFramesInFewerBytes) {
  const core::Spline spline = contour_spline(31);
  for (unsigned payload : {64u, 16u}) {
    EncodeOptions o;
    o.max_payload = payload;
    const auto q = encode_job(plan_with_spline(spline), o);
    o.splines = SplineFrames::kCompact;
    const auto k = encode_job(plan_with_spline(spline), o);
    size_t q_bytes = 0, k_bytes = 0;
    for (const auto& c : q) {
      EXPECT_NE(c.letter, proto::kCmdSplineCompact);
      EXPECT_LE(c.payload.size(), payload);
      if (c.letter == proto::kCmdSplineContour) q_bytes += frame_bytes(c);
    }
    for (const auto& c : k) {
      EXPECT_NE(c.letter, proto::kCmdSplineContour);
      if (c.letter == proto::kCmdSplineCompact) k_bytes += frame_bytes(c);
    }
    EXPECT_GT(q_bytes, 0u);
    EXPECT_LT(q_bytes * 10, k_bytes * 6) << "payload " << payload;  // 40 % fewer at least
    test::expect_same_spline(spline, reassemble(q));
    test::expect_same_spline(spline, reassemble(k));
  }
  // A middle point the controller would not make: #K frames, the same spline.
  core::Spline moved = spline;
  moved.control[3].x_um += 1;
  for (const auto& c : encode_job(plan_with_spline(moved), EncodeOptions{}))
    EXPECT_NE(c.letter, proto::kCmdSplineContour);
  test::expect_same_spline(moved, reassemble(encode_job(plan_with_spline(moved), EncodeOptions{})));
}

TEST(JobEncoder, AVersion2ControllerGetsCompactFrames) {
  proto::SessionReply caps{};
  caps.max_payload = 40;
  caps.protocol_version = 2;
  EncodeOptions o;
  use_session(caps, &o);
  EXPECT_EQ(o.max_payload, 40u);
  EXPECT_EQ(o.splines, SplineFrames::kCompact);
  caps.protocol_version = 3;
  EncodeOptions p;
  use_session(caps, &p);
  EXPECT_EQ(p.splines, SplineFrames::kContour);
}

// Pen-up Z moves go at the reference machine's fastest Z until a controller answers, then at
// the fastest Z feed its *I reports.
TEST(JobEncoder, PenUpGoesAtTheControllersFastestZ) {
  JobPlan plan;
  PlanStep up;
  up.kind = PlanStep::kPenUp;
  up.z_um = 2000;
  plan.steps.push_back(up);
  auto pen_up_feed = [&](const EncodeOptions& o) {
    for (const QueuedCommand& c : encode_job(plan, o))
      if (c.letter == proto::kCmdZMove) return decoded<proto::ZMoveCmd>(c).feed_um_per_s;
    ADD_FAILURE() << "no #Z";
    return uint16_t{0};
  };
  EncodeOptions o;
  EXPECT_EQ(pen_up_feed(o),
            config::default_machine_config().axis[config::kAxisZ].max_speed_um_per_s);
  proto::SessionReply caps{};
  caps.max_payload = 64;
  caps.protocol_version = 3;
  caps.max_feed_z_um_per_s = 3200;
  use_session(caps, &o);
  EXPECT_EQ(pen_up_feed(o), 3200);
}

TEST(JobEncoder, WireBytesCountHeaderAndCrc) {
  std::vector<QueuedCommand> cmds(2);
  cmds[0].payload.resize(10);
  cmds[1].payload.resize(0);
  EXPECT_EQ(wire_bytes(cmds), 16u + 6u);
}

}  // namespace
}  // namespace host
