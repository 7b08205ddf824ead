// One job, planned the same way whichever way in it takes, with no option given: the server
// (its library: the intake plans and archives, a machine's worker plans the archive again and
// encodes it), `engraver run` and `engraver send` (the binary: their planning lives in the
// CLI), `engraver board` and `engraver points` (the binary), for every kind of input: DXF,
// G-code, a board folder (Gerber copper, outline, Excellon) and an Excellon file alone. A
// default written twice and changed in one place shows here as a different job.
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <nlohmann/json.hpp>  // nlohmann::json

#include <algorithm>   // std::min, std::max
#include <filesystem>  // std::filesystem
#include <fstream>     // std::ifstream, std::ofstream
#include <regex>       // std::regex
#include <sstream>     // std::stringstream
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/probe_grid.h"
#include "host/lib/plan/firmware_points.h"
#include "host/lib/plan/job_defaults.h"
#include "host/lib/server/board_height_map.h"  // area_of_json
#include "host/lib/server/job_planning.h"
#include "host_tests/host/cli/tool_run.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server::test {
namespace {

const std::string kExe = ENGRAVER_EXE;
const fs::path kServerData = fs::path(ENGRAVER_SOURCE_DIR) / "host_tests/host/server/data";

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A program with a plunge, a line, an arc, a run of short moves (fitted) and a drilled hole;
// no feed on the cutting moves, so the planner's default feed applies.
const char kGcode[] =
    "G21\nG90\nG0 Z2\nG0 X10 Y10\nG1 Z-0.1\nG1 X30 Y10\nG2 X30 Y30 I0 J10\n"
    "G1 X29 Y30.2\nG1 X28 Y30.5\nG1 X27 Y30.9\nG1 X26 Y31.4\nG1 X25 Y32\nG1 X10 Y30\n"
    "G1 X10 Y10\nG0 Z2\nG81 X40 Y40 Z-1 R1\nG80\nM2\n";

// What the server sends for a job: planned from its archive as a machine's worker does and
// encoded with the job's options (no controller connected: the reference machine's).
struct EncodedJob {
  JobPlan plan;
  int job_id = -1;
  size_t commands = 0;
  size_t wire_bytes = 0;
};

EncodedJob server_job(const Submission& sub, bool board) {
  TempDir dir;
  DataFolder data(dir.path() / "data");
  SqliteJobStore store(data.database().string());
  JobIntake intake(store, data, {MachineFit{}}, 64 * 1024 * 1024);
  const IntakeResult r = intake.submit(sub);
  EXPECT_EQ(r.status, 201) << r.error;
  EncodedJob e;
  if (r.status != 201) return e;
  const JobRecord job = *store.get(r.id);
  e.plan = plan_archived_job(data.job_dir(job.key), job, MachineFit{}.work_width_mm,
                             MachineFit{}.work_height_mm, false);
  if (board) {
    // The one planned difference: a server's board job starts with a pause naming the first
    // tool (any free machine may take it); `send`/`run` print that tool instead.
    EXPECT_EQ(e.plan.steps.front().kind, PlanStep::kPause);
    e.plan.steps.erase(e.plan.steps.begin());
  }
  const std::vector<QueuedCommand> commands = encode_job(e.plan, encode_options(job));
  e.job_id = job_id_of(commands);
  e.commands = commands.size();
  e.wire_bytes = wire_bytes(commands);
  return e;
}

nlohmann::json read_json(const fs::path& p) {
  return nlohmann::json::parse(read_text(p));
}

// `engraver run INPUT`: the report's job identity.
nlohmann::json run_report(const std::string& input, const std::string& name, const TempDir& out) {
  const auto r = host_tests::run_tool(kExe, "run " + input + " -o " + out.path().string());
  EXPECT_EQ(r.code, 0) << r.err;
  return read_json(out.path() / (name + ".json"));
}

// `engraver send INPUT` to `engraver sim`: the job id it prints. The simulator takes a free
// port (0) and says which: a fixed port could be another test's, and a sleep a race.
int sent_job_id(const std::string& input) {
  const std::string script =
      "'F=$(mktemp); " + kExe + " sim --listen 127.0.0.1:0 2>$F >/dev/null & S=$!; P=; " +
      "for i in $(seq 200); do P=$(sed -n \"s/.* on 127.0.0.1:\\([0-9]*\\) .*/\\1/p\" $F); " +
      "[ -n \"$P\" ] && break; sleep 0.05; done; " + kExe + " send " + input +
      " --to tcp://127.0.0.1:$P; r=$?; kill $S; rm -f $F; exit $r'";
  const auto r = host_tests::run_tool("sh -c", script);
  EXPECT_EQ(r.code, 0) << r.err;
  std::smatch m;
  if (!std::regex_search(r.err, m, std::regex("job id ([0-9]+)"))) {
    ADD_FAILURE() << "no job id in: " << r.err;
    return -2;
  }
  return std::stoi(m[1]);
}

void expect_same_job(const EncodedJob& server, const std::string& input, const std::string& name) {
  TempDir out;
  const nlohmann::json run = run_report(input, name, out);
  EXPECT_EQ(run.value("job_id", -1), server.job_id)
      << "run and the server planned " << input << " differently";
  EXPECT_EQ(run.value("commands", size_t{0}), server.commands);
  EXPECT_EQ(run.value("job_wire_bytes", size_t{0}), server.wire_bytes);
  EXPECT_NEAR(run.value("planned_cut_mm", 0.0), server.plan.cut_length_mm, 1e-6);
  EXPECT_EQ(sent_job_id(input), server.job_id)
      << "send and the server planned " << input << " differently";
}

// `engraver board` writes the same plan as the server's (steps, lengths, extents).
void expect_same_board_report(const EncodedJob& server, const std::string& input,
                              const std::string& name) {
  TempDir out;
  const auto r =
      host_tests::run_tool(kExe, "board " + input + " --no-plot -o " + out.path().string());
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = read_json(out.path() / (name + ".board.json"));
  EXPECT_EQ(j.at("steps").get<size_t>(), server.plan.steps.size());
  EXPECT_NEAR(j.at("cut_length_mm").get<double>(), server.plan.cut_length_mm, 1e-6);
  EXPECT_NEAR(j.at("rapid_length_mm").get<double>(), server.plan.rapid_length_mm, 1e-6);
  EXPECT_NEAR(j.at("extents_mm").at("min")[0].get<double>(), server.plan.extents_mm.min.x(), 1e-6);
  EXPECT_NEAR(j.at("extents_mm").at("max")[1].get<double>(), server.plan.extents_mm.max.y(), 1e-6);
}

// `engraver points` on a board prints the isolation tool centres (files' frame): as many
// curves as the server's isolation contours, spanning the same width and height.
void expect_same_board_points(const EncodedJob& server, const std::string& input) {
  const auto r = host_tests::run_tool(kExe, "points --csv " + input);
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);  // header: tool,tool_name,tool_diameter_um,path,point,x_um,...
  ASSERT_EQ(line.rfind("tool,tool_name,tool_diameter_um,path,point,x_um,y_um", 0), 0u) << line;
  Extents printed;
  int curves = 0;
  while (std::getline(lines, line)) {
    int tool = 0, path = 0, point = 0;
    char name[64] = {};
    double diameter_um = 0, x_um = 0, y_um = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%d,%63[^,],%lf,%d,%d,%lf,%lf", &tool, name, &diameter_um,
                          &path, &point, &x_um, &y_um),
              7)
        << line;
    if (std::string(name).rfind("V-bit", 0) != 0) continue;  // the isolation tool's paths
    curves = std::max(curves, path + 1);
    printed.add(Point2(x_um / 1000, y_um / 1000));
  }
  Extents planned;
  int isolation = 0;
  const int tol_um = static_cast<int>(defaults::kChordToleranceMm * 1000 + 0.5);
  for (const PlannedCurve& c : server.plan.curves) {
    if (c.source.rfind("isolation contour", 0) != 0) continue;
    ++isolation;
    for (const Point2& p : firmware_points_mm(c.spline(), tol_um)) planned.add(p);
  }
  EXPECT_EQ(curves, isolation);
  EXPECT_NEAR(printed.max.x() - printed.min.x(), planned.max.x() - planned.min.x(), 0.002);
  EXPECT_NEAR(printed.max.y() - printed.min.y(), planned.max.y() - planned.min.y(), 0.002);
}

