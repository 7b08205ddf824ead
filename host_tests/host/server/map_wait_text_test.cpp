// The `waiting` text of a queued job whose height map belongs to a machine (issue 25's
// outside tester: it said "waiting for machine 'left'" while 'left' was free, and while
// 'left' was no longer one of the server's machines and another took the job at once).
#include <gtest/gtest.h>

#include "host/lib/server/map_source.h"

namespace host::server {
namespace {

JobRecord queued_job() {
  JobRecord job;
  job.id = 7;
  job.state = JobState::kQueued;
  return job;
}

MapSource map_of(int64_t from, bool own) {
  MapSource s;
  s.from = from;
  s.own = own;
  s.has_map = true;
  s.machine = "left";
  s.source_completed = true;
  return s;
}

std::string text(const MapSource& s, MachineAvailability a) {
  return map_wait_text(queued_job(), s, [a](const std::string& machine) {
    EXPECT_EQ(machine, "left");
    return a;
  });
}

TEST(MapWaitText, SaysWhetherTheMapsMachineIsFreeBusyOfflineOrNotThisServers) {
  const MapSource other = map_of(4, false);
  EXPECT_EQ(text(other, MachineAvailability::kFree),
            "about to go to machine 'left' (free), which probed the height map of job 4");
  EXPECT_EQ(text(other, MachineAvailability::kBusy),
            "waiting for machine 'left' (busy), which probed the height map of job 4");
  EXPECT_EQ(text(other, MachineAvailability::kOffline),
            "waiting for machine 'left' (offline), which probed the height map of job 4");
  EXPECT_EQ(text(other, MachineAvailability::kNotHere), "");  // its run says why it fails
  const MapSource own = map_of(7, true);
  EXPECT_EQ(text(own, MachineAvailability::kBusy),
            "waiting for machine 'left' (busy), which probed this job's blank in an earlier run "
            "(the blank is clamped there)");
  EXPECT_EQ(text(own, MachineAvailability::kNotHere),
            "machine 'left', which probed this job's blank in an earlier run, is not one of this "
            "server's machines: the next free one here takes the job and probes the blank again");
}

TEST(MapWaitText, ANotQueuedJobOrOneWithoutAMapWaitsForNoMachine) {
  MapSource s = map_of(4, false);
  JobRecord running = queued_job();
  running.state = JobState::kRunning;
  const auto never = [](const std::string&) -> MachineAvailability {
    ADD_FAILURE() << "no machine asked about";
    return MachineAvailability::kFree;
  };
  EXPECT_EQ(map_wait_text(running, s, never), "");
  s.has_map = false;
  s.source_ended = true;
  EXPECT_EQ(map_wait_text(queued_job(), s, never), "");
}

}  // namespace
}  // namespace host::server
