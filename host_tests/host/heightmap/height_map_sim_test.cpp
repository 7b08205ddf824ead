// End to end in the simulator: a board's isolation on a tilted, bowed blank, probed into a
// map through the controller's probe, the map sent before the job, the controller following
// it; the depth of cut measured against the TRUE surface. Without the map the depth is off
// by the warp; with it within 10 um, and the job's frames are the same bytes.
#include <gtest/gtest.h>

#include <map>     // std::map
#include <memory>  // std::make_shared

#include "firmware/protocol/parser.h"
#include "host/lib/heightmap/controller_map.h"
#include "host/lib/heightmap/depth_meter.h"
#include "host/lib/heightmap/job_area.h"
#include "host/lib/heightmap/probe_session.h"
#include "host/lib/heightmap/simulated_blank.h"
#include "host/lib/pcb/board_job.h"
#include "host/lib/sim/sim_job.h"
#include "host_tests/host/pcb/synthetic_board.h"

namespace host::heightmap {
namespace {

using pcb::test::pad;
using pcb::test::track;

// Pads and tracks spread over 10 .. 70 x 10 .. 50 mm: isolation across the whole warp.
pcb::PcbLayer spread_copper() {
  ClipperLib::Paths c;
  for (double x : {12.0, 40.0, 68.0})
    for (double y : {12.0, 30.0, 48.0}) c.push_back(pad(x, y, 1.0));
  for (const auto& t : {track(12, 12, 68, 12, 0.4), track(12, 48, 68, 30, 0.4)})
    c.insert(c.end(), t.begin(), t.end());
  return pcb::test::copper_layer(c, pcb::LayerKind::kCopperTop);
}

// Records the bytes the sender writes (host -> controller).
class RecordingLink : public Link {
 public:
  RecordingLink(std::unique_ptr<Link> inner, std::shared_ptr<std::vector<uint8_t>> out)
      : inner_(std::move(inner)), out_(std::move(out)) {}
  void write(const uint8_t* data, size_t size) override {
    out_->insert(out_->end(), data, data + size);
    inner_->write(data, size);
  }
  size_t read(uint8_t* buffer, size_t capacity, std::chrono::milliseconds timeout) override {
    return inner_->read(buffer, capacity, timeout);
  }
  std::string name() const override { return "recording " + inner_->name(); }

