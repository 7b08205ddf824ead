// Leases: a server's lease lapses locally before others may take it for dead, and a server
// whose lease was revoked stops its machines (the job it was cutting is not cut further).
#include <gtest/gtest.h>

#include <cstdio>  // std::printf
#include <thread>  // std::this_thread

#include "host/lib/server/job_planning.h"
#include "host/lib/server/server_lease.h"
#include "host/lib/sim/sim_job.h"
#include "host_tests/host/server/server_test_rig.h"
#include "host_tests/host/sim/cut_path.h"

namespace host::server {
namespace {

using test::ServerRig;
using test::SimRig;

TEST(ServerLease, LapsesLocallyBeforeOthersMayTakeTheServerForDeadAndStaysGoneOnceRevoked) {
  test::TempDir dir;
  SqliteJobStore store((dir.path() / "jobs.sqlite").string());
  ServerLease lease(store, "s", "pc:/data", std::chrono::milliseconds(400));
  const Lease first = lease.acquire();
  EXPECT_TRUE(lease.valid(first.epoch));
  EXPECT_FALSE(lease.valid(first.epoch + 1));  // another epoch's work: never
  // Not renewed: lapses at three quarters of stale_after (300 ms), before anyone may take
  // the server for dead (400 ms).
  std::this_thread::sleep_for(std::chrono::milliseconds(330));
  EXPECT_NE(lease.why_not(first.epoch).find("could not renew its lease in time"),
            std::string::npos);
  EXPECT_EQ(lease.renew(), ServerLease::Renewal::kRenewed);
  EXPECT_TRUE(lease.valid(first.epoch));
  // Another server takes it for dead: revoked; the renewal says so and nothing under that
  // epoch is valid again.
  std::this_thread::sleep_for(std::chrono::milliseconds(450));
  SqliteJobStore other((dir.path() / "jobs.sqlite").string());
  other.interrupt_stale(400, "taken for dead");
  EXPECT_EQ(lease.renew(), ServerLease::Renewal::kLost);
  EXPECT_NE(lease.why_not(first.epoch).find("lost its lease"), std::string::npos);
  const Lease second = lease.acquire();
  EXPECT_GT(second.epoch, first.epoch);
  EXPECT_FALSE(lease.valid(first.epoch));
  EXPECT_TRUE(lease.valid(second.epoch));
}

// Another server (here: another connection to the same store) takes this one for dead while
// its machine cuts: the job is interrupted there, and this server stops its machine within
// a heartbeat instead of cutting on.
TEST(ServerLease, AServerWhoseLeaseIsRevokedStopsItsMachineAndSaysSo) {
  test::TempDir dir;
  SimRig sim(true);
  ServerRig server(dir.path(), {test::machine("m1", sim.address())});
  const int64_t id = server.upload_ok("multi.ngc", test::squares_gcode(3, 8), "&feed_mm_s=10");
  ASSERT_TRUE(test::wait_until(
      [&] {
        const auto p = server.running(id);
        return !p.is_null() && p["executed"].get<int>() > 0 &&
               p["executed"].get<int>() * 4 >= p["total"].get<int>();
      },
      30));
  SqliteJobStore other(server.data().database().string());
  ASSERT_EQ(other.interrupt_stale(0, "taken for dead by another server"), 1);
  // Within a heartbeat (1 s) plus a status poll the machine is stopped.
  ASSERT_TRUE(test::wait_until([&] { return server.running(id).is_null(); }, 5));
  EXPECT_EQ(server.job(id)["state"], "interrupted");
  EXPECT_EQ(server.job(id)["message"], "taken for dead by another server");
  auto log = server.client().Get(fmt::format("/api/jobs/{}/files/machine.log", id).c_str());
  ASSERT_TRUE(log && log->status == 200);
  EXPECT_NE(log->body.find("lost its lease"), std::string::npos) << log->body;
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // would it cut on?
  server.shutdown();
  sim.kill();

  const std::optional<JobRecord> rec = server.store().get(id);
  ASSERT_TRUE(rec);
  const MachineSpec spec = test::machine("m", "");
  const JobPlan plan =
      plan_file((server.data().job_dir(rec->key) / rec->input_file).string(), rec->name,
                rec->settings, spec.fit.work_width_mm, spec.fit.work_height_mm);
  const host::test::CutPath got = host::test::cut_path(sim.machine().trace(), plan);
  std::printf("lease revoked at a quarter of the job: %.3f mm of 96 mm cut\n", got.length_mm);
  // Stopped well before the end (about 30 % was cut when the lease went).
  EXPECT_LT(got.length_mm, 96.0 * 0.75);
  // And continued (from where the machine stopped) it completes.
}

}  // namespace
}  // namespace host::server
