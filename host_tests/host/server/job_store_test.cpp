// The SQLite job store: queue order, machine fit, one claim per job, state rules and what a
// restart finds.
#include <gtest/gtest.h>

#include <set>     // std::set
#include <thread>  // std::thread

#include "host/lib/server/job_record_fields.h"
#include "host/lib/server/machine_spec.h"
#include "host/lib/server/sqlite_job_store.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

JobRecord job(const std::string& key, int priority = 0, double w = 50, double h = 50,
              const std::string& tag = "") {
  JobRecord j;
  j.key = key;
  j.name = key + ".dxf";
  j.input_file = "input.dxf";
  j.priority = priority;
  j.width_mm = w;
  j.height_mm = h;
  j.tag = tag;
  return j;
}

// A lease on `name` (one holder, taken for dead after 30 s).
Lease lease_of(JobStore& store, const std::string& name) {
  return store.acquire_lease(name, "test-host:/data", 30000);
}

JobProgress at(int64_t executed, int64_t total, int resume_curve) {
  JobProgress p;
  p.executed = executed;
  p.total = total;
  p.resume_curve = resume_curve;
  return p;
}

TEST(SqliteJobStore, ClaimsByPriorityThenAge) {
  test::TempDir dir;
  SqliteJobStore store((dir.path() / "jobs.sqlite").string());
  const int64_t low = store.add(job("a", 0), "");
  const int64_t high = store.add(job("b", 5), "");
  const int64_t low2 = store.add(job("c", 0), "");
  MachineFit fit;
  const Lease lease = lease_of(store, "s");
  EXPECT_EQ(store.claim(fit, "m1", lease)->id, high);
  EXPECT_EQ(store.claim(fit, "m1", lease)->id, low);
  const auto third = store.claim(fit, "m2", lease);
  ASSERT_TRUE(third);
  EXPECT_EQ(third->id, low2);
  EXPECT_EQ(third->state, JobState::kRunning);
  EXPECT_EQ(third->machine, "m2");
  EXPECT_FALSE(store.claim(fit, "m1", lease));
}

TEST(SqliteJobStore, ClaimsOnlyJobsThatFitTheMachine) {
  test::TempDir dir;
  SqliteJobStore store((dir.path() / "jobs.sqlite").string());
  const int64_t big = store.add(job("big", 9, 250, 150), "");
  const int64_t brass = store.add(job("brass", 8, 20, 20, "brass"), "");
  const int64_t any = store.add(job("any", 0), "");
  const Lease lease = lease_of(store, "s");
  MachineFit small;
  small.work_width_mm = 200;
  small.work_height_mm = 200;
  small.tags = {"pen"};
  EXPECT_TRUE(store.has_claimable(small));
  EXPECT_EQ(store.claim(small, "small", lease)->id, any);  // too big, wrong tag: skipped
  EXPECT_FALSE(store.has_claimable(small));
  MachineFit brass_machine;
  brass_machine.tags = {"pen", "brass"};
  EXPECT_EQ(store.claim(brass_machine, "b", lease)->id, big);
  EXPECT_EQ(store.claim(brass_machine, "b", lease)->id, brass);
}

TEST(SqliteJobStore, ConcurrentClaimsTakeEachJobOnce) {
  test::TempDir dir;
  const std::string path = (dir.path() / "jobs.sqlite").string();
  {
    SqliteJobStore store(path);
    for (int i = 0; i < 200; ++i) store.add(job("j" + std::to_string(i)), "");
  }
  // Two connections (as two processes would have), two threads each.
  SqliteJobStore a(path), b(path);
  const Lease lease = lease_of(a, "s");
  std::vector<std::vector<int64_t>> got(4);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      SqliteJobStore& s = t % 2 ? a : b;
      while (auto j = s.claim(MachineFit{}, "m" + std::to_string(t), lease))
        got[t].push_back(j->id);
    });
  }
  for (auto& t : threads) t.join();
  std::set<int64_t> all;
  size_t count = 0;
  for (const auto& g : got) {
    all.insert(g.begin(), g.end());
    count += g.size();
  }
  EXPECT_EQ(count, 200u);
  EXPECT_EQ(all.size(), 200u);
}

