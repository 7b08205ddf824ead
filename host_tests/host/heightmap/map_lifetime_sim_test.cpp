// A height map's lifetime on the simulated machine (docs/protocol.md, #A): a job sent
// after a job with a map, without one, cuts at its planned depth — in the same session (the
// host's clear, job_map_commands) and in a new one (#I clears the map).
#include <gtest/gtest.h>

#include <cmath>   // std::abs
#include <memory>  // std::make_unique
#include <vector>  // std::vector

#include "firmware/protocol/messages.h"
#include "host/lib/heightmap/controller_map.h"
#include "host/lib/sim/sim_link.h"
#include "host/lib/sim/sim_machine.h"
#include "host/lib/stream/encode_command.h"

namespace host::heightmap {
namespace {

const int32_t kDepthUm = -100;

// Up, over to (10, 10) mm, down to the depth, a 20 mm cut along X, up again.
std::vector<QueuedCommand> cut_job() {
  return {encode_command(proto::ZMoveCmd{2000, 5000}),
          encode_command(proto::RapidMoveCmd{10000, 10000}),
          encode_command(proto::ZMoveCmd{kDepthUm, 2000}),
          encode_command(proto::FeedMoveCmd{30000, 10000, 5000}),
          encode_command(proto::ZMoveCmd{2000, 5000})};
}

// 50 x 50 mm, 300 um higher than the job's zero (the cut and outside: the edge value).
HeightMap raised_map() {
  HeightMap m;
  m.rows = m.cols = 2;
  m.pitch_x_mm = m.pitch_y_mm = 50;
  m.heights_um = {300, 300, 300, 300};
  return m;
}

std::vector<QueuedCommand> with_setup(const HeightMap* map) {
  std::vector<QueuedCommand> c = job_map_commands(map);
  const std::vector<QueuedCommand> job = cut_job();
  c.insert(c.end(), job.begin(), job.end());
  return c;
}

// The Z (um) of the tool along the middle of the cut, the worst from `want`.
struct CutDepth {
  std::vector<sim::ToolSample> samples;
  double worst_from(double want_um) const {
    double worst = 0;
    int n = 0;
    for (const sim::ToolSample& s : samples) {
      if (s.x_mm < 15 || s.x_mm > 25 || std::abs(s.y_mm - 10) > 0.01 || s.z_mm > 1) continue;
      worst = std::max(worst, std::abs(s.z_mm * 1000 - want_um));
      ++n;
    }
    return n > 100 ? worst : 1e9;  // too few samples: not the cut
  }
};

void run_job(Sender& sender, const std::vector<QueuedCommand>& commands) {
  ASSERT_EQ(sender.run(commands, [](const Progress&) {}), JobOutcome::kCompleted)
      << sender.message();
}

TEST(MapLifetime, AJobWithoutAMapAfterOneWithAMapIsNotCompensated) {
  for (const bool new_session : {false, true}) {
    sim::SimMachine machine{sim::SimOptions{}};
    CutDepth cut;
    machine.set_sample_sink([&cut](const sim::ToolSample& s) { cut.samples.push_back(s); });
    SenderOptions so;
    so.clock = [&machine] { return sim::machine_clock(machine); };
    sim::SimLink link(machine);
    auto sender = std::make_unique<Sender>(link, so);
    sender->open_session();
    const HeightMap map = raised_map();
    run_job(*sender, with_setup(&map));
    EXPECT_LE(cut.worst_from(kDepthUm + 300), 2.0) << "the map job follows its map";
    cut.samples.clear();
    if (new_session) {
      sender = std::make_unique<Sender>(link, so);
      sender->open_session();
    }
    run_job(*sender, with_setup(nullptr));
    EXPECT_LE(cut.worst_from(kDepthUm), 2.0)
        << (new_session ? "new session" : "same session")
        << ": the last job's map compensated a job sent without one";
  }
}

TEST(MapLifetime, AJobWithoutAMapStartsWithTheClear) {
  const std::vector<QueuedCommand> c = job_map_commands(nullptr);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].letter, clear_height_map_command().letter);
  EXPECT_EQ(c[0].payload, clear_height_map_command().payload);
}

}  // namespace
}  // namespace host::heightmap
