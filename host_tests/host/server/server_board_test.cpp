// Boards (Gerber/Excellon files) as workshop jobs over real HTTP on loopback: several files
// in one multipart upload become one job that runs on a simulated machine and lands in the
// archive with all its files; a board folder in the inbox becomes a job once it stops
// changing; a broken Gerber and a hostile file name are refused and store nothing.
#include <gtest/gtest.h>

#include <algorithm>  // std::min
#include <map>        // std::map
#include <optional>   // std::optional

#include "host/lib/server/board_bundle.h"
#include "host/lib/server/board_planning.h"
#include "host/lib/server/inbox_watcher.h"
#include "host/lib/server/job_planning.h"
#include "host/lib/server/zip_upload.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

using test::ServerRig;
using test::SimRig;
namespace fs = std::filesystem;

// A file of host_tests/host/server/data/ (the project's own tiny board).
std::string board_file(const std::string& name) {
  return read_file(fs::path(ENGRAVER_SOURCE_DIR) / "host_tests/host/server/data" / name);
}

size_t files_under(const fs::path& dir) {
  size_t n = 0;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       it != fs::recursive_directory_iterator(); ++it) {
    if (it->is_regular_file()) ++n;
  }
  return n;
}

httplib::MultipartFormDataItems blinky_form() {
  return {{"file", board_file("blinky-F.Cu.gbr"), "blinky-F.Cu.gbr", "application/octet-stream"},
          {"file", board_file("blinky.drl"), "blinky.drl", "application/octet-stream"},
          {"file", board_file("blinky-Edge.Cuts.gbr"), "blinky-Edge.Cuts.gbr",
           "application/octet-stream"},
          {"priority", "2", "", ""}};
}

void expect_refused(const httplib::Result& r, int status, const std::string& needle) {
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, status) << r->body;
  const nlohmann::json body = nlohmann::json::parse(r->body, nullptr, false);
  ASSERT_TRUE(body.is_object()) << r->body;
  EXPECT_NE(body.value("error", "").find(needle), std::string::npos) << r->body;
}

// A board is sent with points at most 1 um off its curves, whatever tol_mm says: the
// controller's chords come out of the isolation clearance. A drawing keeps its tol_mm.
TEST(ServerBoards, ABoardIsSentWithTheBoardsChordTolerance) {
  JobRecord board;
  board.name = "blinky.zip";
  board.input_file = kBoardManifest;
  board.settings.tol_mm = 0.005;
  EXPECT_EQ(encode_options(board).chord_tolerance_um, 1);
  EXPECT_EQ(encode_options(board).title, "blinky");
  JobRecord drawing = board;
  drawing.input_file = "input.dxf";
  EXPECT_EQ(encode_options(drawing).chord_tolerance_um, 5);
  drawing.settings.tol_mm = 0.002;
  EXPECT_EQ(encode_options(drawing).chord_tolerance_um, 2);
}

// The archive's plan.json is written step by step (a million steps as one JSON tree took
// 1.4 GB): it reads back as the same JSON as plan_json, with and without steps.
TEST(ServerBoards, PlanJsonWrittenStepByStepIsThePlansJson) {
  JobPlan plan;
  plan.pen_lifts = 1;
  plan.cut_length_mm = 12.5;
  for (int i = 0; i < 3; ++i) {
    PlanStep s;
    s.kind = i == 1 ? PlanStep::kFeed : PlanStep::kPenUp;
    s.to = {1000 * i, -20};
    s.z_um = 2000;
    s.feed_um_per_s = 500 * i;
    s.curve = i - 1;
    plan.steps.push_back(s);
  }
  const fs::path path = fs::path(testing::TempDir()) / "plan-steps.json";
  for (const JobPlan& p : {plan, JobPlan()}) {
    write_plan_json(path, p);
    const nlohmann::json written = nlohmann::json::parse(read_file(path));
    EXPECT_EQ(written, plan_json(p));
    EXPECT_EQ(written["steps"].size(), p.steps.size());
  }
}