TEST(SqliteJobStore, StateRulesForCancelRequeueAndPriority) {
  test::TempDir dir;
  SqliteJobStore store((dir.path() / "jobs.sqlite").string());
  const int64_t id = store.add(job("a"), "");
  EXPECT_TRUE(store.set_priority(id, 7));
  EXPECT_EQ(store.get(id)->priority, 7);
  EXPECT_FALSE(store.requeue(id, false));  // queued already
  const Lease lease = lease_of(store, "s");
  ASSERT_TRUE(store.claim(MachineFit{}, "m", lease));
  EXPECT_FALSE(store.cancel(id));  // running: abort it on the machine instead
  EXPECT_FALSE(store.set_priority(id, 1));
  EXPECT_TRUE(store.finish(id, lease, JobState::kInterrupted, "link lost", at(5, 20, 2)));
  EXPECT_FALSE(store.finish(id, lease, JobState::kCompleted, "twice", at(20, 20, -1)));
  const JobRecord r = *store.get(id);
  EXPECT_EQ(r.state, JobState::kInterrupted);
  EXPECT_EQ(r.executed, 5);
  EXPECT_EQ(r.resume_curve, 2);
  EXPECT_TRUE(store.requeue(id, true));  // continue from curve 2
  EXPECT_EQ(store.get(id)->start_curve, 2);
  EXPECT_EQ(store.get(id)->state, JobState::kQueued);
  EXPECT_TRUE(store.cancel(id));
  EXPECT_EQ(store.get(id)->state, JobState::kCancelled);
  EXPECT_FALSE(store.requeue(id, false));
}

TEST(SqliteJobStore, RestartKeepsQueuedJobsAndMarksOwnRunningJobsInterrupted) {
  test::TempDir dir;
  const std::string path = (dir.path() / "jobs.sqlite").string();
  int64_t mine = 0, theirs = 0, queued = 0;
  {
    SqliteJobStore store(path);
    mine = store.add(job("mine", 3), "");
    theirs = store.add(job("theirs", 2), "");
    queued = store.add(job("queued", 1), "");
    store.claim(MachineFit{}, "m1", lease_of(store, "this-server"));
    store.claim(MachineFit{}, "m9", lease_of(store, "other-server"));
  }  // the process dies here without finishing anything
  SqliteJobStore store(path);
  EXPECT_EQ(store.interrupt_running("this-server", "server restarted"), 1);
  EXPECT_EQ(store.get(mine)->state, JobState::kInterrupted);
  EXPECT_EQ(store.get(mine)->message, "server restarted");
  EXPECT_EQ(store.get(theirs)->state, JobState::kRunning);  // another server's job
  EXPECT_EQ(store.get(queued)->state, JobState::kQueued);
  EXPECT_EQ(store.list("", 10).size(), 3u);
  EXPECT_EQ(store.list("queued", 10).size(), 1u);
}

TEST(SqliteJobStore, RunningJobsOfASilentServerBecomeInterruptedAndItsLeaseIsFenced) {
  test::TempDir dir;
  SqliteJobStore store((dir.path() / "jobs.sqlite").string());
  const int64_t alive_job = store.add(job("a"), "");
  const int64_t dead_job = store.add(job("b"), "");
  const int64_t queued = store.add(job("c"), "");
  const Lease dead = lease_of(store, "dead");
  const Lease alive = lease_of(store, "alive");
  ASSERT_EQ(store.claim(MachineFit{}, "m1", alive)->id, alive_job);
  ASSERT_EQ(store.claim(MachineFit{}, "m2", dead)->id, dead_job);
  EXPECT_TRUE(store.save_progress(dead_job, dead, at(3, 20, 1)));
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  ASSERT_TRUE(store.renew_lease(alive));  // "dead" said nothing since
  EXPECT_EQ(store.interrupt_stale(20, "server gone"), 1);
  EXPECT_EQ(store.get(dead_job)->state, JobState::kInterrupted);
  EXPECT_EQ(store.get(dead_job)->message, "server gone");
  EXPECT_EQ(store.get(dead_job)->executed, 3);  // the progress it saved is kept
  EXPECT_EQ(store.get(alive_job)->state, JobState::kRunning);
  EXPECT_EQ(store.get(queued)->state, JobState::kQueued);
  EXPECT_EQ(store.interrupt_stale(20, "again"), 0);

  // The silent server wakes: nothing it does under its old lease is taken.
  EXPECT_FALSE(store.renew_lease(dead));
  EXPECT_FALSE(store.save_progress(dead_job, dead, at(9, 20, 2)));
  EXPECT_FALSE(store.finish(dead_job, dead, JobState::kCompleted, "done", at(20, 20, -1)));
  EXPECT_THROW(store.claim(MachineFit{}, "m2", dead), LeaseLost);
  EXPECT_EQ(store.get(queued)->state, JobState::kQueued);
  // Re-queued, the job runs under the other server; the woken one cannot touch it either.
  ASSERT_TRUE(store.requeue(dead_job, true));
  ASSERT_EQ(store.claim(MachineFit{}, "m1", alive)->id, dead_job);
  EXPECT_FALSE(store.save_progress(dead_job, dead, at(9, 20, 2)));
  EXPECT_FALSE(store.finish(dead_job, dead, JobState::kAborted, "x", at(9, 20, 2)));
  EXPECT_TRUE(store.finish(dead_job, alive, JobState::kCompleted, "", at(20, 20, -1)));
  // It takes its name again with a new epoch and works on under that.
  const Lease again = lease_of(store, "dead");
  EXPECT_GT(again.epoch, dead.epoch);
  EXPECT_EQ(store.claim(MachineFit{}, "m2", again)->id, queued);
}

