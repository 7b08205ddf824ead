// The watched inbox: a finished drawing becomes a job and leaves the folder; a file still
// growing waits; a refused one goes to refused/ with the reason.
#include <gtest/gtest.h>

#include "host/lib/server/inbox_watcher.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

namespace fs = std::filesystem;

TEST(InboxWatcher, QueuesFinishedDrawingsAndRefusesOthersWithAReason) {
  test::TempDir dir;
  const fs::path inbox = dir.path() / "inbox";
  DataFolder data(dir.path() / "data");
  SqliteJobStore store(data.database().string());
  JobIntake intake(store, data, {MachineFit{}}, 64 * 1024);
  int queued = 0;
  InboxWatcher watcher(inbox, intake, JobPlanSettings{}, std::chrono::milliseconds(50),
                       [&] { ++queued; });
  write_file(inbox / "board.ngc", test::square_gcode(10, 10, 10));
  write_file(inbox / "readme.txt", "not a drawing\n");
  write_file(inbox / ".partial.ngc", test::square_gcode(10, 10, 10));
  watcher.scan();  // first sight: sizes noted, nothing taken (could still be written)
  EXPECT_EQ(store.list("", 10).size(), 0u);
  watcher.scan();
  const auto jobs = store.list("", 10);
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_EQ(jobs[0].name, "board.ngc");
  EXPECT_EQ(jobs[0].state, JobState::kQueued);
  EXPECT_EQ(queued, 1);
  EXPECT_FALSE(fs::exists(inbox / "board.ngc"));
  EXPECT_TRUE(fs::exists(data.job_dir(jobs[0].key) / "input.ngc"));
  EXPECT_TRUE(fs::exists(inbox / "refused" / "readme.txt"));
  EXPECT_NE(read_file(inbox / "refused" / "readme.txt.why.txt").find("readme.txt"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(inbox / ".partial.ngc"));  // hidden files are left alone

  // A file that grows between scans waits until it stops growing.
  write_file(inbox / "growing.ngc", "G21\n");
  watcher.scan();
  write_file(inbox / "growing.ngc", test::square_gcode(20, 20, 10));
  watcher.scan();
  EXPECT_EQ(store.list("", 10).size(), 1u);
  watcher.scan();
  EXPECT_EQ(store.list("", 10).size(), 2u);
}

}  // namespace
}  // namespace host::server