 private:
  std::unique_ptr<Link> inner_;
  std::shared_ptr<std::vector<uint8_t>> out_;
};

// The queued frames from the job's first job mark (#J) on, each once (letter + payload).
std::vector<std::string> job_frames(const std::vector<uint8_t>& bytes) {
  proto::Parser parser(proto::kCommandStart);
  std::vector<std::string> frames;
  std::map<uint8_t, std::string> last_by_seq;
  bool in_job = false;
  for (uint8_t b : bytes) {
    for (proto::ParseEvent e = parser.feed(b); e != proto::ParseEvent::kNone; e = parser.poll()) {
      if (e != proto::ParseEvent::kFrame) continue;
      const proto::Frame& f = parser.frame();
      if (f.kind != proto::FrameKind::kQueued) continue;
      if (f.letter == proto::kCmdJobMark) in_job = true;
      if (!in_job) continue;
      const std::string frame = std::string(1, static_cast<char>(f.letter)) +
                                std::string(reinterpret_cast<const char*>(f.payload), f.length);
      auto it = last_by_seq.find(f.seq);
      if (it != last_by_seq.end() && it->second == frame) continue;  // a resend
      last_by_seq[f.seq] = frame;
      frames.push_back(frame);
    }
  }
  return frames;
}

struct Outcome {
  sim::SimJobResult run;
  DepthReport depth;
  std::vector<std::string> frames;
  std::optional<HeightMap> map;
};

// The board through the simulator on the blank, probed first when `probe`.
Outcome cut(const pcb::BoardJob& job, const std::string& surface, bool probe) {
  const SurfaceModel model(parse_surface_spec(surface), AreaMm{0, 0, 80, 60});
  auto blank = std::make_shared<SimulatedBlank>(model);
  Outcome out;
  DepthOptions d;
  d.isolation_z_mm = -0.05;
  d.planned_width_um = 200;
  DepthMeter meter(model, nullptr, d);
  bool job_started = !probe;
  sim::SimJobOptions o;
  o.sender.status_interval = std::chrono::milliseconds(50);
  o.machine.surface_um = [blank](int32_t x, int32_t y) { return blank->surface_um(x, y); };
  o.on_sample = [&](const sim::ToolSample& s) {
    blank->tool_at(s.x_mm, s.y_mm, s.z_mm);
    if (job_started) meter.add(s.x_mm, s.y_mm, s.z_mm);
  };
  auto bytes = std::make_shared<std::vector<uint8_t>>();
  o.wrap_link = [bytes](std::unique_ptr<Link> inner) -> std::unique_ptr<Link> {
    return std::make_unique<RecordingLink>(std::move(inner), bytes);
  };
  if (probe) {
    o.before_job = [&](Sender& sender) {
      ProbeOptions p;
      p.grid.spacing_mm = 10;
      out.map =
          probe_blank(*cutting_area(job.plan), p, controller_touch(sender, ProbeMotion{})).map;
      refuse_job_outside_map(job.plan, *out.map, "the probed map");
      meter.set_applied_map(&*out.map);
      job_started = true;
      return height_map_commands(*out.map);
    };
  }
  out.run = sim::run_sim_job(job.plan, o);
  out.depth = meter.report();
  out.frames = job_frames(*bytes);
  return out;
}

const char* const kWarped = "tilt=0.1mm,bow=0.2mm,noise=2um,seed=1";

TEST(HeightMapSim, ProbedMapKeepsTheDepthWithin10umOnAWarpedBlank) {
  const pcb::PcbLayer copper = spread_copper();
  pcb::BoardLayers layers;
  layers.copper_top = &copper;
  pcb::BoardOptions bo;
  bo.spindle = false;
  const pcb::BoardJob job = pcb::plan_board(layers, bo);

  const Outcome flat = cut(job, "noise=0um", false);
  ASSERT_EQ(flat.run.outcome, JobOutcome::kCompleted) << flat.run.message;
  const Outcome without = cut(job, kWarped, false);
  ASSERT_EQ(without.run.outcome, JobOutcome::kCompleted) << without.run.message;
  const Outcome with = cut(job, kWarped, true);
  ASSERT_EQ(with.run.outcome, JobOutcome::kCompleted) << with.run.message;
  ASSERT_TRUE(with.map);

  // Every isolation path measured in each run.
  EXPECT_GT(with.depth.length_mm, 0.95 * without.depth.length_mm);
  EXPECT_GT(without.depth.length_mm, 100.0);
  // Without the map the warp is cut into the board: far too deep in its middle.
  EXPECT_GT(std::abs(without.depth.max_error_um), 100.0);
  // With it: within 10 um everywhere, the groove within 10 um of its planned width.
  EXPECT_LE(std::abs(with.depth.max_error_um), 10.0)
      << "at " << with.depth.max_error_at_mm[0] << ", " << with.depth.max_error_at_mm[1];
  EXPECT_LE(std::abs(with.depth.max_width_error_um), 10.0);
  EXPECT_DOUBLE_EQ(with.depth.uncut_mm, 0.0);
  // The map rides beside the job: the job's frames are the same bytes.
  EXPECT_EQ(with.run.wire_bytes, without.run.wire_bytes);
  ASSERT_FALSE(with.frames.empty());
  EXPECT_EQ(with.frames, without.frames);
  EXPECT_EQ(with.frames, flat.frames);
  EXPECT_GT(with.run.setup.commands, 1u);  // the #A header and its #E heights
}

}  // namespace
}  // namespace host::heightmap
