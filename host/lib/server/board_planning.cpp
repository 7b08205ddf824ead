// Board jobs for the server (see board_planning.h).
#include "host/lib/server/board_planning.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::min
#include <cmath>      // std::hypot, std::lround

#include "firmware/config/machine_config.h"
#include "host/lib/drawing/drawing.h"
#include "host/lib/pcb/board_args.h"   // resolve_board_options, is_board_side
#include "host/lib/pcb/board_check.h"  // refuse_copper_hits
#include "host/lib/pcb/board_files.h"
#include "host/lib/pcb/board_probe_area.h"
#include "host/lib/pcb/cutout.h"
#include "host/lib/server/board_height_map.h"
#include "host/lib/server/data_folder.h"

namespace host::server {

namespace fs = std::filesystem;
using pcb::LayerKind;

const char kBoardManifest[] = "board.json";

namespace {

const char* const kDrillNames[] = {"drill.drl", "drill.b.drl", "drill.c.drl", "drill.d.drl"};
const size_t kMaxDrillFiles = sizeof(kDrillNames) / sizeof(kDrillNames[0]);

const char* kind_key(LayerKind k) {
  return pcb::layer_kind_key(k);
}

LayerKind kind_from_key(const std::string& key) {
  for (LayerKind k :
       {LayerKind::kCopperTop, LayerKind::kCopperBottom, LayerKind::kOutline, LayerKind::kDrill}) {
    if (key == kind_key(k)) return k;
  }
  throw std::runtime_error("board.json: unknown layer kind '" + key + "'");
}

// The command line's words in the planner's advice, as the server's fields.
std::string server_words(std::string text);

// The server's board settings through the CLI's resolver (pcb/board_args.h): one place says
// what a board job is planned with.
pcb::BoardOptions board_options(const std::string& side, const BoardSettings& b,
                                const JobPlanSettings& s, const pcb::BoardFileSet& set,
                                double work_w_mm, double work_h_mm) {
  pcb::BoardArgs a;
  a.side = side;
  a.isolation.tool_width_mm = b.tool_width_mm;
  a.isolation.passes = b.passes;
  a.isolation.clearing_tool_mm = b.clearing_tool_mm;
  a.isolation.narrow_passes = b.narrow_passes;
  a.allow_narrow_gaps = b.allow_narrow_gaps;
  a.alignment.holes = b.align_holes;
  a.alignment.diameter_mm = b.align_diameter_mm;
  a.alignment.depth_mm = b.align_depth_mm;
  a.alignment.measured_mm = b.align_measured_mm;
  pcb::BoardMachine m;
  m.margin_mm = s.margin_mm;
  m.work_w_mm = work_w_mm;
  m.work_h_mm = work_h_mm;
  try {
    return pcb::resolve_board_options(a, m, set, "");
  } catch (const pcb::BoardArgsError& e) {
    throw PlanError(server_words(e.what()));
  }
}

// The command line's words in the planner's advice, as the server's fields.
std::string server_words(std::string text) {
  const std::pair<const char*, const char*> words[] = {
      {"--tool-width", "tool_width_mm"},
      {"--allow-narrow-gaps", "allow_narrow_gaps=1"},
      {"--clearing-tool", "clearing_tool_mm"},
      {"--narrow-passes", "narrow_passes"},
      {"--passes", "passes"},
      {"--align-holes", "align_holes"},
      {"--align-measured", "align_measured"}};
  for (const auto& [from, to] : words) {
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at))
      text.replace(at, std::string(from).size(), to);
  }
  return text;
}

// The board planner's errors as the intake's: what cannot run is refused with the message.
// A workshop job goes to whichever machine is free, so unlike `engraver send` it starts
// with a pause (#P) naming the first tool: the operator mounts it and confirms.
// measured_mm: X1 Y1 X2 Y2 of the alignment holes after the flip (as `board
// --align-measured`): planned once for where they should be, then turned and shifted onto them.
pcb::BoardJob plan(const pcb::BoardFileSet& set, pcb::BoardOptions o,
                   const JobPlanSettings& settings, const std::vector<double>& measured_mm) {
  pcb::PcbLayer drill;
  pcb::BoardJob job;
  try {
    const pcb::BoardLayers layers = set.layers(&drill);
    if (measured_mm.size() == 4) {
      if (!o.alignment.enabled) throw PlanError("align_measured needs the job's align_holes");
      const pcb::BoardJob nominal = pcb::plan_board(layers, o);
      const Point2 expected[2] = {nominal.alignment_holes_mm.at(0),
                                  nominal.alignment_holes_mm.at(1)};
      const Point2 measured[2] = {Point2(measured_mm[0], measured_mm[1]),
                                  Point2(measured_mm[2], measured_mm[3])};
      o.alignment.placement = pcb::measured_alignment(expected, measured);
    }
    job = pcb::plan_board(layers, o);
  } catch (const pcb::CutoutError& e) {
    throw PlanError(e.what());
  } catch (const PlanError& e) {
    throw PlanError(server_words(e.what()));
  }
  // A job that would cut copper is refused with the places (a PlanError): the controller's
  // points at the chord tolerance the job is sent with (encode_options()).
  const double tol_mm = std::min(settings.tol_mm, pcb::kBoardChordToleranceMm);
  pcb::refuse_copper_hits(
      pcb::check_controller_isolation(job, o, static_cast<int>(std::lround(tol_mm * 1000))),
      fmt::format("the controller's points at {} mm chords", tol_mm));
  if (!job.report.first_tool.empty()) {
    PlanStep mount;
    mount.kind = PlanStep::kPause;
    mount.set_text(job.report.first_tool);
    job.plan.steps.insert(job.plan.steps.begin(), mount);
  }
  return job;
}

}  // namespace