TEST(ServerBoards, BoardUploadedAsSeveralFilesRunsOnASimulatedMachineAndIsArchived) {
  test::TempDir dir;
  SimRig sim(false);
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  auto r = server.client().Post("/api/jobs", server.auth(), blinky_form());
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  const nlohmann::json queued = nlohmann::json::parse(r->body);
  const int64_t id = queued["id"];
  EXPECT_EQ(queued["name"], "blinky");  // the files' common name
  EXPECT_EQ(queued["input_file"], "board.json");
  EXPECT_EQ(queued["priority"], 2);
  EXPECT_GT(queued["planned_s"].get<double>(), 10.0);  // three cut-out passes at 3 mm/s alone
  // Planned at upload: the board spans the 20 x 15 mm outline plus the cutter, from the
  // 5 mm margin `engraver board` leaves.
  EXPECT_EQ(queued["margin_mm"], 5.0);
  EXPECT_GT(queued["size_mm"][0].get<double>(), 25.0);
  EXPECT_LT(queued["size_mm"][0].get<double>(), 28.0);

  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "completed"; }, 100))
      << server.job(id).dump();
  const nlohmann::json done = server.job(id);
  EXPECT_EQ(done["executed"], done["total"]);
  EXPECT_EQ(done["machine"], "mill");

  // The archive keeps every input file under the server's names, byte for byte.
  auto get = [&](const std::string& file) {
    auto g = server.client().Get(fmt::format("/api/jobs/{}/files/{}", id, file).c_str());
    EXPECT_TRUE(g && g->status == 200) << file;
    return g && g->status == 200 ? g->body : std::string();
  };
  EXPECT_EQ(get("copper.top.gbr"), board_file("blinky-F.Cu.gbr"));
  EXPECT_EQ(get("drill.drl"), board_file("blinky.drl"));
  EXPECT_EQ(get("outline.gbr"), board_file("blinky-Edge.Cuts.gbr"));
  const nlohmann::json manifest = nlohmann::json::parse(get("board.json"));
  EXPECT_EQ(manifest["side"], "top");
  ASSERT_EQ(manifest["files"].size(), 3u);
  EXPECT_EQ(manifest["files"][0]["name"], "blinky-F.Cu.gbr");
  EXPECT_EQ(manifest["files"][0]["kind"], "copper_top");
  EXPECT_EQ(manifest["report"]["holes"], 3);
  EXPECT_EQ(manifest["report"]["holes_on_copper"], 3);
  EXPECT_EQ(manifest["report"]["tool_changes"], 2);
  // Plan, plot, report and the machine's log.
  const nlohmann::json plan = nlohmann::json::parse(get("plan.json"));
  size_t drills = 0;
  for (const auto& s : plan["steps"]) drills += s["kind"] == "drill";
  EXPECT_EQ(drills, 3u);
  // It starts with a pause naming the first tool: the operator mounts it and confirms.
  EXPECT_EQ(plan["steps"][0]["kind"], "pause");
  EXPECT_NE(get("plot.svg").find("<svg"), std::string::npos);
  EXPECT_EQ(get("plot.png").substr(1, 3), "PNG");
  EXPECT_NE(get("machine.log").find("ended: completed"), std::string::npos);
  const nlohmann::json report = nlohmann::json::parse(get("report.json"));
  EXPECT_EQ(report["state"], "completed");

  // The machine really made the board: the first tool and two tool changes confirmed at the
  // panel, the spindle
  // switched, and the tool went down to the drill and cut-out depth (1.8 mm).
  EXPECT_EQ(sim.machine().pauses_confirmed(), 3);
  EXPECT_GE(sim.machine().spindle_switches(), 2);
  double lowest_mm = 0;
  for (const auto& s : sim.machine().trace()) lowest_mm = std::min(lowest_mm, s.z_mm);
  EXPECT_LT(lowest_mm, -1.7);
}

