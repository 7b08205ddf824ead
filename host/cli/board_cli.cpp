// `engraver board` and the PCB hooks of `points`, `run` and `send` (see board_cli.h): the
// options bound to host/lib/commands' functions, and what they say printed.
#include "host/cli/board_cli.h"

#include <iomanip>   // std::setprecision
#include <iostream>  // std::cout, std::cerr

#include "host/cli/command_registry.h"
#include "host/cli/exit_codes.h"
#include "host/cli/option_ranges.h"  // output_folder
#include "host/cli/terminal_text.h"
#include "host/lib/commands/board_command.h"

namespace host::cli {

namespace {

// `engraver board`'s options: the command's, and the work area as the two numbers given.
struct BoardCommand {
  commands::BoardCommandOptions run;
  std::vector<double> work_mm{defaults::work_width_mm(), defaults::work_height_mm()};
  bool json = false;
  bool no_check = false;
  bool no_plot = false;
  bool png = false;
};

void run_board(const BoardCommand& a) {
  refuse_board_option_combinations(a.run.board);
  commands::BoardCommandOptions o = a.run;
  o.machine.work_w_mm = a.work_mm[0];
  o.machine.work_h_mm = a.work_mm[1];
  o.check = !a.no_check;
  o.plot = !a.no_plot;
  o.png = a.png;
  commands::BoardResult r = commands::run_board(o, stderr_log());
  const nlohmann::json report = commands::board_report_json(o, r);
  commands::write_board_outputs(o, report, &r);
  if (a.json) {
    std::cout << report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  } else {
    std::cout << commands::board_report_text(o, r);
  }
  commands::refuse_failed_board(r);
}

void add_board_command(CLI::App& app) {
  auto a = std::make_shared<BoardCommand>();
  CLI::App* cmd = app.add_subcommand(
      "board",
      "Plan a whole PCB (copper, drill and outline files, each optional): isolation, drilling "
      "with tool changes, cut-out with tabs; check it, plot it, report it");
  cmd->add_option("FILES", a->run.files,
                  "Gerber/Excellon files or a directory of them (its subfolders are not "
                  "searched; one of its copper, drill or outline files unreadable refuses it); "
                  "kinds from X2 attributes or names");
  cmd->add_option("--top", a->run.top, "top copper Gerber");
  cmd->add_option("--bottom", a->run.bottom, "bottom copper Gerber");
  cmd->add_option("--drill", a->run.drills, "Excellon drill file (may be given twice: PTH, NPTH)");
  cmd->add_option("--outline", a->run.outline, "board outline (Edge.Cuts, profile) Gerber");
  add_board_options(cmd, &a->run.board);
  cmd->add_option("--feed", a->run.machine.feed_mm_s, "isolation feed, mm/s")
      ->capture_default_str();
  cmd->add_option("--z-up", a->run.machine.z_up_mm, "travel height, mm")->capture_default_str();
  cmd->add_option("--margin", a->run.machine.margin_mm, "job corner from the zero, mm")
      ->capture_default_str();
  cmd->add_option("--work", a->work_mm, "work area W H in mm (default A4)")->expected(2);
  cmd->add_flag("--wire-bytes", a->run.wire_bytes,
                "also encode the isolation as #K frames, #D frames and G1 lines and report "
                "their bytes (docs/performance.md)");
  cmd->add_option("--tol", a->run.tol_mm, "chord tolerance for the G1 comparison, mm")
      ->capture_default_str();
  cmd->add_option("-o,--outdir", a->run.outdir, "where NAME.board.svg/.json (and .png) go")
      ->check(output_folder())
      ->capture_default_str();
  cmd->add_flag("--json", a->json, "print the report as JSON");
  cmd->add_flag("--no-check", a->no_check, "skip the geometric isolation check");
  CLI::Option* no_plot = cmd->add_flag("--no-plot", a->no_plot, "write no plot");
  cmd->add_flag("--png", a->png, "also write the plot as NAME.board.png (1400 px wide)")
      ->excludes(no_plot);
  cmd->footer(
      "Example: engraver board board-F.Cu.gbr board-PTH.drl board-Edge.Cuts.gbr -o out\n"
      "         engraver board --side bottom board/   (a folder of Gerber and drill files)\n"
      "Then: engraver run board/ (simulate) or engraver send board/ --to tcp://HOST:PORT.\n"
      "Exit: 0 planned and checked, 1 refused (narrow gaps, work area, islands left joined), "
      "2 bad input (a file, an option out of its range or options that cannot go together), 8 "
      "the tool would cut copper.");
  cmd->callback([a] { run_board(*a); });
}

const CommandRegistrar registrar("board", {"board"}, add_board_command);

}  // namespace

commands::CommandLog stderr_log() {
  return [](const std::string& line) { std::cerr << "engraver: " << printable(line) << "\n"; };
}

namespace {

// The isolation tool, its passes and depth.
void add_isolation_options(CLI::App* cmd, pcb::BoardIsolationArgs* a) {
  const std::string g = kBoardOptionsGroup;
  cmd->add_option("--tool-width", a->tool_width_mm, "isolation: V-bit width at the depth, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--passes", a->passes, "isolation passes")->group(g)->capture_default_str();
  cmd->add_option("--overlap", a->overlap, "overlap of passes (fraction of the tool width)")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--clearance", a->clearance_mm,
                  "isolation: kept between the tool's edge and the copper for the fit and the "
                  "machine's contour error, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_flag("--mill-all", a->mill_all, "clear all copper-free area")->group(g);
  CLI::Option* clearing =
      cmd->add_option("--clearing-tool", a->clearing_tool_mm,
                      "isolation: a wider tool for the outer part of the --passes width, mm "
                      "(mounted after the isolation tool; 0: none)")
          ->group(g);
  cmd->add_option("--narrow-passes", a->narrow_passes,
                  "with --clearing-tool: passes of the isolation tool next to the copper")
      ->group(g)
      ->needs(clearing)
      ->capture_default_str();
  cmd->add_flag("--isolate-empty-holes", a->isolate_empty_holes,
                "also cut inside openings of an island that hold no other island (hatched pours)")
      ->group(g);
  cmd->add_option("--depth", a->depth_mm, "isolation depth, mm")->group(g)->capture_default_str();
}

// Drilling, the cut-out and its tabs.
void add_drill_and_cutout_options(CLI::App* cmd, BoardArgs* a) {
  const std::string g = kBoardOptionsGroup;
  cmd->add_option("--drill-depth", a->drill.depth_mm, "drill plunge depth, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--drill-start", a->drill.start_mm, "height where each plunge starts, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--drill-feed", a->drill.feed_mm_s, "drill plunge feed, mm/s")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--cutter", a->cutout.cutter_mm, "cut-out cutter diameter, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--cut-depth", a->cutout.depth_mm, "cut-out depth, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--cut-step", a->cutout.step_mm, "cut-out depth per pass, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--cut-feed", a->cutout.feed_mm_s, "cut-out feed, mm/s")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--tab-width", a->cutout.tab_width_mm, "holding tab width, mm (0: none)")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--tabs", a->cutout.tabs, "holding tabs per board")
      ->group(g)
      ->capture_default_str();
  cmd->add_option(
         "--tab-spacing", a->cutout.tab_spacing_mm,
         "one tab per this much outline length, mm (instead of --tabs; 0: as if not given)")
      ->group(g)
      ->excludes("--tabs");  // a clash: neither wins
  cmd->add_option("--tab-height", a->cutout.tab_height_mm, "board thickness the tabs keep, mm")
      ->group(g)
      ->capture_default_str();
}

// The side, and a double-sided board's alignment holes.
void add_side_and_alignment_options(CLI::App* cmd, BoardArgs* a) {
  const std::string g = kBoardOptionsGroup;
  cmd->add_option("--side", a->side, "top or bottom (mirrored); default: the copper given")
      ->group(g)
      ->check(CLI::Validator(  // as the line is read, not after the files' notes
          [](const std::string& side) {
            return side.empty() || pcb::is_board_side(side) ? std::string()
                                                            : "'" + side + "' is not top or bottom";
          },
          "", "side"));
  cmd->add_option("--align-holes", a->alignment.holes,
                  "double-sided: alignment holes for pins, 'auto' (on the flip axis below and "
                  "above the board) or X,Y[;X,Y...] mm in the files' frame, each with its mirror; "
                  "drilled with the top side, which leaves the cut-out to the bottom")
      ->group(g)
      ->check(CLI::Validator(
          [](std::string& v) {
            return v.empty() ? std::string("empty: say auto, or X,Y[;X,Y...] mm") : "";
          },
          "", "not empty"));
  cmd->add_option("--align-diameter", a->alignment.diameter_mm, "alignment hole (pin) diameter, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--align-depth", a->alignment.depth_mm,
                  "alignment hole depth, through the blank into the spoil board, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--align-measured", a->alignment.measured_mm,
                  "double-sided, second setup: X1 Y1 X2 Y2, machine mm where alignment holes 1 "
                  "and 2 were found after the flip; the job is turned and shifted onto them")
      ->group(g)
      ->expected(4);
}

}  // namespace

