// `engraver info` (what a drawing holds) and `engraver points` (the points the firmware
// core generates for each curve).
#include <CLI/CLI.hpp>  // CLI::App

#include <iomanip>            // std::setprecision
#include <iostream>           // std::cout
#include <nlohmann/json.hpp>  // nlohmann::json

#include "host/cli/board_cli.h"  // PCB input: isolation tool centres
#include "host/cli/command_registry.h"
#include "host/cli/drawing_read.h"
#include "host/cli/exit_codes.h"
#include "host/cli/pcb_info.h"
#include "host/cli/terminal_text.h"
#include "host/lib/commands/info_command.h"
#include "host/lib/drawing/drawing.h"
#include "host/lib/plan/job_defaults.h"
#include "host/lib/progress/progress_meter.h"

namespace host::cli {

namespace {

struct InfoArgs {
  std::string file;
  bool json = false;
};

struct PointsArgs {
  std::string file;
  double tol_mm = defaults::kChordToleranceMm;
  bool csv = false;
  BoardArgs board;  // PCB input: the job `board` plans
};

void run_info(const InfoArgs& a) {
  if (print_board_folder_info_if_folder(a.file, a.json)) return;  // a board folder
  if (print_pcb_info_if_pcb(a.file, a.json)) return;              // Gerber, Excellon
  const Drawing d = read_drawing_reporting(a.file);
  if (a.json) {
    std::cout << commands::drawing_info_json(d).dump(2, ' ', false,
                                                     nlohmann::json::error_handler_t::replace)
              << "\n";
  } else {
    // Names and messages quote the file: shown terminal-safe.
    std::cout << printable(commands::drawing_info_text(d));
  }
}

// The board options on a drawing are refused rather than ignored.
void refuse_board_options_for_drawings(const CLI::App& cmd, const std::string& file) {
  if (is_pcb_input(file)) return;
  for (const CLI::Option* o : cmd.get_options()) {
    if (o->count() > 0 && o->get_group() == kBoardOptionsGroup)
      throw CLI::ValidationError(o->get_name() +
                                 " is for PCB files (Gerber, Excellon, a board folder), not "
                                 "drawings");
  }
}

void run_points(const PointsArgs& a) {
  const int tol = commands::points_tolerance_um(a.tol_mm);
  if (print_board_points_if_pcb(a.file, a.board, a.tol_mm, a.csv)) return;  // tool centres
  const Drawing d = read_drawing_reporting(a.file);
  for (const std::string& w : d.warnings) std::cerr << "warning: " << printable(w) << "\n";
  std::cout << std::fixed << std::setprecision(3);
  if (a.csv) std::cout << "curve,x_mm,y_mm\n";
  ProgressMeter progress("points", "curves", std::cerr, ProgressMeter::for_stderr());
  for (size_t i = 0; i < d.curves.size(); ++i) {
    progress.update(i, d.curves.size());
    const std::vector<Point2> pts = commands::curve_points(d, i, tol);
    if (!a.csv) {
      std::cout << "# curve " << i << ": " << printable(d.curves[i].source) << ": " << pts.size()
                << " points (x_mm y_mm)\n";
    }
    for (const Point2& p : pts) {
      if (a.csv) {
        std::cout << i << "," << p.x() << "," << p.y() << "\n";
      } else {
        std::cout << p.x() << " " << p.y() << "\n";
      }
    }
  }
  progress.update(d.curves.size(), d.curves.size());
}

void add_drawing_commands(CLI::App& app) {
  auto info_args = std::make_shared<InfoArgs>();
  CLI::App* info = app.add_subcommand(
      "info",
      "Show what a drawing holds: entities by type, curves (degree, rational, knots, "
      "control points), extents, units and the problems found; of a Gerber or Excellon file, "
      "its layer, apertures or tools, polygons and holes; of a board folder, which file is "
      "taken for which layer (as `board` reads it; not its subfolders) and which are left "
      "out and why, and each one's summary");
  info->add_option("FILE", info_args->file,
                   "drawing (DXF, G-code) or PCB file (Gerber, Excellon, a board folder)")
      ->required();
  info->add_flag("--json", info_args->json, "print JSON instead of text");
  info->footer(
      "Examples:\n"
      "  engraver info samples/engraver-word.dxf\n"
      "  engraver info --json board_back.ngc > board_back.json\n"
      "  engraver info board-F.Cu.gbr\n"
      "  engraver info board/\n"
      "Exit codes: 0 shown; 2 bad option, or the file cannot be read or imported (the message "
      "names the file and the place in it).");
  info->callback([info_args]() { run_info(*info_args); });

  auto points_args = std::make_shared<PointsArgs>();
  CLI::App* points =
      app.add_subcommand("points",
                         "Print the points the firmware's point generator produces for each curve "
                         "(drawing frame, mm); for PCB files, every tool-centre path of the board "
                         "job, tool by tool (files' frame, um)");
  points
      ->add_option("FILE", points_args->file,
                   "drawing (DXF, G-code) or PCB files (Gerber, Excellon, a board folder)")
      ->required();
  points->add_option("--tol", points_args->tol_mm, "chord tolerance in mm")->capture_default_str();
  points->add_flag("--csv", points_args->csv,
                   "CSV: header, then curve,x_mm,y_mm rows (PCB files: tool,tool_name,"
                   "tool_diameter_um,path,point,x_um,y_um,z_um)");
  add_board_options(points, &points_args->board);
  points->footer(
      "Examples:\n"
      "  engraver points samples/engraver-word.dxf --tol 0.005 --csv > points.csv\n"
      "  engraver points board_outline.ngc --tol 0.01\n"
      "  engraver points board/ --side bottom --tool-width 0.1 --passes 3 --csv > paths.csv\n"
      "Exit codes: 0 printed; 1 a curve the firmware cannot hold, or a board's copper refused "
      "(narrow gaps, the work area); 2 bad option, or the file "
      "cannot be read or imported.");
  points->callback([points, points_args]() {
    refuse_board_options_for_drawings(*points, points_args->file);
    if (is_pcb_input(points_args->file)) refuse_board_option_combinations(points_args->board);
    run_points(*points_args);
  });
}

const CommandRegistrar registrar("drawing", {"info", "points"}, add_drawing_commands);

}  // namespace

}  // namespace host::cli