// A board's margin is `engraver board`'s 5 mm unless the upload gives one (0 included); a
// drawing keeps 0.
TEST(ServerBoards, ABoardSitsAtTheBoardCommandsMarginUnlessTheUploadSaysOtherwise) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  auto upload = [&](const std::string& margin) {
    httplib::MultipartFormDataItems form = blinky_form();
    if (!margin.empty()) form.push_back({"margin_mm", margin, "", ""});
    auto r = server.client().Post("/api/jobs", server.auth(), form);
    EXPECT_TRUE(r && r->status == 201) << (r ? r->body : "no reply");
    return r && r->status == 201 ? nlohmann::json::parse(r->body) : nlohmann::json::object();
  };
  const nlohmann::json by_default = upload("");
  const nlohmann::json at_zero = upload("0");
  const nlohmann::json at_two = upload("2");
  EXPECT_EQ(by_default["margin_mm"], 5.0);
  EXPECT_EQ(at_zero["margin_mm"], 0.0);
  EXPECT_EQ(at_two["margin_mm"], 2.0);
  const double w = at_zero["size_mm"][0].get<double>();
  EXPECT_NEAR(by_default["size_mm"][0].get<double>(), w + 5.0, 1e-6);
  EXPECT_NEAR(at_two["size_mm"][0].get<double>(), w + 2.0, 1e-6);
  const int64_t drawing = server.upload_ok("square.ngc", test::square_gcode(10, 10, 10));
  EXPECT_EQ(server.job(drawing)["margin_mm"], 0.0);
}

TEST(ServerBoards, BrokenBoardIsRefusedWithTheReadersMessageAndNothingIsStored) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  httplib::MultipartFormDataItems form = blinky_form();
  form[0] = {"file", board_file("broken-F.Cu.gbr"), "broken-F.Cu.gbr", "application/octet-stream"};
  expect_refused(server.client().Post("/api/jobs", server.auth(), form), 422,
                 "broken-F.Cu.gbr:7: D42 selects an aperture that is not defined");
  // The same file alone (a raw upload) is a one-layer board, refused the same way.
  expect_refused(server.upload("broken-F.Cu.gbr", board_file("broken-F.Cu.gbr")), 422,
                 "broken-F.Cu.gbr:7");
  // A file that is no PCB file among the board's.
  form = blinky_form();
  form.push_back({"file", "Remember to buy milk.\n", "notes.txt", "text/plain"});
  expect_refused(server.client().Post("/api/jobs", server.auth(), form), 422,
                 "notes.txt: not a Gerber or Excellon file");
  // Two files for the top copper.
  form = blinky_form();
  form.push_back({"file", board_file("blinky-F.Cu.gbr"), "copy-F.Cu.gbr", ""});
  expect_refused(server.client().Post("/api/jobs", server.auth(), form), 422, "copy-F.Cu.gbr");
  // A Gerber whose name and attributes do not say which layer it is.
  expect_refused(server.upload("board.gbr", board_file("blinky-F.Cu.gbr")), 422,
                 "board.gbr: no copper, drill or outline layer among the files; a Gerber says "
                 "which it is by its X2 attributes or its name (KiCad's -F.Cu");
  expect_refused(server.upload("board.gbr", board_file("blinky-F.Cu.gbr")), 422,
                 "\n  board.gbr: not a copper, drill or outline layer");
  // Settings a board cannot take.
  form = blinky_form();
  form.push_back({"side", "left", "", ""});
  expect_refused(server.client().Post("/api/jobs", server.auth(), form), 400, "side");
  form = blinky_form();
  form.push_back({"scale", "2", "", ""});
  expect_refused(server.client().Post("/api/jobs", server.auth(), form), 400, "scale");
  // No token: nothing is even read.
  auto r = server.client().Post("/api/jobs", blinky_form());
  expect_refused(r, 401, "token");

  EXPECT_TRUE(server.jobs().empty());
  EXPECT_EQ(files_under(dir.path() / "jobs"), 0u);
  EXPECT_EQ(files_under(dir.path() / "tmp"), 0u);
}

TEST(ServerBoards, NarrowGapsAreRefusedWithTheServersAdviceUnlessAllowed) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  // A 4.5 mm tool cannot pass between the track and the lone pad (4 mm apart).
  httplib::MultipartFormDataItems form = blinky_form();
  form.push_back({"tool_width_mm", "4.5", "", ""});
  expect_refused(server.client().Post("/api/jobs", server.auth(), form), 422,
                 "or plan anyway (allow_narrow_gaps=1: the copper at those gaps stays joined)");
  EXPECT_TRUE(server.jobs().empty());
  form.push_back({"allow_narrow_gaps", "maybe", "", ""});
  expect_refused(server.client().Post("/api/jobs", server.auth(), form), 400, "allow_narrow_gaps");
  form.back().content = "1";
  auto r = server.client().Post("/api/jobs", server.auth(), form);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  const int64_t id = nlohmann::json::parse(r->body)["id"];
  auto g = server.client().Get(fmt::format("/api/jobs/{}/files/board.json", id).c_str());
  ASSERT_TRUE(g && g->status == 200);
  const nlohmann::json manifest = nlohmann::json::parse(g->body);
  EXPECT_EQ(manifest["allow_narrow_gaps"], true);
  EXPECT_DOUBLE_EQ(manifest["tool_width_mm"].get<double>(), 4.5);
  ASSERT_FALSE(manifest["report"]["narrow_gaps"].empty());
  EXPECT_NE(manifest["report"]["narrow_gaps"][0].get<std::string>().find(
                "(tool 4.500 mm + 2 x 0.008 mm clearance)"),
            std::string::npos);
}

