// Prints the example frames quoted in docs/protocol.md section 6 (run it and paste the
// output when the protocol changes; the doc-example test checks the pasted bytes).
#include <cstdio>  // printf
#include <string>  // std::string

#include "firmware/protocol/codec.h"
#include "firmware/protocol/compact_spline.h"
#include "firmware/protocol/contour_spline.h"

namespace {

template <typename Msg>
void show(const Msg& msg, uint8_t seq, const std::string& what) {
  uint8_t buf[proto::kMaxFrameBytes];
  uint8_t n = 0;
  if (proto::write_frame(msg, seq, buf, sizeof buf, &n) != proto::ErrorCode::kOk) {
    std::printf("ENCODE FAILED ; %s\n", what.c_str());
    return;
  }
  for (uint8_t i = 0; i < n; ++i) std::printf("%02X ", buf[i]);
  std::printf("; %s\n", what.c_str());
}

}  // namespace

int main() {
  std::printf("```frames\n");
  show(proto::SessionCmd{3}, 0, "#I seq 0: open session, protocol version 3");
  show(proto::SessionReply{3, 64, 8, 16, 256, 3, 64, 0, 3, 297000, 210000, 40000, 25000, 5000}, 0,
       "*I seq 0: v3, payload 64, window 8, 16 slots, rx 256 B, degree 3, 64 points, fw 0.3, "
       "travel 297 x 210 x 40 mm, feeds up to 25 mm/s (X/Y) and 5 mm/s (Z)");
  show(proto::TextCmd{0, 9, {'E', 'n', 'g', 'r', 'a', 'v', 'i', 'n', 'g'}}, 1,
       "#S seq 1: row 0 \"Engraving\"");
  show(proto::AckReply{15, 2, false}, 1,
       "*O seq 1: stored, 15 queue slots and 2 spline slots free");
  show(proto::ResolutionCmd{50, 5}, 2, "#U seq 2: points at most 50 um apart, chord error 5 um");
  show(proto::RapidMoveCmd{10000, 5000}, 3, "#F seq 3: rapid to X 10 mm, Y 5 mm");
  show(proto::ZMoveCmd{-200, 500}, 4, "#Z seq 4: Z to -0.2 mm at 0.5 mm/s");
  show(proto::FeedMoveCmd{12000, -3500, 2000}, 5, "#G seq 5: to X 12 mm, Y -3.5 mm at 2 mm/s");
  show(proto::SplineHeaderCmd{3, false, 4, 8, 1500}, 6,
       "#B seq 6: cubic, not rational, 4 control points, 8 knots, 1.5 mm/s");
  proto::SplineDataCmd d1 = {};
  d1.control_index = 0;
  d1.control_n = 4;
  d1.knot_index = 0;
  d1.knot_n = 4;
  const int32_t xs[4] = {12000, 15000, 18000, 21000};
  const int32_t ys[4] = {-3500, 2000, 2000, -3500};
  for (int i = 0; i < 4; ++i) {
    d1.control[i].x_um = xs[i];
    d1.control[i].y_um = ys[i];
    d1.control[i].weight_q14 = 16384;
    d1.knot[i] = 0;
  }
  show(d1, 7, "#D seq 7: control points 0..3 (weight 1.0), knots 0..3 = 0 0 0 0");
  proto::SplineDataCmd d2 = {};
  d2.control_index = 4;  // all 4 control points are stored: the next index, even with nc 0
  d2.knot_index = 4;
  d2.knot_n = 4;
  for (int i = 0; i < 4; ++i) d2.knot[i] = 1000;
  show(d2, 8, "#D seq 8: no control points (control_index 4: all stored), knots 4..7 = 1000");
  // The same data as seq 7 and 8 in one compact frame instead.
  proto::SplineCompactCmd k = {};
  k.control_n = 4;
  k.knot_n = 8;
  core::ControlPoint prev = {0, 0, core::kWeightOneQ14};
  for (int i = 0; i < 4; ++i) {
    const core::ControlPoint p = {xs[i], ys[i], core::kWeightOneQ14};
    k.data_n = uint8_t(k.data_n + proto::put_compact_point(prev, p, false, k.data + k.data_n));
    prev = p;
  }
  const int32_t knots[8] = {0, 0, 0, 0, 1000, 1000, 1000, 1000};
  for (int i = 0; i < 8;) {
    const bool repeat = i > 0 && i + 1 < 8 && knots[i + 1] == knots[i];
    k.data_n = uint8_t(k.data_n + proto::put_compact_knot(i ? knots[i - 1] : 0, knots[i], i == 0,
                                                          repeat, k.data + k.data_n));
    i += repeat ? 2 : 1;
  }
  show(k, 7,
       "#K seq 7, instead of seq 7 and 8: the 4 control points as differences (+12 mm, "
       "-3.5 mm; +3 mm, +5.5 mm; +3 mm, 0; +3 mm, -5.5 mm) and the 8 knots as 0, then spans "
       "0 (repeated), 0, 1000 (repeated), 0 (repeated): 26 bytes of payload instead of 80");
  // A contour: a line, then a quarter circle turning left, as #B and one #Q.
  show(proto::SplineHeaderCmd{2, true, 5, 8, 2000}, 17,
       "#B seq 17: quadratic, rational, 5 control points (2 elements), 8 knots, 2 mm/s");
  proto::SplineContourCmd q = {};
  q.control_n = 5;
  q.data_n = proto::put_contour_start(10000, 5000, q.data);
  const proto::ContourElement line = {10000, 0, false, 0};
  const proto::ContourElement arc = {5000, 5000, true, -3536};
  q.data_n = uint8_t(q.data_n + proto::put_contour_element(line, q.data + q.data_n));
  q.data_n = uint8_t(q.data_n + proto::put_contour_element(arc, q.data + q.data_n));
  show(q, 18,
       "#Q seq 18: from (10, 5) mm a line by (+10, 0) mm, then an arc by (+5, +5) mm whose "
       "middle control point stands 3.536 mm right of the chord: the quarter circle about "
       "(20, 10) mm; the controller makes the middle points (15, 5) and (25, 5) mm, weights "
       "1.0 and 0.7071, and the knots 0 0 0 1 1 2 2 2");
  show(proto::ZeroingCmd{7}, 9, "#M seq 9: zero X, Y and Z with the joystick");
  show(proto::StatusCmd{}, 10, "#? seq 10: status query");
  proto::StatusReply s = {proto::MachineState::kRunning,
                          proto::Alarm::kNone,
                          proto::kStatusZeroed | proto::kStatusSession | proto::kStatusExecuted |
                              proto::kStatusJob | proto::kStatusJobStarted,
                          100,
                          12,
                          10,
                          5,
                          proto::ErrorCode::kOk,
                          12000,
                          -3500,
                          -200,
                          0,
                          1,
                          7,
                          18,
                          0x5A17};
  show(s, 10,
       "*? seq 10: running; flags 0xE6: zeroed, session open, done 5, job command 7 under way "
       "(heading for curve point 18) of job 5A17; 100 %, 12 free, expects 10, at (12, -3.5, "
       "-0.2) mm, 1 spline slot free");
  show(proto::ErrorReply{proto::ErrorCode::kSeqGap, 0, 10}, 12,
       "*E seq 12: seq_gap (20), controller expects seq 10");
  show(proto::ErrorReply{proto::ErrorCode::kGeometry, 5, 8}, 8,
       "*E seq 8: geometry (35), detail 5 = knots decreasing; the refused frame did not use up "
       "its seq: the controller expects seq 8 again");
  show(proto::HoldCmd{}, 0, "#H real-time seq 0: feed hold");
  show(proto::OverrideCmd{120}, 1, "#V real-time seq 1: feed override 120 %");
  show(proto::ResumeCmd{}, 2, "#R real-time seq 2: resume");
  show(proto::AbortCmd{}, 3, "#X real-time seq 3: abort");
  show(proto::AlarmReply{proto::Alarm::kLimitSwitch, proto::MachineState::kAlarm}, 1,
       "*A alarm #1: limit switch (1), state alarm (5)");
  show(proto::ClearAlarmCmd{}, 4, "#C real-time seq 4: clear alarm (the one just reported)");
  show(proto::AckReply{16, 2, true}, 4,
       "*O seq 4: real-time frame done (real-time flag set; 16 queue slots, 2 spline slots free)");
  show(proto::ClearAlarmCmd{}, 5, "#C real-time seq 5: clear alarm, with none active");
  show(proto::ErrorReply{proto::ErrorCode::kBadState, 0, 19}, 5,
       "*E seq 5: bad_state (33): no alarm to clear (next_expected_seq 19 is the ordered "
       "stream's, untouched by real-time frames)");
  show(proto::PauseCmd{13, {'T', 'o', 'o', 'l', ' ', '2', ':', ' ', '0', '.', '8', 'm', 'm'}}, 11,
       "#P seq 11: pause, LCD \"Tool 2: 0.8mm\", wait for the confirm button");
  show(proto::SpindleCmd{1}, 12, "#N seq 12: spindle on");
  show(proto::DwellCmd{1500}, 13, "#W seq 13: dwell 1.5 s (spindle run-up)");
  show(proto::DrillCmd{25400, 12700, 500, -1800, 800}, 14,
       "#L seq 14: drill at X 25.4 mm, Y 12.7 mm from Z 0.5 mm down to Z -1.8 mm at 0.8 mm/s");
  show(proto::SpindleCmd{0}, 15, "#N seq 15: spindle off");
  show(proto::JobMarkCmd{7, 18, 0x5A17}, 16,
       "#J seq 16: job 5A17, the next job command is number 7; resume its spline at curve "
       "point 18");
  show(proto::ProbeCmd{-3000, 200, 1000}, 17,
       "#Y seq 17: probe: Z down at 0.2 mm/s to at most Z -3 mm, on contact back up 1 mm");
  show(proto::ProbeResultCmd{}, 18, "#T seq 18: probe result query");
  show(proto::ProbeResultReply{1, 3, 10000, 5000, -137}, 18,
       "*T seq 18: contact, the 3rd probe since power-up, at X 10 mm, Y 5 mm: the copper is at "
       "Z -0.137 mm");
  show(proto::AlarmReply{proto::Alarm::kProbeNoContact, proto::MachineState::kAlarm}, 2,
       "*A alarm #2: probe without contact (8), state alarm (5)");
  show(proto::HeightMapHeaderCmd{3, 2, 0, 0, 40000, 30000}, 18,
       "#A seq 18 (the #T query before it used up no seq): height map of 3 x 2 points from (0, 0), "
       "40 mm apart in X, 30 mm in Y");
  show(proto::HeightMapDataCmd{0, 6, {0, -40, -95, 25, -20, -80}}, 19,
       "#E seq 19: its heights from index 0: 0, -40, -95 um (row Y 0), 25, -20, -80 um (row Y "
       "30 mm); the map is complete, compensation on");
  show(proto::ErrorReply{proto::ErrorCode::kHeightMap, proto::kHeightMapSpan, 19}, 19,
       "*E seq 19: height_map (38), detail 2: had the map spanned more than 1 mm, it would be "
       "refused (and the controller would expect seq 19 again)");
  std::printf("```\n");
  return 0;
}