bool is_board_job(const JobRecord& job) {
  return job.input_file == kBoardManifest;
}

std::string check_board_settings(const BoardSettings& s) {
  using namespace defaults;
  if (!s.side.empty() && !pcb::is_board_side(s.side)) return "side must be top or bottom";
  const struct {
    const char* name;
    double value;
    Range range;
  } numbers[] = {{"tool_width_mm", s.tool_width_mm, kToolWidthRangeMm},
                 {"passes", double(s.passes), kPassesRange},
                 {"clearing_tool_mm", s.clearing_tool_mm, kClearingToolRangeMm},
                 {"narrow_passes", double(s.narrow_passes), kPassesRange},
                 {"align_diameter_mm", s.align_diameter_mm, kAlignDiameterRangeMm},
                 {"align_depth_mm", s.align_depth_mm, kAlignDepthRangeMm}};
  for (const auto& n : numbers) {
    if (!n.range.holds(n.value))
      return fmt::format("{} must be {} .. {}", n.name, n.range.min, n.range.max);
  }
  if (s.clearing_tool_mm > 0 && s.clearing_tool_mm <= s.tool_width_mm)
    return "clearing_tool_mm must be wider than tool_width_mm (0: no clearing tool)";
  if (s.clearing_tool_mm == 0 && s.narrow_passes != 1)
    return "narrow_passes goes with a clearing tool (clearing_tool_mm)";
  std::vector<Point2> holes;
  if (!s.align_holes.empty()) {
    const std::string why = parse_align_holes(s.align_holes, &holes);
    if (!why.empty()) return why;
  }
  if (!s.align_measured_mm.empty() && s.align_measured_mm.size() != 4)
    return "align_measured takes X1,Y1,X2,Y2 (mm, where holes 1 and 2 were found)";
  if (!s.align_measured_mm.empty() && s.align_holes.empty())
    return "align_measured needs the job's align_holes";
  if (!(s.probe_spacing_mm >= heightmap::kMinPitchMm &&
        s.probe_spacing_mm <= heightmap::kMaxPitchMm))
    return fmt::format("probe_spacing_mm must be {} .. {}", heightmap::kMinPitchMm,
                       heightmap::kMaxPitchMm);
  if (s.probe_first && s.height_map_from != 0)
    return "probe_first and height_map_from exclude each other (probe, or use another job's map)";
  if (s.height_map_from < 0) return "height_map_from must be a job id";
  if (s.height_map_flip != "table" && s.height_map_flip != "blank")
    return "height_map_flip must be table or blank";
  return "";
}

std::string parse_align_holes(const std::string& text, std::vector<Point2>* holes_file_mm) {
  return server_words(pcb::parse_align_holes(text, holes_file_mm));
}

bool is_pcb_upload(const UploadFile& file) {
  return pcb::board_file_format(file.name, file.content) != pcb::PcbFileFormat::kNone;
}

