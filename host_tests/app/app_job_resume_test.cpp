// Job progress and resume through the Application (docs/protocol.md, "#J job mark" and
// "Resuming"): a job with a setup before its first #J and a later #J that renumbers, cut off
// at every command boundary and inside its dwells, resumed from the status exactly as the
// document says, and cut off again inside that resume's lead-in: the cut path is the
// uninterrupted one, nothing skipped and nothing cut twice.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "host_tests/app/app_rig.h"
#include "host_tests/app/through_wire.h"

namespace fake_app {
namespace {

using proto::MachineState;
using Frame = TestHost::Frame;

const uint16_t kJobId = 0x5A17;
const int32_t kTravelZUm = 1000;
const int32_t kDepthUm = -200;

template <typename Msg>
Msg decoded(const Frame& f) {
  Msg m{};
  EXPECT_EQ(proto::decode(f.payload.data(), uint8_t(f.payload.size()), &m), proto::ErrorCode::kOk);
  return m;
}

proto::JobMarkCmd mark(int32_t index, uint16_t first_point) {
  return test::through_wire(proto::JobMarkCmd{index, first_point, kJobId});
}

// The job as a host streams it: a setup (resolution, spindle on and its run-up dwell, pen up)
// before the first #J, then two groups of job commands, the second numbered from 10 by a
// later #J (numbers 5..9 are not used).
std::vector<Frame> the_job() {
  const core::Spline first = blob_spline(30000, 30000, 10000, 12);
  const core::Spline second = blob_spline(60000, 60000, 8000, 10);
  std::vector<Frame> job;
  auto add = [&](const Frame& f) { job.push_back(f); };
  auto add_spline = [&](const core::Spline& s) {
    for (const Frame& f : spline_frames(s, 10000)) add(f);
  };
  add(TestHost::make(proto::ResolutionCmd{1000, 2}));
  add(TestHost::make(proto::SpindleCmd{1}));
  add(TestHost::make(proto::DwellCmd{400}));
  add(TestHost::make(proto::ZMoveCmd{kTravelZUm, 2000}));
  add(TestHost::make(mark(0, 0)));
  add(TestHost::make(proto::RapidMoveCmd{first.control[0].x_um, first.control[0].y_um}));  // 0
  add(TestHost::make(proto::ZMoveCmd{kDepthUm, 1000}));                                    // 1
  add_spline(first);                                                                       // 2
  add(TestHost::make(proto::ZMoveCmd{kTravelZUm, 2000}));                                  // 3
  add(TestHost::make(proto::RapidMoveCmd{70000, 20000}));                                  // 4
  add(TestHost::make(mark(10, 0)));
  add(TestHost::make(proto::ZMoveCmd{kDepthUm, 1000}));                    // 10
  add(TestHost::make(proto::FeedMoveCmd{90000, 25000, 10000}));            // 11
  add(TestHost::make(proto::DwellCmd{300}));                               // 12
  add(TestHost::make(proto::FeedMoveCmd{second.control[0].x_um,            // 13
                                        second.control[0].y_um, 10000}));  //
  add_spline(second);                                                      // 14
  add(TestHost::make(proto::ZMoveCmd{kTravelZUm, 2000}));                  // 15
  add(TestHost::make(proto::RapidMoveCmd{10000, 10000}));                  // 16
  return job;
}

// Each frame's job index by the document's numbering (-1: not a job command).
std::vector<int32_t> job_indices(const std::vector<Frame>& job) {
  std::vector<int32_t> out;
  bool numbering = false;
  int32_t next = 0;
  for (const Frame& f : job) {
    if (f.letter == proto::kCmdJobMark) {
      numbering = true;
      next = decoded<proto::JobMarkCmd>(f).job_index;
      out.push_back(-1);
    } else if (proto::command_role(f.letter) != proto::CommandRole::kJobCommand || !numbering) {
      out.push_back(-1);
    } else {
      out.push_back(next++);
    }
  }
  return out;
}

// The resume procedure of docs/protocol.md, step 2 and 3, from a status read at rest after
// #I: the lead-in (resolution, pen up, travel to where the tool stands, spindle on again and
// its run-up, pen down to the depth cut there), #J job_index curve_point job_id, then the job
// from that command on as first sent (its later #J marks included). Empty: nothing left.
std::vector<Frame> resume_stream(const std::vector<Frame>& job, const proto::StatusReply& st) {
  const std::vector<int32_t> index = job_indices(job);
  size_t from = job.size();
  for (size_t i = 0; i < job.size(); ++i) {
    if (index[i] == st.job_index) from = i;
  }
  if (from == job.size()) return {};
  const Frame* resolution = nullptr;
  const Frame* height = nullptr;
  size_t spindle_on = job.size();
  for (size_t i = 0; i < from; ++i) {
    const uint8_t l = job[i].letter;
    if (l == proto::kCmdResolution) resolution = &job[i];
    if (l == proto::kCmdZMove) height = &job[i];
    if (l == proto::kCmdSpindle)
      spindle_on = decoded<proto::SpindleCmd>(job[i]).on ? i : job.size();
  }
  std::vector<Frame> out;
  if (resolution != nullptr) out.push_back(*resolution);
  out.push_back(TestHost::make(proto::ZMoveCmd{kTravelZUm, 2000}));
  out.push_back(TestHost::make(proto::RapidMoveCmd{st.x_um, st.y_um}));
  if (spindle_on < job.size()) {
    out.push_back(job[spindle_on]);
    for (size_t i = spindle_on + 1; i < from && job[i].letter == proto::kCmdDwell; ++i)
      out.push_back(job[i]);
  }
  if (height != nullptr && job[from].letter != proto::kCmdZMove &&
      decoded<proto::ZMoveCmd>(*height).z_um < kTravelZUm)
    out.push_back(*height);
  const uint16_t point = job[from].letter == proto::kCmdSplineHeader ? st.curve_point : 0;
  out.push_back(TestHost::make(mark(st.job_index, point)));
  out.insert(out.end(), job.begin() + long(from), job.end());
  return out;
}

// How the link goes: the host stops talking (the watchdog holds the job after 2 s), the
// operator aborts, or the host reconnects at once (its #I stops the job).
enum class Cut { kLinkLost, kAbort, kSessionReset };

// Where to cut: once `items` commands of the session have finished, `delay_ms` later.
struct CutAt {
  int items;
  int delay_ms;
  Cut how;
};

std::string describe(const CutAt& c) {
  const char* how = c.how == Cut::kLinkLost ? "link lost" : c.how == Cut::kAbort ? "abort" : "#I";
  return std::to_string(c.items) + " done +" + std::to_string(c.delay_ms) + " ms, " + how;
}

// Streams `frames` in a fresh session and runs them to the end, or cuts them off as `cut`
// says. False when the cut point was never reached (the session ended first).
bool run_session(AppRig& rig, const std::vector<Frame>& frames, const CutAt* cut) {
  EXPECT_TRUE(rig.open_session());
  for (const Frame& f : frames) rig.host.queue(f);
  if (cut == nullptr) {
    EXPECT_TRUE(rig.run_job(400000));
    return true;
  }
  const bool reached = rig.run_until(
      [&] {
        return rig.app.items_done() >= cut->items ||
               (rig.host.all_acked() && rig.app.queue_size() == 0);
      },
      400000);
  if (!reached || rig.app.items_done() < cut->items) {
    EXPECT_TRUE(rig.run_job(400000));
    return false;
  }
  rig.run(cut->delay_ms);
  if (cut->how == Cut::kAbort) {
    rig.host.send_realtime(proto::AbortCmd{});
    rig.run(1500);
  } else if (cut->how == Cut::kLinkLost) {
    for (int ms = 0; ms < 2500; ++ms) {  // nobody talks: the watchdog holds the job
      rig.app.tick_1ms();
      rig.plant.step_1ms();
      rig.app.poll();
    }
    EXPECT_EQ(rig.app.state(), MachineState::kHeld);
    rig.link.rx.clear();
    rig.link.tx.clear();
  }
  return true;
}

// Step 1 of the resume: #I, then the status once the machine is at rest.
proto::StatusReply status_at_rest(AppRig& rig) {
  EXPECT_TRUE(rig.open_session());
  rig.host.have_status = false;
  EXPECT_TRUE(rig.run_until(
      [&] { return rig.host.have_status && rig.host.status.state == MachineState::kIdle; }, 10000));
  return rig.host.status;
}

// The cut: the tool's X/Y path (µm, every millisecond) while it is below the board surface,
// as segments.
struct Seg {
  double x0, y0, x1, y1;
};

std::vector<Seg> cut_segments(const AppRig& rig) {
  const double k = 1000.0 / config::usteps_per_mm(rig.cfg.axis[0]);
  std::vector<Seg> out;
  const auto& path = rig.plant.path;
  for (size_t i = KinematicPlant::kSubSteps; i < path.size(); i += KinematicPlant::kSubSteps) {
    const auto& a = path[i - KinematicPlant::kSubSteps];
    const auto& b = path[i];
    if (a[2] * k > kDepthUm / 2 || b[2] * k > kDepthUm / 2) continue;
    const Seg s{a[0] * k, a[1] * k, b[0] * k, b[1] * k};
    if (s.x0 != s.x1 || s.y0 != s.y1) out.push_back(s);
  }
  return out;
}

double length_um(const std::vector<Seg>& segs) {
  double sum = 0;
  for (const Seg& s : segs) sum += std::hypot(s.x1 - s.x0, s.y1 - s.y0);
  return sum;
}

double point_segment_um(double x, double y, const Seg& s) {
  const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
  const double l2 = dx * dx + dy * dy;
  const double t = l2 > 0 ? std::clamp(((x - s.x0) * dx + (y - s.y0) * dy) / l2, 0.0, 1.0) : 0;
  return std::hypot(x - (s.x0 + t * dx), y - (s.y0 + t * dy));
}

// Farthest a point of `a` lies from the path `b` (b's segments in a 0.5 mm grid).
double farthest_um(const std::vector<Seg>& a, const std::vector<Seg>& b) {
  const double cell = 500;
  std::map<std::pair<int, int>, std::vector<size_t>> grid;
  for (size_t i = 0; i < b.size(); ++i) {
    const Seg& s = b[i];
    for (int gx = int(std::floor(std::min(s.x0, s.x1) / cell));
         gx <= int(std::floor(std::max(s.x0, s.x1) / cell)); ++gx)
      for (int gy = int(std::floor(std::min(s.y0, s.y1) / cell));
           gy <= int(std::floor(std::max(s.y0, s.y1) / cell)); ++gy)
        grid[{gx, gy}].push_back(i);
  }
  double worst = 0;
  for (const Seg& s : a) {
    for (const auto& [x, y] : {std::pair{s.x0, s.y0}, std::pair{s.x1, s.y1}}) {
      double best = 1e9;
      const int gx = int(std::floor(x / cell)), gy = int(std::floor(y / cell));
      for (int ix = gx - 1; ix <= gx + 1; ++ix)
        for (int iy = gy - 1; iy <= gy + 1; ++iy) {
          const auto it = grid.find({ix, iy});
          if (it == grid.end()) continue;
          for (size_t n : it->second) best = std::min(best, point_segment_um(x, y, b[n]));
        }
      worst = std::max(worst, best);
    }
  }
  return worst;
}

// A zeroed machine at the work zero, recording its path.
void start(AppRig& rig) {
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  rig.plant.record = true;
}

std::vector<Seg> uninterrupted_cut() {
  AppRig rig;
  start(rig);
  run_session(rig, the_job(), nullptr);
  return cut_segments(rig);
}

// The status as seen by the host (a #? answered).
proto::StatusReply status_now(AppRig& rig) {
  rig.host.have_status = false;
  rig.host.query_status();
  EXPECT_TRUE(rig.run_until([&] { return rig.host.have_status; }, 100));
  return rig.host.status;
}

// The case of the issue: the host has queued a setup dwell, #J 0, job commands and a later
// #J 10; while the dwell runs, and after the link is lost there, command 0 is the first one
// that has not finished (not 10).
TEST(AppJobProgress, ALaterMarkQueuedBehindASetupDwellDoesNotMoveTheProgress) {
  AppRig rig;
  start(rig);
  rig.host.queue(proto::DwellCmd{3000});
  rig.host.queue(mark(0, 0));
  rig.host.queue(proto::FeedMoveCmd{5000, 0, 5000});     // 0
  rig.host.queue(proto::FeedMoveCmd{5000, 5000, 5000});  // 1
  rig.host.queue(mark(10, 0));
  rig.host.queue(proto::FeedMoveCmd{0, 5000, 5000});  // 10
  ASSERT_TRUE(rig.run_until([&] { return rig.host.all_acked(); }, 1000));
  rig.run(500);
  proto::StatusReply st = status_now(rig);
  EXPECT_EQ(st.state, MachineState::kRunning);
  EXPECT_EQ(st.job_index, 0);
  EXPECT_EQ(st.job_id, kJobId);
  EXPECT_FALSE(st.flags & proto::kStatusJobStarted);
  st = status_at_rest(rig);  // the link lost, the resume's #I
  EXPECT_EQ(st.job_index, 0);
  EXPECT_EQ(st.curve_point, 0);
  EXPECT_EQ(rig.position_um().x, 0);
}

// A #J with nothing stored after it names the next job command (and its first point).
TEST(AppJobProgress, AMarkWithNothingAfterItIsTheNextJobCommand) {
  AppRig rig;
  start(rig);
  rig.host.queue(proto::FeedMoveCmd{3000, 0, 5000});
  rig.host.queue(mark(7, 3));
  ASSERT_TRUE(rig.run_job(10000));
  proto::StatusReply st = status_now(rig);
  ASSERT_TRUE(st.flags & proto::kStatusJob);
  EXPECT_EQ(st.job_index, 7);
  EXPECT_EQ(st.curve_point, 3);
  st = status_at_rest(rig);  // kept through #I
  EXPECT_EQ(st.job_index, 7);
  EXPECT_EQ(st.curve_point, 3);
}

// Commands of two marks in the tick's ring when the job is dropped: the tick finishes the
// first while it decelerates; the first unfinished one is then the second mark's.
TEST(AppJobProgress, ADropWithTwoMarksInTheRingFollowsTheSecondMarksNumbers) {
  AppRig rig;
  start(rig);
  const uint16_t zeroing_done = rig.app.items_done();
  rig.host.queue(mark(0, 0));
  rig.host.queue(proto::FeedMoveCmd{20000, 0, 10000});  // 0
  rig.host.queue(mark(10, 0));
  rig.host.queue(proto::FeedMoveCmd{40000, 0, 10000});     // 10
  rig.host.queue(proto::FeedMoveCmd{40000, 9000, 10000});  // 11
  ASSERT_TRUE(rig.run_until([&] { return rig.position_um().x > 19950; }, 10000));
  ASSERT_EQ(rig.app.items_done(), zeroing_done);  // command 0 still running at the drop
  const proto::StatusReply st = status_at_rest(rig);
  EXPECT_GT(rig.position_um().x, 20000);  // the tick finished it while decelerating
  EXPECT_EQ(st.job_index, 10);
  EXPECT_TRUE(st.flags & proto::kStatusJobStarted);
}

TEST(AppJobResume, CutAtEveryBoundaryAndInItsDwellsAndResumedTwiceCutsTheSamePath) {
  const std::vector<Frame> job = the_job();
  const std::vector<Seg> reference = uninterrupted_cut();
  const double reference_um = length_um(reference);
  ASSERT_GT(reference_um, 100000.0);
  // The first session runs the setup (4 commands) and the 12 job commands: cut at each
  // boundary, inside each dwell (the setup's run-up is the 3rd command, the job's dwell the
  // 12th) and inside the first spline (the 7th).
  std::vector<CutAt> first_cuts;
  const Cut hows[] = {Cut::kSessionReset, Cut::kLinkLost, Cut::kAbort};
  for (int n = 1; n <= 15; ++n) first_cuts.push_back({n, 0, hows[n % 3]});
  first_cuts.push_back({2, 200, Cut::kLinkLost});
  first_cuts.push_back({2, 200, Cut::kSessionReset});
  first_cuts.push_back({11, 150, Cut::kAbort});
  first_cuts.push_back({6, 1500, Cut::kSessionReset});
  int scenario = 0;
  for (const CutAt& first : first_cuts) {
    ++scenario;
    AppRig rig;
    start(rig);
    ASSERT_TRUE(run_session(rig, job, &first)) << describe(first);
    const proto::StatusReply at = status_at_rest(rig);
    ASSERT_TRUE(at.flags & proto::kStatusJob) << describe(first);
    ASSERT_EQ(at.job_id, kJobId);
    const std::vector<Frame> resumed = resume_stream(job, at);
    ASSERT_FALSE(resumed.empty()) << describe(first);
    // Cut the resume too: inside its lead-in (at each of its boundaries in turn, some inside
    // the spindle's run-up dwell), then resume again from what the status says now.
    const CutAt second{1 + scenario % 5, scenario % 2 ? 0 : 250, hows[(scenario + 1) % 3]};
    run_session(rig, resumed, &second);
    const proto::StatusReply again = status_at_rest(rig);
    ASSERT_TRUE(again.flags & proto::kStatusJob);
    run_session(rig, resume_stream(job, again), nullptr);

    const std::vector<Seg> got = cut_segments(rig);
    const double off_um = farthest_um(got, reference);
    const double missed_um = farthest_um(reference, got);
    const double length = length_um(got);
    std::printf(
        "[ resume   ] %-28s -> %d:%u%s, then %-22s -> %d:%u%s: off %.2f um, uncut %.2f um, "
        "length %+.2f um\n",
        describe(first).c_str(), at.job_index, at.curve_point,
        at.flags & proto::kStatusJobStarted ? " cut short" : "", describe(second).c_str(),
        again.job_index, again.curve_point,
        again.flags & proto::kStatusJobStarted ? " cut short" : "", off_um, missed_um,
        length - reference_um);
    // Cut off again before the resumed command moved on: still the command cut short.
    if ((at.flags & proto::kStatusJobStarted) && again.job_index == at.job_index &&
        again.curve_point == at.curve_point)
      EXPECT_TRUE(again.flags & proto::kStatusJobStarted) << describe(first);
    EXPECT_LE(off_um, 5.0) << describe(first);
    EXPECT_LE(missed_um, 5.0) << describe(first);
    EXPECT_NEAR(length, reference_um, 10.0) << describe(first);  // nothing cut twice
  }
}

}  // namespace
}  // namespace fake_app
