// The top side's probe area of a double-sided board reaches every cut of its bottom side
// (issue 25, the workshop): the bottom job cuts with the top job's map, kept with the table
// (height_map_flip=table) or flipped with the blank (=blank), and must never leave it. The
// board of the outside tester's report (../shared/samples/pcb/example_board, skipped
// without it) at its 0.04 mm tool and a few others.
#include <gtest/gtest.h>

#include "host/lib/heightmap/job_area.h"
#include "host/lib/heightmap/probe_grid.h"
#include "host/lib/server/board_height_map.h"
#include "host/lib/server/job_planning.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

const fs::path kExampleBoard =
    fs::path(ENGRAVER_SOURCE_DIR) / "../shared/samples/pcb/example_board";

// The job as the intake keeps it (board.json) and as a machine's worker plans it.
struct Intake {
  TempDir dir;
  DataFolder data{dir.path() / "data"};
  SqliteJobStore store{data.database().string()};
  JobIntake intake{store, data, {MachineFit{}}, 64 * 1024 * 1024};

  JobRecord submit(const BoardSettings& board) {
    Submission sub;
    for (const auto& e : fs::directory_iterator(kExampleBoard))
      sub.files.push_back(UploadFile{e.path().filename().string(), read_file(e.path())});
    sub.board = board;
    const IntakeResult r = intake.submit(sub);
    if (r.status != 201) throw std::runtime_error(r.error);
    return *store.get(r.id);
  }
  nlohmann::json manifest(const JobRecord& job) {
    return nlohmann::json::parse(read_file(data.job_dir(job.key) / "board.json"));
  }
  JobPlan plan(const JobRecord& job) {
    return plan_archived_job(data.job_dir(job.key), job, MachineFit{}.work_width_mm,
                             MachineFit{}.work_height_mm, false);
  }
};

// The map the top job's probe makes over its area (flat: only where it lies matters).
heightmap::HeightMap probed_map(const nlohmann::json& manifest) {
  heightmap::GridOptions g;
  g.spacing_mm = manifest.at("probe_spacing_mm").get<double>();
  const heightmap::ProbeGrid grid =
      heightmap::plan_probe_grid(area_of_json(manifest.at("probe_area_mm")), g);
  heightmap::HeightMap map;
  map.origin_x_mm = grid.origin_x_mm;
  map.origin_y_mm = grid.origin_y_mm;
  map.pitch_x_mm = grid.pitch_x_mm;
  map.pitch_y_mm = grid.pitch_y_mm;
  map.rows = grid.rows;
  map.cols = grid.cols;
  map.heights_um.assign(static_cast<size_t>(grid.rows * grid.cols), 0.0);
  return map;
}

TEST(ServerProbeArea, TheTopSidesMapCoversEveryBottomCutInBothFlipModes) {
  if (!fs::exists(kExampleBoard)) GTEST_SKIP() << kExampleBoard << " is not here";
  for (const double tool_mm : {0.04, 0.3}) {
    SCOPED_TRACE(fmt::format("tool {} mm", tool_mm));
    Intake in;
    BoardSettings top;
    top.side = "top";
    top.tool_width_mm = tool_mm;
    top.allow_narrow_gaps = true;
    top.align_holes = "auto";
    top.probe_first = true;
    const JobRecord top_job = in.submit(top);
    const nlohmann::json m = in.manifest(top_job);
    const heightmap::HeightMap map = probed_map(m);
    const double axis_mm = m.at("flip_axis_machine_x_mm").get<double>();
    for (const std::string flip : {"table", "blank"}) {
      BoardSettings bottom = top;
      bottom.side = "bottom";
      bottom.probe_first = false;
      bottom.height_map_from = top_job.id;
      bottom.height_map_flip = flip;
      const JobPlan cut = in.plan(in.submit(bottom));
      EXPECT_NO_THROW(heightmap::refuse_job_outside_map(cut, map_after_flip(map, axis_mm, flip),
                                                        "flip " + flip));
    }
  }
}

}  // namespace
}  // namespace host::server
