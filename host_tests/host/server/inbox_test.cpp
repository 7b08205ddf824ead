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

// What the intake hands the store for each job.
class InputRecordingStore : public SqliteJobStore {
 public:
  InputRecordingStore(const std::string& path, bool keeps) : SqliteJobStore(path), keeps_(keeps) {}
  int64_t add(const JobRecord& job, const std::string& input) override {
    inputs.push_back(input);
    return SqliteJobStore::add(job, input);
  }
  bool keeps_input() const override { return keeps_; }
  std::vector<std::string> inputs;

 private:
  bool keeps_;
};

// A drawing received to disk (an HTTP upload's part, an inbox file) is copied into its archive
// folder and planned from there. A store that keeps no input (SQLite: the archive has it) is
// handed no bytes, so the drawing is never read whole into memory (a 1 M-line upload was
// held four times at once); one that keeps inputs (PostgreSQL) gets the file's bytes.
TEST(JobIntake, ADrawingOnDiskIsNotReadIntoMemoryForAStoreThatKeepsNoInput) {
  test::TempDir dir;
  DataFolder data(dir.path() / "data");
  const std::string gcode = test::square_gcode(10, 10, 10);
  const fs::path received = dir.path() / "received";
  write_file(received, gcode);
  for (const bool keeps : {false, true}) {
    InputRecordingStore store((dir.path() / (keeps ? "k.sqlite" : "n.sqlite")).string(), keeps);
    JobIntake intake(store, data, {MachineFit{}}, 64 * 1024);
    for (const bool on_disk : {true, false}) {
      Submission sub;
      sub.name = "square.ngc";
      if (on_disk) {
        sub.content_file = received;
      } else {
        sub.content = gcode;
      }
      const IntakeResult r = intake.submit(sub);
      ASSERT_EQ(r.status, 201) << r.error;
      EXPECT_EQ(store.inputs.back(), keeps ? gcode : "") << keeps << on_disk;
      EXPECT_EQ(read_file(data.job_dir(store.get(r.id)->key) / "input.ngc"), gcode);
    }
    EXPECT_TRUE(fs::exists(received));  // the caller's: it removes it
  }
  // Over the limit: refused before it is copied.
  SqliteJobStore store((dir.path() / "small.sqlite").string());
  JobIntake small(store, data, {MachineFit{}}, gcode.size() - 1);
  Submission sub;
  sub.name = "square.ngc";
  sub.content_file = received;
  EXPECT_EQ(small.submit(sub).status, 413);
  EXPECT_TRUE(store.list("", 10).empty());
}

// A server that stops ends an upload's planning at once (a 1 M-line upload planned on for
// a minute and more after Ctrl-C): 503, nothing queued or left in the data folder; later
// uploads and inbox files get the same, and the inbox keeps its file for the next start.
TEST(JobIntake, AStopEndsAnUploadsPlanningAndQueuesNothing) {
  test::TempDir dir;
  DataFolder data(dir.path() / "data");
  SqliteJobStore store(data.database().string());
  JobIntake intake(store, data, {MachineFit{}}, 64 * 1024 * 1024);
  Submission sub;
  sub.name = "lines.dxf";
  sub.content = test::separate_lines_dxf(100000);
  std::thread stopper([&intake] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    intake.stop();
  });
  const IntakeResult r = intake.submit(sub);
  stopper.join();
  EXPECT_EQ(r.status, 503) << r.error;
  EXPECT_NE(r.error.find("lines.dxf: the server is stopping: not queued"), std::string::npos)
      << r.error;
  EXPECT_TRUE(store.list("", 10).empty());
  EXPECT_TRUE(fs::is_empty(data.root() / "jobs"));
  EXPECT_EQ(intake.submit(sub).status, 503);

  const fs::path inbox = dir.path() / "inbox";
  InboxWatcher watcher(inbox, intake, JobPlanSettings{}, std::chrono::milliseconds(50), [] {});
  write_file(inbox / "square.ngc", test::square_gcode(10, 10, 10));
  watcher.scan();
  watcher.scan();
  EXPECT_TRUE(fs::exists(inbox / "square.ngc"));
  EXPECT_FALSE(fs::exists(inbox / "refused" / "square.ngc"));
}

}  // namespace
}  // namespace host::server
