// Height maps of board jobs (see board_height_map.h).
#include "host/lib/server/board_height_map.h"

#include <fmt/format.h>  // fmt::format

#include <fstream>  // std::ofstream

#include "host/lib/heightmap/job_area.h"    // refuse_job_outside_map
#include "host/lib/heightmap/probe_grid.h"  // plan_probe_grid
#include "host/lib/plot/height_map_plot.h"  // write_height_map_svg

namespace host::server {

const char kHeightMapFile[] = "heightmap.json";
const char kHeightMapMachineFile[] = "heightmap.machine";
const char kHeightMapPicture[] = "heightmap.svg";

nlohmann::json area_json(const heightmap::AreaMm& a) {
  return {a.x0, a.y0, a.x1, a.y1};
}

heightmap::AreaMm area_of_json(const nlohmann::json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>(),
          j.at(3).get<double>()};
}

heightmap::HeightMap map_after_flip(const heightmap::HeightMap& top, double flip_axis_x_mm,
                                    const std::string& flip) {
  if (flip == "table") return top;
  if (flip != "blank")
    throw heightmap::HeightMapError("height_map_flip '" + flip + "': table or blank");
  heightmap::HeightMap m = top;
  const double a = flip_axis_x_mm;
  // Column c of the new grid lies at 2a - x(cols - 1 - c) of the old one.
  m.origin_x_mm = 2 * a - top.max_x_mm();
  const double zero_um = top.interpolate_um(2 * a, 0.0);
  for (int row = 0; row < top.rows; ++row) {
    for (int col = 0; col < top.cols; ++col) {
      m.heights_um[row * m.cols + col] = -(top.height_um(row, top.cols - 1 - col) - zero_um);
    }
  }
  heightmap::validate(m, "the flipped map");
  return m;
}

std::string map_probed_on(const std::filesystem::path& job_dir) {
  std::error_code ec;
  return std::filesystem::exists(job_dir / kHeightMapMachineFile, ec)
             ? read_file(job_dir / kHeightMapMachineFile)
             : std::string();
}

void keep_height_map(const std::filesystem::path& job_dir, const heightmap::HeightMap& map,
                     const std::string& title, const std::string& machine) {
  // The machine first: a queue that sees the map sees whose it is (map_source.h).
  std::ofstream(job_dir / kHeightMapMachineFile, std::ios::binary | std::ios::trunc) << machine;
  write_height_map_svg(map, title, (job_dir / kHeightMapPicture).string());
  heightmap::write_height_map_file(map, (job_dir / kHeightMapFile).string());
}

std::string source_ended_text(const JobRecord& from) {
  if (!is_final(from.state) || from.state == JobState::kCompleted) return "";
  return fmt::format("job {} ended {} without a height map{}", from.id, state_name(from.state),
                     from.message.empty() ? "" : " (" + from.message + ")");
}

namespace {

// The source job's map as it lies in its archive; throws why there is none to use.
heightmap::HeightMap source_map(const JobRecord& from, const std::filesystem::path& from_dir,
                                const std::string& machine) {
  if (!std::filesystem::exists(from_dir / kHeightMapFile)) {
    const std::string ended = source_ended_text(from);
    if (!ended.empty()) throw std::runtime_error(ended);
    throw std::runtime_error(fmt::format(
        "job {} has no height map (here): it was not probed, or not yet, or on a server "
        "whose archive this one does not share",
        from.id));
  }
  const std::string from_machine = map_probed_on(from_dir);
  if (from_machine != machine) {
    throw std::runtime_error(fmt::format(
        "job {}'s map was probed on machine '{}', this job runs on '{}': a map belongs to "
        "the machine whose table it was probed on (upload this job with probe_first=1, or "
        "run it there)",
        from.id, from_machine, machine));
  }
  return heightmap::read_height_map_file((from_dir / kHeightMapFile).string());
}

double flip_axis_of(const JobRecord& from, const std::filesystem::path& from_dir) {
  const nlohmann::json m = nlohmann::json::parse(read_file(from_dir / kBoardManifest));
  if (!m.contains("flip_axis_machine_x_mm")) {
    throw std::runtime_error(fmt::format(
        "job {} has no alignment holes: no flip axis to mirror its map about", from.id));
  }
  return m["flip_axis_machine_x_mm"].get<double>();
}

}  // namespace