TEST(SamePlan, DxfIsPlannedAlikeByRunSendAndTheServer) {
  const fs::path dxf = fs::path(ENGRAVER_SOURCE_DIR) / "samples/engraver-word.dxf";
  Submission sub;
  sub.name = "engraver-word.dxf";
  sub.content = read_text(dxf);
  expect_same_job(server_job(sub, false), dxf.string(), "engraver-word");
}

TEST(SamePlan, GcodeIsPlannedAlikeByRunSendAndTheServer) {
  TempDir in;
  const fs::path file = in.path() / "square.ngc";
  std::ofstream(file) << kGcode;
  Submission sub;
  sub.name = "square.ngc";
  sub.content = kGcode;
  expect_same_job(server_job(sub, false), file.string(), "square");
}

TEST(SamePlan, BoardFolderIsPlannedAlikeByRunSendBoardPointsAndTheServer) {
  TempDir in;
  const fs::path folder = in.path() / "blinky";
  fs::create_directories(folder);
  Submission sub;
  for (const char* f : {"blinky-F.Cu.gbr", "blinky-Edge.Cuts.gbr", "blinky.drl"}) {
    fs::copy_file(kServerData / f, folder / f);
    sub.files.push_back(UploadFile{f, read_text(kServerData / f)});
  }
  const EncodedJob server = server_job(sub, true);
  expect_same_job(server, folder.string(), "blinky");
  expect_same_board_report(server, folder.string(), "blinky");
  expect_same_board_points(server, folder.string());
}