TEST(ServerBoards, HostileFileNameInAMultiFileUploadIsRefusedAndNothingIsStored) {
  test::TempDir dir;
  ServerRig server(dir.path(), {}, 64 * 1024);
  for (const char* name : {"../../token", "../blinky-F.Cu.gbr", "sub/blinky.drl", "..\\blinky.drl",
                           ".hidden.gbr", "/etc/passwd", "C:blinky.drl"}) {
    httplib::MultipartFormDataItems form = blinky_form();
    form[1].filename = name;  // the drill file's name
    expect_refused(server.client().Post("/api/jobs", server.auth(), form), 400, "file name");
  }
  // The board's own name (a form field) is checked the same way, and named as the field.
  httplib::MultipartFormDataItems form = blinky_form();
  form.push_back({"name", "../../jobs/x", "", ""});
  expect_refused(server.client().Post("/api/jobs", server.auth(), form), 400, "field 'name'");
  // All files together count against the size limit.
  form = blinky_form();
  std::string padding = "G04 padding*\n";
  while (padding.size() < 40 * 1024) padding += "G04 padding*\n";
  form.push_back({"file", padding + board_file("blinky-F.Cu.gbr"), "b-B.Cu.gbr", ""});
  form.push_back({"file", padding + board_file("blinky-F.Cu.gbr"), "c-B.Cu.gbr", ""});
  expect_refused(server.client().Post("/api/jobs", server.auth(), form), 413, "limit");

  EXPECT_TRUE(server.jobs().empty());
  EXPECT_EQ(files_under(dir.path() / "jobs"), 0u);
  EXPECT_EQ(files_under(dir.path() / "tmp"), 0u);
  // Nothing was written outside the data folder's own names either.
  EXPECT_FALSE(fs::exists(dir.path() / "blinky-F.Cu.gbr"));
  EXPECT_FALSE(fs::exists(dir.path().parent_path() / "blinky-F.Cu.gbr"));
}

TEST(ServerBoards, BoardAsOneZipFileBecomesAJobAndZipTricksAreRefused) {
  test::TempDir dir;
  ServerRig server(dir.path(), {}, 256 * 1024);
  const std::string zip = board_file("blinky.zip");
  auto r = server.upload("blinky.zip", zip);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  const nlohmann::json job = nlohmann::json::parse(r->body);
  EXPECT_EQ(job["name"], "blinky");
  EXPECT_EQ(job["input_file"], "board.json");
  auto get = [&](const std::string& file) {
    auto g = server.client().Get(
        fmt::format("/api/jobs/{}/files/{}", job["id"].get<int64_t>(), file).c_str());
    EXPECT_TRUE(g && g->status == 200) << file;
    return g && g->status == 200 ? g->body : std::string();
  };
  EXPECT_EQ(get("input.zip"), zip);  // the upload as it came
  EXPECT_EQ(get("copper.top.gbr"), board_file("blinky-F.Cu.gbr"));
  EXPECT_EQ(get("outline.gbr"), board_file("blinky-Edge.Cuts.gbr"));
  const nlohmann::json manifest = nlohmann::json::parse(get("board.json"));
  EXPECT_EQ(manifest["files"].size(), 3u);
  EXPECT_EQ(manifest["files"][1]["name"], "blinky.drl");  // the entry's name, not its folder
  ASSERT_EQ(manifest["notes"].size(), 1u);  // the .gbrjob; the __MACOSX entry is dropped
  EXPECT_NE(manifest["notes"][0].get<std::string>().find("blinky-job.gbrjob"), std::string::npos);
  const size_t stored = files_under(dir.path() / "jobs");

  // Entries named to land elsewhere, a bomb, a damaged zip, a zip among other files.
  expect_refused(server.upload("traversal.zip", board_file("traversal.zip")), 422,
                 "entry '../../evil-F.Cu.gbr' points outside the zip");
  expect_refused(server.upload("bomb.zip", board_file("bomb.zip")), 413,
                 "bomb.zip: more than the limit of 262144 bytes once unpacked");
  expect_refused(server.upload("cut.zip", zip.substr(0, zip.size() / 2)), 422,
                 "cut.zip: not a readable zip file");
  httplib::MultipartFormDataItems form = blinky_form();
  form.push_back({"file", zip, "blinky.zip", "application/zip"});
  expect_refused(server.client().Post("/api/jobs", server.auth(), form), 400, "uploaded alone");
  EXPECT_EQ(server.jobs().size(), 1u);
  EXPECT_EQ(files_under(dir.path() / "jobs"), stored);
  EXPECT_EQ(files_under(dir.path() / "tmp"), 0u);
  EXPECT_FALSE(fs::exists(dir.path().parent_path() / "evil-F.Cu.gbr"));
  EXPECT_FALSE(fs::exists("/etc/evil.drl"));
}