namespace {

// The upload's layers as read: the planner's set, the archive's files under the server's names,
// what the manifest lists of them and the notes (files left out, the readers' warnings).
struct UploadLayers {
  pcb::BoardFileSet set;
  NamedFiles files;
  nlohmann::json listed = nlohmann::json::array();
  nlohmann::json notes = nlohmann::json::array();
};

// Reads each file into its layer, under its server name; throws ImportError / PlanError.
UploadLayers read_upload_layers(const std::vector<UploadFile>& files, bool skip_other,
                                const std::string& board_name) {
  UploadLayers u;
  pcb::BoardFileSet& set = u.set;
  nlohmann::json& listed = u.listed;
  nlohmann::json& notes = u.notes;
  NamedFiles& layer_files = u.files;
  for (const UploadFile& f : files) {
    if (!is_pcb_upload(f)) {
      if (skip_other) {
        notes.push_back(f.name + ": not a Gerber or Excellon file: left out");
        continue;
      }
      throw ImportError(f.name +
                        ": not a Gerber or Excellon file (a board takes copper, drill and "
                        "outline files only)");
    }
    pcb::PcbLayer layer;
    try {
      layer = pcb::read_board_text(f.content, f.name, LayerKind::kUnknown);
    } catch (const pcb::PcbReadError& e) {
      throw ImportError(e.what());
    }
    for (const std::string& n : layer.notes)  // the reader's warnings, as the CLI prints them
      if (n.find("warning: ") != std::string::npos) notes.push_back(f.name + ": " + n);
    const LayerKind kind = layer.kind;
    std::string file;
    switch (kind) {
      case LayerKind::kCopperTop:
        file = "copper.top.gbr";
        break;
      case LayerKind::kCopperBottom:
        file = "copper.bot.gbr";
        break;
      case LayerKind::kOutline:
        file = "outline.gbr";
        break;
      case LayerKind::kDrill:
        if (set.drill.size() >= kMaxDrillFiles)
          throw PlanError(fmt::format("{}: more than {} drill files", f.name, kMaxDrillFiles));
        file = kDrillNames[set.drill.size()];
        break;
      case LayerKind::kUnknown:
        notes.push_back(f.name +
                        ": not a copper, drill or outline layer (by its X2 attributes or its "
                        "name): left out");
        continue;
    }
    set.add(std::move(layer));
    for (const auto& [taken, bytes] : layer_files) {
      if (taken == file) {
        throw PlanError(fmt::format("{}: a second {} layer (one board takes one of each)", f.name,
                                    pcb::layer_kind_name(kind)));
      }
    }
    layer_files.emplace_back(file, f.content);
    listed.push_back(
        {{"file", file}, {"kind", kind_key(kind)}, {"name", f.name}, {"bytes", f.content.size()}});
  }
  if (set.empty()) {
    std::string msg = board_name +
                      ": no copper, drill or outline layer among the files; a Gerber says "
                      "which it is by its X2 attributes or its name (KiCad's -F.Cu, -B.Cu, "
                      "-Edge.Cuts; .GTL, .GBL, .GKO; .DRL for Excellon)";
    for (const auto& n : notes) msg += "\n  " + n.get<std::string>();
    throw ImportError(msg);
  }
  return u;
}

// The side to cut: the one asked for, else the one whose copper is given; the other side's
// copper alone is refused (the job would drill and cut out, and never isolate).
std::string board_side(const BoardSettings& board, const pcb::BoardFileSet& set,
                       const std::string& board_name) {
  std::string side = board.side;
  if (side.empty()) side = pcb::side_of_copper(set);
  const bool top = side == "top";
  if ((top ? set.copper_top : set.copper_bottom).empty() &&
      !(top ? set.copper_bottom : set.copper_top).empty()) {
    throw PlanError(fmt::format(
        "{}: side={} but the files hold {} copper only: ask for side={}, or add the {} copper",
        board_name, side, top ? "bottom" : "top", top ? "bottom" : "top", side));
  }
  return side;
}

// The manifest's report: what the planner made of the board.
nlohmann::json report_json(const pcb::BoardReport& r, const nlohmann::json& gaps) {
  return {{"first_tool", r.first_tool},
          {"islands", r.islands},
          {"isolation_contours", r.isolation_contours},
          {"isolation_length_mm", r.isolation_length_mm},
          {"holes", r.holes},
          {"holes_on_copper", r.holes_on_copper},
          {"slots", r.slots},
          {"drill_tools", r.drill_tools},
          {"tabs", r.tabs},
          {"cutout_length_mm", r.cutout_length_mm},
          {"tool_changes", r.tool_changes},
          {"narrow_gaps", gaps}};
}

}  // namespace