heightmap::HeightMap map_from_source_job(JobStore& store, const DataFolder& data,
                                         const std::filesystem::path& job_dir,
                                         const std::string& job_name, const BoardSettings& board,
                                         const std::string& machine, const JobPlan& plan,
                                         const std::function<void(const std::string&)>& note) {
  const std::optional<JobRecord> from = store.get(board.height_map_from);
  if (!from) throw std::runtime_error(fmt::format("no job {}", board.height_map_from));
  const std::filesystem::path from_dir = data.job_dir(from->key);
  const heightmap::HeightMap top = source_map(*from, from_dir, machine);
  const double axis_mm = board.height_map_flip == "blank" ? flip_axis_of(*from, from_dir) : 0.0;
  const heightmap::HeightMap map = map_after_flip(top, axis_mm, board.height_map_flip);
  // Checked before it is kept: a job's map in its archive is one it was cut with.
  heightmap::refuse_job_outside_map(plan, map, fmt::format("the height map of job {}", from->id));
  note(fmt::format("height map of job {} ({} x {} points, flip {})", from->id, map.rows, map.cols,
                   board.height_map_flip));
  keep_height_map(
      job_dir, map,
      fmt::format("{} (the map of job {}, flip {})", job_name, from->id, board.height_map_flip),
      machine);
  return map;
}

namespace {

std::string check_probe_spacing(const BoardSettings& board, const PlannedBoard& planned) {
  if (!planned.manifest.contains("probe_area_mm")) return "probe_first: the job cuts nothing";
  heightmap::GridOptions grid;  // as the workshop probes it (probe_board_blank)
  grid.spacing_mm = board.probe_spacing_mm;
  try {
    heightmap::plan_probe_grid(area_of_json(planned.manifest["probe_area_mm"]), grid);
  } catch (const heightmap::GridError& e) {
    return std::string("probe_spacing_mm: ") + e.what();
  }
  return "";
}

std::string check_source_map(JobStore& store, const DataFolder& data, const BoardSettings& board,
                             const PlannedBoard& planned) {
  const std::optional<JobRecord> from = store.get(board.height_map_from);
  if (!from) return "";  // refused before planning
  const std::filesystem::path dir = data.job_dir(from->key);
  double axis_mm = 0;
  try {
    const nlohmann::json m = nlohmann::json::parse(read_file(dir / kBoardManifest));
    if (board.height_map_flip == "blank" && !m.contains("flip_axis_machine_x_mm")) {
      return fmt::format(
          "height_map_flip=blank: job {} has no alignment holes (align_holes), so no flip axis "
          "to mirror its map about: give its map with height_map_flip=table, or probe this job "
          "(probe_first=1)",
          from->id);
    }
    axis_mm = m.value("flip_axis_machine_x_mm", 0.0);
  } catch (const std::exception&) {
    return "";  // another server's upload not in this archive: checked when it runs
  }
  std::error_code ec;
  if (!std::filesystem::exists(dir / kHeightMapFile, ec)) return "";  // checked when it runs
  try {
    const heightmap::HeightMap top =
        heightmap::read_height_map_file((dir / kHeightMapFile).string());
    heightmap::refuse_job_outside_map(planned.job.plan,
                                      map_after_flip(top, axis_mm, board.height_map_flip),
                                      fmt::format("the height map of job {}", from->id));
  } catch (const heightmap::HeightMapError& e) {
    // At upload nothing is started but nothing is queued either.
    std::string why = server_map_words(e.what());
    const std::string started = "the job was not started";
    const size_t at = why.find(started);
    if (at != std::string::npos) why.replace(at, started.size(), "the job was not queued");
    return "height_map_from: " + why;
  }
  return "";
}

}  // namespace

std::string check_height_map_fields(JobStore& store, const DataFolder& data,
                                    const BoardSettings& board, const PlannedBoard& planned) {
  if (board.probe_first) return check_probe_spacing(board, planned);
  if (board.height_map_from != 0) return check_source_map(store, data, board, planned);
  return "";
}

std::string server_map_words(std::string text) {
  const std::pair<const char*, const char*> words[] = {
      {"probe again over this job (--probe)",
       "probe again over this job (upload it with probe_first=1)"},
      {"clean the blank there, or raise --outlier-limit if the blank is that uneven",
       "clean the blank there and requeue the job (a blank that uneven is cut without "
       "probe_first)"}};
  for (const auto& [from, to] : words) {
    const size_t at = text.find(from);
    if (at != std::string::npos) text.replace(at, std::string(from).size(), to);
  }
  return text;
}

}  // namespace host::server