TEST(ServerBoards, DamagedZipsAreRefusedWithZipErrorsAndStayWithinTheLimit) {
  const std::string zip = board_file("blinky.zip");
  const size_t limit = 4096;
  uint32_t seed = 12345;
  auto next = [&] { return seed = seed * 1664525u + 1013904223u; };
  size_t refused = 0, read = 0;
  for (int round = 0; round < 2000; ++round) {
    std::string bytes = zip;
    for (int k = 0, n = 1 + next() % 4; k < n; ++k) {
      bytes[next() % bytes.size()] = static_cast<char>(next() >> 24);
    }
    if (next() % 8 == 0) bytes.resize(next() % bytes.size());
    try {
      size_t total = 0;
      for (const UploadFile& f : unzip_upload(bytes, "m.zip", limit, 16)) {
        total += f.content.size();
        EXPECT_EQ(f.name.find_first_of("/\\"), std::string::npos) << f.name;
      }
      EXPECT_LE(total, limit);
      ++read;
    } catch (const ZipError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("m.zip: ", 0), 0u) << e.what();
      ++refused;
    }
  }
  // Both outcomes occur (a flipped byte in file data is caught by the CRC; in a name or
  // padding it may not matter).
  EXPECT_GT(refused, 100u);
  EXPECT_GT(read, 0u);
}

TEST(ServerBoards, BoardFolderInTheInboxBecomesAJobOnceItStopsChanging) {
  test::TempDir dir;
  SimRig sim(false);
  ServerRig server(dir.path() / "data", {test::machine("mill", sim.address())});
  const fs::path inbox = dir.path() / "inbox";
  InboxWatcher watcher(inbox, server.intake(), JobPlanSettings{}, std::chrono::milliseconds(50),
                       [&] { server.workshop().notify(true); });
  const fs::path board = inbox / "blinky";
  fs::create_directories(board);
  write_file(board / "blinky-F.Cu.gbr", board_file("blinky-F.Cu.gbr"));
  write_file(board / "blinky.drl", board_file("blinky.drl"));
  write_file(board / "blinky.gbrjob", "{\"Header\": {}}\n");  // CAM job file: left out
  watcher.scan();                                             // first sight
  write_file(board / "blinky-Edge.Cuts.gbr", board_file("blinky-Edge.Cuts.gbr"));
  watcher.scan();  // it changed: still being copied
  EXPECT_TRUE(server.jobs().empty());
  watcher.scan();  // unchanged since the last scan: taken
  const nlohmann::json jobs = server.jobs();
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_EQ(jobs[0]["name"], "blinky");
  EXPECT_EQ(jobs[0]["input_file"], "board.json");
  EXPECT_FALSE(fs::exists(board));
  const int64_t id = jobs[0]["id"];
  const fs::path archive = server.data().job_dir(server.store().get(id)->key);
  const nlohmann::json manifest = nlohmann::json::parse(read_file(archive / "board.json"));
  EXPECT_EQ(manifest["files"].size(), 3u);
  ASSERT_EQ(manifest["notes"].size(), 1u);
  EXPECT_NE(manifest["notes"][0].get<std::string>().find("blinky.gbrjob"), std::string::npos);
  EXPECT_EQ(read_file(archive / "outline.gbr"), board_file("blinky-Edge.Cuts.gbr"));
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "completed"; }, 100))
      << server.job(id).dump();
  EXPECT_TRUE(fs::exists(archive / "runs" / "1" / "report.json"));

  // A broken board goes to refused/ with the reader's message; nothing is queued.
  const fs::path broken = inbox / "broken";
  fs::create_directories(broken);
  write_file(broken / "broken-F.Cu.gbr", board_file("broken-F.Cu.gbr"));
  write_file(broken / "blinky.drl", board_file("blinky.drl"));
  watcher.scan();
  watcher.scan();
  EXPECT_EQ(server.jobs().size(), 1u);
  EXPECT_FALSE(fs::exists(broken));
  EXPECT_TRUE(fs::exists(inbox / "refused" / "broken" / "broken-F.Cu.gbr"));
  EXPECT_NE(read_file(inbox / "refused" / "broken.why.txt").find("broken-F.Cu.gbr:7: D42"),
            std::string::npos);

  // A board as one zip file in the inbox.
  write_file(inbox / "zipped.zip", board_file("blinky.zip"));
  watcher.scan();
  watcher.scan();
  ASSERT_EQ(server.jobs().size(), 2u);
  EXPECT_EQ(server.jobs()[0]["name"], "zipped");
  EXPECT_EQ(server.jobs()[0]["input_file"], "board.json");
  EXPECT_FALSE(fs::exists(inbox / "zipped.zip"));
}