TEST(SqliteJobStore, ALiveNameIsRefusedToAnotherHolderAndTakenOverByItsOwn) {
  test::TempDir dir;
  SqliteJobStore store((dir.path() / "jobs.sqlite").string());
  const Lease first = store.acquire_lease("shop", "pc1:/srv/a", 30000);
  try {
    store.acquire_lease("shop", "pc2:/srv/b", 30000);
    FAIL() << "a second live server with the same name was let in";
  } catch (const NameInUse& e) {
    EXPECT_NE(std::string(e.what()).find("another server named 'shop' is alive"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("pc1:/srv/a"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(store.renew_lease(first));  // untouched
  // The same holder again (the process died; its data folder lock is free): a new epoch,
  // and the old one is fenced.
  const Lease second = store.acquire_lease("shop", "pc1:/srv/a", 30000);
  EXPECT_GT(second.epoch, first.epoch);
  EXPECT_FALSE(store.renew_lease(first));
  // A name silent longer than stale_ms is free for anyone.
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_GT(store.acquire_lease("shop", "pc2:/srv/b", 20).epoch, second.epoch);
}

TEST(SqliteJobStore, ProgressSavedWhileRunningMakesAnInterruptedJobContinuable) {
  test::TempDir dir;
  SqliteJobStore store((dir.path() / "jobs.sqlite").string());
  const int64_t id = store.add(job("a"), "");
  const Lease lease = lease_of(store, "s");
  ASSERT_TRUE(store.claim(MachineFit{}, "m", lease));
  JobProgress p = at(7, 30, -1);  // past the last curve: only the position says where
  p.resume_index = 12;
  p.resume_point = 18;
  p.resume_job_id = 0x5A17;
  ASSERT_TRUE(store.save_progress(id, lease, p));
  EXPECT_EQ(store.get(id)->state, JobState::kRunning);
  EXPECT_EQ(store.get(id)->executed, 7);
  // The server dies; its restart marks the job interrupted, the position is kept.
  EXPECT_EQ(store.interrupt_running("s", "server restarted"), 1);
  const JobRecord r = *store.get(id);
  EXPECT_EQ(r.resume_index, 12);
  EXPECT_EQ(r.resume_point, 18);
  EXPECT_EQ(r.resume_job_id, 0x5A17);
  EXPECT_TRUE(store.requeue(id, true));
  EXPECT_EQ(store.get(id)->resume_index, 12);
  EXPECT_EQ(store.get(id)->message, "");
  // Claimed again to continue: planning (no commands yet), not the last run's "cutting",
  // and still where it stopped.
  ASSERT_TRUE(store.claim(MachineFit{}, "m", lease));
  const JobRecord continued = *store.get(id);
  EXPECT_EQ(continued.total, 0);
  EXPECT_EQ(continued.executed, 0);
  EXPECT_EQ(job_record_json(continued)["stage"], "planning");
  EXPECT_EQ(continued.resume_index, 12);
  ASSERT_TRUE(store.finish(id, lease, JobState::kInterrupted, "stopped again", p));
  EXPECT_TRUE(store.requeue(id, true));
  // Re-run from the start instead: the position is forgotten.
  ASSERT_TRUE(store.claim(MachineFit{}, "m", lease));
  ASSERT_TRUE(store.finish(id, lease, JobState::kFailed, "alarm", p));
  EXPECT_TRUE(store.requeue(id, false));
  EXPECT_EQ(store.get(id)->resume_index, -1);
  EXPECT_EQ(store.get(id)->resume_curve, -1);
  EXPECT_EQ(store.get(id)->message, "");  // not the failed run's "alarm"
}

// A server that dies between the claim and its first save leaves the job interrupted with
// nothing executed and no position: "continue" runs it from the start (it answered 409,
// and the fencing soak's operator, who only continues, waited for it forever). A job that
// executed something without a position saved stays for a re-queue.
TEST(SqliteJobStore, AJobInterruptedBeforeItsFirstSaveContinuesFromTheStart) {
  test::TempDir dir;
  SqliteJobStore store((dir.path() / "jobs.sqlite").string());
  const int64_t fresh = store.add(job("fresh"), "");
  const int64_t cut = store.add(job("cut"), "");
  const Lease lease = lease_of(store, "s");
  ASSERT_EQ(store.claim(MachineFit{}, "m1", lease)->id, fresh);
  ASSERT_EQ(store.claim(MachineFit{}, "m2", lease)->id, cut);
  ASSERT_TRUE(store.save_progress(cut, lease, at(4, 20, -1)));
  EXPECT_EQ(store.interrupt_running("s", "server restarted"), 2);
  EXPECT_TRUE(store.requeue(fresh, true));
  EXPECT_EQ(store.get(fresh)->state, JobState::kQueued);
  EXPECT_EQ(store.get(fresh)->start_curve, -1);  // from the start
  EXPECT_FALSE(store.requeue(cut, true));
  EXPECT_TRUE(store.requeue(cut, false));
}

TEST(SqliteJobStore, UnopenableFileIsAnErrorNamingIt) {
  try {
    SqliteJobStore store("/nonexistent-folder/x/jobs.sqlite");
    FAIL() << "opened";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/x/jobs.sqlite"), std::string::npos);
  }
}

TEST(MachineSpec, ParsesAddressNameWorkAreaAndTags) {
  const MachineSpec m =
      parse_machine_spec("tcp://10.0.0.5:10001 name=left work=200x150.5 tags=pen,brass", "m1");
  EXPECT_EQ(m.address, "tcp://10.0.0.5:10001");
  EXPECT_EQ(m.name, "left");
  EXPECT_DOUBLE_EQ(m.fit.work_width_mm, 200);
  EXPECT_DOUBLE_EQ(m.fit.work_height_mm, 150.5);
  EXPECT_EQ(m.fit.tags, (std::vector<std::string>{"pen", "brass"}));
  EXPECT_EQ(parse_machine_spec("serial:/dev/ttyUSB0,57600", "m2").name, "m2");
  for (const char* bad : {"", "ftp://x", "tcp://h:1 work=0x5", "tcp://h:1 tags=a/b",
                          "tcp://h:1 colour=red", "tcp://h:1 name=../x"}) {
    EXPECT_THROW(parse_machine_spec(bad, "m"), std::invalid_argument) << bad;
  }
}

TEST(UploadName, RefusesPathsAndOddNames) {
  EXPECT_EQ(check_upload_name("Board v2 (final).dxf"), "");
  for (const char* bad : {"../x.dxf", "a/b.dxf", "..\\x.dxf", "C:x.dxf", ".hidden.dxf", "a..b",
                          "tab\there.dxf", ""}) {
    EXPECT_NE(check_upload_name(bad), "") << bad;
  }
  EXPECT_EQ(archive_input_name("Board.DXF"), "input.dxf");
  EXPECT_EQ(archive_input_name("x.ngc"), "input.ngc");
  EXPECT_EQ(archive_input_name("x.exe"), "input");
  EXPECT_EQ(archive_input_name("noext"), "input");
}

}  // namespace
}  // namespace host::server