TEST(SamePlan, ExcellonIsPlannedAlikeByRunSendBoardAndTheServer) {
  const fs::path drl = kServerData / "blinky.drl";
  Submission sub;
  sub.name = "blinky.drl";
  sub.content = read_text(drl);
  const EncodedJob server = server_job(sub, true);
  expect_same_job(server, drl.string(), "blinky");
  expect_same_board_report(server, drl.string(), "blinky");
}

// A double-sided board's top side probes the same grid from `engraver probe` (as `run
// --probe` and `send --probe`) and from the server: the area over both sides' cuts
// (pcb::board_probe_area). ../shared/samples/pcb/example_board; skipped without it.
TEST(SamePlan, ADoubleSidedBoardsProbeAreaIsTheServers) {
  const fs::path board = fs::path(ENGRAVER_SOURCE_DIR) / "../shared/samples/pcb/example_board";
  if (!fs::exists(board)) GTEST_SKIP() << board << " is not here";
  Submission sub;
  for (const auto& e : fs::directory_iterator(board))
    sub.files.push_back(UploadFile{e.path().filename().string(), read_text(e.path())});
  sub.board.side = "top";
  sub.board.tool_width_mm = 0.04;
  sub.board.align_holes = "auto";
  sub.board.probe_first = true;
  TempDir dir;
  DataFolder data(dir.path() / "data");
  SqliteJobStore store(data.database().string());
  JobIntake intake(store, data, {MachineFit{}}, 64 * 1024 * 1024);
  const IntakeResult r = intake.submit(sub);
  ASSERT_EQ(r.status, 201) << r.error;
  const nlohmann::json m = read_json(data.job_dir(store.get(r.id)->key) / "board.json");
  const heightmap::ProbeGrid server =
      heightmap::plan_probe_grid(area_of_json(m.at("probe_area_mm")), heightmap::GridOptions{});

  SimRig sim(false, 0, [] {
    sim::SimOptions o;
    o.surface_um = [](int32_t, int32_t) { return 0; };  // a flat blank: the probe touches
    return o;
  }());
  const fs::path map_file = dir.path() / "top.map.json";
  const auto probed = host_tests::run_tool(
      kExe, "probe " + board.string() + " --side top --tool-width 0.04 --align-holes auto --to " +
                sim.address() + " --height-map " + map_file.string());
  ASSERT_EQ(probed.code, 0) << probed.err;
  const heightmap::HeightMap cli = heightmap::read_height_map_file(map_file.string());
  EXPECT_EQ(cli.rows, server.rows);
  EXPECT_EQ(cli.cols, server.cols);
  EXPECT_NEAR(cli.origin_x_mm, server.origin_x_mm, 1e-6);
  EXPECT_NEAR(cli.origin_y_mm, server.origin_y_mm, 1e-6);
  EXPECT_NEAR(cli.max_x_mm(), server.x_mm(server.cols - 1), 1e-6);
  EXPECT_NEAR(cli.max_y_mm(), server.y_mm(server.rows - 1), 1e-6);
}

}  // namespace
}  // namespace host::server::test