// What a shared store (PostgreSQL) keeps of each job: the bytes given to add().
class InputKeepingStore : public SqliteJobStore {
 public:
  using SqliteJobStore::SqliteJobStore;
  int64_t add(const JobRecord& job, const std::string& input) override {
    const int64_t id = SqliteJobStore::add(job, input);
    inputs_[id] = input;
    return id;
  }
  bool keeps_input() const override { return true; }
  std::optional<std::string> input(int64_t id) override {
    const auto it = inputs_.find(id);
    return it == inputs_.end() ? std::nullopt : std::optional<std::string>(it->second);
  }

 private:
  std::map<int64_t, std::string> inputs_;
};

TEST(ServerBoards, AnotherServerPlansTheBoardFromTheStoredBundleAlike) {
  test::TempDir dir;
  DataFolder data(dir.path() / "data");
  InputKeepingStore store(data.database().string());
  JobIntake intake(store, data, {MachineFit{}}, 256 * 1024);
  Submission sub;
  for (const char* f : {"blinky-F.Cu.gbr", "blinky.drl", "blinky-Edge.Cuts.gbr"}) {
    sub.files.push_back(UploadFile{f, board_file(f)});
  }
  const IntakeResult r = intake.submit(sub);
  ASSERT_EQ(r.status, 201) << r.error;
  const JobRecord job = *store.get(r.id);
  const std::optional<std::string> stored = store.input(r.id);
  ASSERT_TRUE(stored);
  // A server sharing the queue has no archive folder for the job: it unpacks the bundle.
  const fs::path other = dir.path() / "other" / job.key;
  restore_job_input(other, job, *stored);
  const fs::path mine = data.job_dir(job.key);
  for (const char* f : {"board.json", "copper.top.gbr", "drill.drl", "outline.gbr"}) {
    EXPECT_EQ(read_file(other / f), read_file(mine / f)) << f;
  }
  const JobPlan again = plan_archived_job(other, job, 297.0, 210.0, true);
  const nlohmann::json planned = nlohmann::json::parse(read_file(mine / "plan.json"));
  EXPECT_EQ(plan_json(again), planned);
  EXPECT_TRUE(fs::exists(other / "plot.svg"));

  // A damaged or hostile bundle is refused before anything is written.
  EXPECT_THROW(unpack_board_bundle("engraver-board 1\n../token 3\nabc\n"), std::runtime_error);
  EXPECT_THROW(unpack_board_bundle(stored->substr(0, stored->size() - 10)), std::runtime_error);
  EXPECT_THROW(unpack_board_bundle("not a bundle"), std::runtime_error);
  const NamedFiles files = unpack_board_bundle(pack_board_bundle({{"drill.drl", "M48\n"}}));
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].second, "M48\n");
}

}  // namespace
}  // namespace host::server