PlannedBoard plan_board_upload(const std::vector<UploadFile>& files, bool skip_other,
                               const std::string& board_name, const BoardSettings& board,
                               const JobPlanSettings& settings, double work_w_mm,
                               double work_h_mm) {
  UploadLayers layers = read_upload_layers(files, skip_other, board_name);
  const pcb::BoardFileSet& set = layers.set;
  const nlohmann::json& listed = layers.listed;
  nlohmann::json& notes = layers.notes;
  const NamedFiles& layer_files = layers.files;
  const std::string side = board_side(board, set, board_name);
  PlannedBoard out;
  const pcb::BoardOptions options = board_options(side, board, settings, set, work_w_mm, work_h_mm);
  out.job = plan(set, options, settings, board.align_measured_mm);
  const pcb::BoardReport& r = out.job.report;
  for (const std::string& n : r.notes) notes.push_back(n);  // e.g. an empty outline left out
  nlohmann::json gaps = nlohmann::json::array();
  for (const pcb::NarrowGap& g : r.narrow_gaps)
    gaps.push_back(pcb::describe_gap(g, options.isolation));
  out.manifest = {{"board", board_name},
                  {"side", side},
                  {"tool_width_mm", board.tool_width_mm},
                  {"allow_narrow_gaps", board.allow_narrow_gaps},
                  {"passes", board.passes},
                  {"clearing_tool_mm", board.clearing_tool_mm},
                  {"narrow_passes", board.narrow_passes},
                  {"align_holes", board.align_holes},
                  {"align_diameter_mm", board.align_diameter_mm},
                  {"align_depth_mm", board.align_depth_mm},
                  {"align_measured_mm", board.align_measured_mm},
                  {"probe_first", board.probe_first},
                  {"probe_spacing_mm", board.probe_spacing_mm},
                  {"height_map_from", board.height_map_from},
                  {"height_map_flip", board.height_map_flip},
                  {"files", listed},
                  {"notes", notes},
                  {"report", report_json(r, gaps)}};
  // Where a probe-first job probes; where the bottom side's job finds the flip axis.
  pcb::PcbLayer drill;  // the layers again: the bottom side is planned from them too
  if (const std::optional<heightmap::AreaMm> area =
          pcb::board_probe_area(set.layers(&drill), options, out.job))
    out.manifest["probe_area_mm"] = area_json(*area);
  if (!out.job.alignment_holes_mm.empty()) {
    out.manifest["flip_axis_machine_x_mm"] = pcb::flip_axis_machine_x_mm(out.job);
    // Where the pins stand (machine frame, hole 1 first): what align_measured is measured
    // against after the flip.
    nlohmann::json holes = nlohmann::json::array();
    for (const Point2& h : out.job.alignment_holes_mm) holes.push_back({h.x(), h.y()});
    out.manifest["alignment_holes_mm"] = holes;
  }
  out.files.emplace_back(
      kBoardManifest,
      out.manifest.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  out.files.insert(out.files.end(), layer_files.begin(), layer_files.end());
  return out;
}

BoardSettings board_settings_of(const nlohmann::json& m) {
  // Manifests written before a field existed plan as they did then.
  BoardSettings b;
  b.side = m.value("side", "");
  b.tool_width_mm = m.at("tool_width_mm").get<double>();
  b.allow_narrow_gaps = m.value("allow_narrow_gaps", false);
  b.passes = m.value("passes", defaults::kPasses);
  b.clearing_tool_mm = m.value("clearing_tool_mm", 0.0);
  b.narrow_passes = m.value("narrow_passes", 1);
  b.align_holes = m.value("align_holes", "");
  b.align_diameter_mm = m.value("align_diameter_mm", defaults::kAlignDiameterMm);
  b.align_depth_mm = m.value("align_depth_mm", defaults::kAlignDepthMm);
  b.align_measured_mm = m.value("align_measured_mm", std::vector<double>{});
  b.probe_first = m.value("probe_first", false);
  b.probe_spacing_mm = m.value("probe_spacing_mm", 10.0);
  b.height_map_from = m.value("height_map_from", int64_t{0});
  b.height_map_flip = m.value("height_map_flip", "table");
  return b;
}

BoardSettings read_board_settings(const fs::path& dir) {
  try {
    return board_settings_of(nlohmann::json::parse(read_file(dir / kBoardManifest)));
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error((dir / kBoardManifest).string() + ": damaged: " + e.what());
  }
}

pcb::BoardJob plan_board_folder(const fs::path& dir, const JobPlanSettings& settings,
                                double work_w_mm, double work_h_mm) {
  nlohmann::json m;
  try {
    m = nlohmann::json::parse(read_file(dir / kBoardManifest));
    pcb::BoardFileSet set;
    for (const nlohmann::json& f : m.at("files")) {
      const std::string file = f.at("file").get<std::string>();
      if (!is_archive_file(file) || file == kBoardManifest)
        throw std::runtime_error("board.json: unexpected file " + file);
      const LayerKind kind = kind_from_key(f.at("kind").get<std::string>());
      try {
        set.add(pcb::read_board_text(read_file(dir / file), f.at("name").get<std::string>(), kind));
      } catch (const pcb::PcbReadError& e) {
        throw ImportError(e.what());
      }
    }
    const BoardSettings b = board_settings_of(m);
    return plan(
        set, board_options(m.at("side").get<std::string>(), b, settings, set, work_w_mm, work_h_mm),
        settings, b.align_measured_mm);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error((dir / kBoardManifest).string() + ": damaged: " + e.what());
  }
}

}  // namespace host::server