void add_board_options(CLI::App* cmd, BoardArgs* a) {
  const std::string g = kBoardOptionsGroup;
  add_isolation_options(cmd, &a->isolation);
  add_drill_and_cutout_options(cmd, a);
  add_side_and_alignment_options(cmd, a);
  cmd->add_flag("--no-spindle", a->no_spindle, "no spindle on/off commands")->group(g);
  cmd->add_flag("--allow-narrow-gaps", a->allow_narrow_gaps,
                "plan even where copper is closer than the tool width (reported; exit 0 though "
                "the copper there stays joined)")
      ->group(g);
}

void refuse_board_option_combinations(const BoardArgs& args) {
  try {
    pcb::refuse_option_combinations(args);
  } catch (const pcb::BoardArgsError& e) {
    throw CLI::ValidationError(e.what());
  }
}

JobPlan plan_pcb_input(const std::string& input, const BoardArgs& args, const MachineDefaults& d,
                       commands::PlannedBoard* board) {
  return commands::plan_pcb_input(input, args, d, stderr_log(), board);
}

bool print_board_points_if_pcb(const std::string& input, const BoardArgs& args, double tol_mm,
                               bool csv) {
  if (!is_pcb_input(input)) return false;
  const commands::BoardPoints b = commands::board_points(input, args, tol_mm, stderr_log());
  if (csv) std::cout << "tool,tool_name,tool_diameter_um,path,point,x_um,y_um,z_um\n";
  std::cout << std::fixed << std::setprecision(1);
  for (const commands::BoardToolPath& p : b.paths) {
    const pcb::BoardTool& t = b.job.tools[p.tool];
    if (!csv)
      std::cout << "# tool " << p.tool + 1 << " (" << t.label << "), path " << p.path << " at z "
                << p.z_um << " um: " << p.points_file_mm.size() << " points (x_um y_um)\n";
    for (size_t k = 0; k < p.points_file_mm.size(); ++k) {
      const Point2& f = p.points_file_mm[k];
      if (csv)
        std::cout << p.tool + 1 << "," << t.label << "," << t.diameter_mm * 1000 << "," << p.path
                  << "," << k << "," << f.x() * 1000 << "," << f.y() * 1000 << "," << p.z_um
                  << "\n";
      else
        std::cout << f.x() * 1000 << " " << f.y() * 1000 << "\n";
    }
  }
  return true;
}

}  // namespace host::cli
