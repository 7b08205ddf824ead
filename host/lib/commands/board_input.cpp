// PCB input of the engraver's commands (see board_input.h).
#include "host/lib/commands/board_input.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>   // std::sort
#include <cmath>       // std::lround
#include <filesystem>  // directories

#include "host/lib/commands/exit_codes.h"  // CommandFailure
#include "host/lib/drawing/file_text.h"    // not_a_file_text
#include "host/lib/pcb/board_check.h"
#include "host/lib/pcb/board_probe_area.h"
#include "host/lib/pcb/isolation_check.h"
#include "host/lib/pcb/pcb_file_names.h"
#include "host/lib/plan/counted.h"  // counted: "1 hole", "2 holes"
#include "host/lib/plan/firmware_points.h"

namespace host::commands {

namespace {

// Where a Gerber's X2 file function is looked for: its head when the attribute is whole in
// it (or the file is no longer), else the whole file (a long licence or a tool's settings
// may come first, or the attribute straddle the head's end).
std::string x2_header_text(const std::string& path, const std::string& head) {
  const bool whole = !pcb::x2_file_function(head).empty();
  std::string text;
  if (whole || head.size() < 4096 || read_file_text(path, &text) != FileRead::kOk) return head;
  return text;
}

using pcb::LayerKind;
using pcb::PcbLayer;

PcbLayer read_layer(const std::string& path, LayerKind forced) {
  try {
    return pcb::read_board_file(path, forced);
  } catch (const pcb::PcbReadError& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
}

// The reader's warnings about a layer (its other notes are for `engraver info`).
const PcbLayer& take_warnings(BoardFiles* b, const PcbLayer& l) {
  const std::string warning = "warning: ";
  for (const std::string& n : l.notes) {
    const size_t at = n.find(warning);
    if (at != std::string::npos)
      b->warnings.push_back(l.path + ": " + n.substr(0, at) + n.substr(at + warning.size()));
  }
  return l;
}

void add_layer(BoardFiles* b, PcbLayer l, bool from_directory) {
  const std::string path = l.path;
  take_warnings(b, l);
  if (b->layers.add(std::move(l))) return;
  if (from_directory) {
    b->notes.push_back(path + ": not a copper, drill or outline layer: left out");
    return;
  }
  if (std::find(b->warnings.begin(), b->warnings.end(), path + ": " + pcb::kGerberNotADrillFile) !=
      b->warnings.end())
    throw CommandFailure(kExitUsage, path + ": " + pcb::kGerberNotADrillFile +
                                         " (a drill drawing?); name its layer with --top, "
                                         "--bottom or --outline, or give the Excellon file");
  throw CommandFailure(
      kExitUsage, path +
                      ": cannot tell which layer this is (no X2 TF.FileFunction, no "
                      "usual name); name it with --top, --bottom or --outline (engraver board), "
                      "or give copper as top:FILE or bottom:FILE");
}

bool has_prefix(const std::string& s, const std::string& p) {
  return s.compare(0, p.size(), p) == 0;
}

// "bottom:a,b" -> side "bottom", files {a, b}; a directory -> its PCB files (not those in
// its subfolders).
// left_out: notes on a directory's files that are not read: neither Gerber nor Excellon (by
// name or content), or not regular files (a FIFO is never opened: that would wait).
// subfolders: set when the directory has some.
std::vector<std::string> expand_input(const std::string& input, std::string* side, bool* directory,
                                      std::string* stripped = nullptr,
                                      std::vector<std::string>* left_out = nullptr,
                                      bool* subfolders = nullptr) {
  std::string rest = input;
  for (const char* s : {"top:", "bottom:"}) {
    if (has_prefix(rest, s)) {
      *side = std::string(s, std::string(s).size() - 1);
      rest = rest.substr(std::string(s).size());
    }
  }
  std::vector<std::string> files;
  if (stripped) *stripped = rest;
  *directory = std::filesystem::is_directory(rest);
  if (*directory) {
    for (const auto& e : std::filesystem::directory_iterator(rest)) {
      const std::string p = e.path().string();
      if (e.is_directory()) {
        if (subfolders) *subfolders = true;
        continue;
      }
      if (!e.is_regular_file()) {
        if (left_out) left_out->push_back(p + ": " + not_a_file_text(p) + ": left out");
        continue;
      }
      if (pcb::pcb_file_format(p) == pcb::PcbFileFormat::kNone) {
        if (left_out)
          left_out->push_back(p +
                              ": neither Gerber nor Excellon (by its name or content): left out");
        continue;
      }
      files.push_back(p);
    }
    std::sort(files.begin(), files.end());
    if (left_out) std::sort(left_out->begin(), left_out->end());
    return files;
  }
  size_t start = 0;
  while (start <= rest.size()) {
    const size_t comma = rest.find(',', start);
    const std::string f = rest.substr(start, comma == std::string::npos ? comma : comma - start);
    if (!f.empty()) files.push_back(f);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return files;
}

// "not a Gerber file: binary data (a NUL byte at byte N)", the reader's words, when the head
// of a file holds a NUL before any M02 (padding after the end is not binary data); else "".
std::string binary_data_text(const std::string& head) {
  const size_t nul = head.find('\0');
  if (nul == std::string::npos || head.rfind("M02", nul) != std::string::npos) return "";
  return "not a Gerber file: binary data (a NUL byte at byte " + std::to_string(nul) + ")";
}

// The copper kind a board folder's file names show for the job's side: the side asked for,
// else top if a file is named as top copper (the default side then); kUnknown if the names
// cannot tell.
LayerKind copper_for_side(const std::string& side, const std::vector<std::string>& files) {
  if (side == "top") return LayerKind::kCopperTop;
  if (side == "bottom") return LayerKind::kCopperBottom;
  for (const std::string& f : files) {
    if (pcb::pcb_file_format(f) == pcb::PcbFileFormat::kGerber &&
        pcb::layer_kind_from_file_name(f) == LayerKind::kCopperTop)
      return LayerKind::kCopperTop;
  }
  return LayerKind::kUnknown;
}

}  // namespace

std::string board_name(const std::string& input_or_file) {
  std::filesystem::path p(input_or_file);
  if (!std::filesystem::is_directory(p)) return p.stem().string();
  // A folder by its own name, also when given as `.` or `dir/..` (outside tester 21: `board .`
  // wrote `..board.svg`).
  p = std::filesystem::absolute(p).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  const std::string name = p.filename().string();
  return name.empty() ? std::string("board") : name;  // the root folder
}

std::string input_name(const std::string& input) {
  std::string s = input;
  const bool bottom = s.rfind("bottom:", 0) == 0;
  for (const char* side : {"top:", "bottom:"}) {
    if (s.rfind(side, 0) == 0) s = s.substr(std::string(side).size());
  }
  if (bottom && !std::filesystem::is_directory(s)) {
    // A bottom job of several files is named after its bottom copper.
    std::string side;
    bool directory = false;
    for (const std::string& f : expand_input(s, &side, &directory))
      if (pcb::layer_kind_from_file_name(f) == LayerKind::kCopperBottom) return board_name(f);
  }
  return board_name(s.substr(0, s.find(',')));
}

namespace {

// read_board_input without its refusal of a folder that holds no copper.
BoardFiles read_board_files(const std::string& input, const std::string& side_asked,
                            bool both_copper) {
  BoardFiles b;
  bool directory = false;
  std::string stripped;
  std::vector<std::string> left_out;
  bool subfolders = false;
  const std::vector<std::string> files =
      expand_input(input, &b.side, &directory, &stripped, &left_out, &subfolders);
  for (const std::string& n : left_out) b.notes.push_back(n);
  if (files.empty()) {
    // With what was left out and why, as a folder without copper is refused (the first 20).
    std::string msg = input +
                      ": no Gerber or Excellon files there (by their names or first lines)" +
                      (subfolders ? " (subfolders are not searched)" : "");
    const size_t shown = std::min<size_t>(left_out.size(), 20);
    for (size_t k = 0; k < shown; ++k) msg += "\n  " + left_out[k];
    if (left_out.size() > shown)
      msg += "\n  ... and " + std::to_string(left_out.size() - shown) + " more left out";
    throw CommandFailure(kExitUsage, msg);
  }
  const LayerKind wanted_copper = copper_for_side(side_asked.empty() ? b.side : side_asked, files);
  for (const std::string& f : files) {
    // In a directory, only files whose names or X2 file functions say copper, drill or
    // outline are read (no silkscreen, mask or paste), and of the copper only the job
    // side's: reading the other was a fifth of a large board's planning time.
    const std::string head = directory ? pcb::read_file_head(f) : std::string();
    std::string how;  // what said which layer the file is
    LayerKind forced = LayerKind::kUnknown;
    if (directory && pcb::pcb_file_format(f, head) == pcb::PcbFileFormat::kExcellon)
      how = pcb::pcb_file_format(f, "") == pcb::PcbFileFormat::kExcellon ? "its name"
                                                                         : "its content (M48)";
    if (directory && pcb::pcb_file_format(f, head) == pcb::PcbFileFormat::kGerber) {
      // The file's own X2 file function first, then the table of usual names. A layer no job
      // cuts is left out saying what it is (an X2 Legend named .GTL is not copper).
      const std::string x2 = x2_header_text(f, head);
      LayerKind named = pcb::layer_kind_from_x2(x2);
      how = "its X2 file function";
      std::string other = pcb::other_layer_from_x2(x2);
      if (named == LayerKind::kUnknown && other.empty()) {
        named = pcb::layer_kind_from_file_name(f);
        how = "its name";
        if (named == LayerKind::kUnknown) other = pcb::other_layer_from_name(f);
      }
      if (named == LayerKind::kDrill) {  // a drill drawing (OrCAD's .drd): no holes in it
        b.notes.push_back(f + ": " + pcb::kGerberNotADrillFile + " (left out)");
        continue;
      }
      if (named == LayerKind::kUnknown && !binary_data_text(head).empty()) {
        // An executable or image with a Gerber extension: say what it is, no --top advice.
        b.notes.push_back(f + ": " + binary_data_text(head) + ": left out");
        continue;
      }
      if (!other.empty()) {
        b.notes.push_back(fmt::format("{}: {} {} layer (from {}): left out", f,
                                      other == "inner copper" ? "an" : "a", other, how));
        continue;
      }
      if (named == LayerKind::kUnknown) {
        b.notes.push_back(f +
                          ": neither its name nor an X2 file function says copper, drill or "
                          "outline: left out (name it with --top, --bottom or --outline)");
        continue;
      }
      if (!both_copper && wanted_copper != LayerKind::kUnknown && named != wanted_copper &&
          (named == LayerKind::kCopperTop || named == LayerKind::kCopperBottom)) {
        b.notes.push_back(f + ": copper of the other side: not read for this job");
        continue;
      }
      forced = named;
    }
    // A folder's Gerber is read as what the note below says it was taken for (its reader
    // would find the same, but for a file function after M02).
    PcbLayer l = read_layer(f, directory ? forced : LayerKind::kUnknown);
    if (l.kind == LayerKind::kUnknown && !directory && files.size() == 1 && !b.side.empty() &&
        pcb::pcb_file_format(f) == pcb::PcbFileFormat::kGerber) {
      // "top:FILE" names the copper side of a file nothing else names (Eagle's .gbx).
      l.kind = b.side == "bottom" ? LayerKind::kCopperBottom : LayerKind::kCopperTop;
      b.notes.push_back(f + ": taken as " + b.side + " copper (from the '" + b.side + ":' prefix)");
    }
    if (directory && !how.empty() && l.kind != LayerKind::kUnknown)
      b.notes.push_back(f + ": taken as " + pcb::layer_kind_name(l.kind) + " (from " + how + ")");
    add_layer(&b, std::move(l), directory);
  }
  b.from_directory = directory;
  b.name = board_name(directory ? stripped : files.front());
  return b;
}

}  // namespace

BoardFiles read_board_folder(const std::string& folder) {
  return read_board_files(folder, "", true);
}

// side_asked: --side, or "" (a "top:"/"bottom:" prefix, else the board's default side).
BoardFiles read_board_input(const std::string& input, const std::string& side_asked,
                            bool both_copper) {
  BoardFiles b = read_board_files(input, side_asked, both_copper);
  if (b.from_directory && b.layers.copper_top.empty() && b.layers.copper_bottom.empty()) {
    // A board folder without copper is a folder whose copper was not recognised: planning
    // its holes alone would look like success.
    // Naming copper helps only when a Gerber file was left out for saying no layer.
    // The other side's copper alone: the side asked for is the thing to change.
    bool nameable = false, other_side = false;
    for (const std::string& n : b.notes) {
      nameable = nameable || n.find("(name it with --top") != std::string::npos;
      other_side = other_side || n.find(": copper of the other side:") != std::string::npos;
    }
    const std::string other = side_asked == "bottom" ? "top" : "bottom";
    std::string msg =
        input + ": no copper layer for the job among the folder's files (" +
        (other_side ? "its copper is " + other + " copper: give --side " + other + "; " : "") +
        (nameable ? "name it with --top or --bottom; " : "") +
        "to cut only holes or an outline, give that file itself)";
    for (const std::string& n : b.notes) msg += "\n  " + n;
    throw CommandFailure(kExitUsage, msg);
  }
  return b;
}

void add_named_layer(BoardFiles* b, const std::string& path, LayerKind kind) {
  PcbLayer l = read_layer(path, kind);
  take_warnings(b, l);
  l.kind = kind;  // whatever its name or attributes say
  b->layers.add(std::move(l));
}

void log_board_notes(const BoardFiles& b, const CommandLog& log) {
  for (const std::string& n : b.notes) log("note: " + n);
  for (const std::string& w : b.warnings) log("warning: " + w);
}

pcb::BoardOptions board_options_for(const pcb::BoardArgs& args, const pcb::BoardMachine& m,
                                    const BoardFiles& b) {
  try {
    return pcb::resolve_board_options(args, m, b.layers, b.side);
  } catch (const pcb::BoardArgsError& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
}

// measured_mm: X1 Y1 X2 Y2 of the alignment holes after the flip; the job is planned once
// without, for where they should be, then turned and shifted onto them.
pcb::BoardJob plan_board_files(const BoardFiles& b, const pcb::BoardOptions& o,
                               const std::vector<double>& measured_mm) {
  PcbLayer drill;  // several drill files (plated and not) make one drill layer
  pcb::BoardLayers l;
  try {
    l = b.layers.layers(&drill);
  } catch (const PlanError& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
  try {
    if (measured_mm.size() == 4) {
      const pcb::BoardJob nominal = pcb::plan_board(l, o);
      if (nominal.alignment_holes_mm.size() < 2)
        throw CommandFailure(kExitUsage,
                             "--align-measured needs two alignment holes; --align-holes gave one "
                             "(a hole on the flip axis is its own mirror image): give another");
      const Point2 expected[2] = {nominal.alignment_holes_mm.at(0),
                                  nominal.alignment_holes_mm.at(1)};
      const Point2 measured[2] = {Point2(measured_mm[0], measured_mm[1]),
                                  Point2(measured_mm[2], measured_mm[3])};
      pcb::BoardOptions aligned = o;
      aligned.alignment.placement = pcb::measured_alignment(expected, measured);
      return pcb::plan_board(l, aligned);
    }
    return pcb::plan_board(l, o);
  } catch (const PlanError& e) {
    throw CommandFailure(kExitJobFailed, e.what());
  } catch (const pcb::CutoutError& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
}

bool is_pcb_input(const std::string& input) {
  std::string side;
  bool directory = false;
  std::string rest = input;
  if (has_prefix(rest, "top:") || has_prefix(rest, "bottom:")) return true;
  // A folder can only be a board's: one without PCB files is refused as one, in the words
  // info and board use ("no Gerber or Excellon files there"), not as a drawing.
  if (std::filesystem::is_directory(rest)) return true;
  for (const std::string& f : expand_input(rest, &side, &directory))
    if (pcb::pcb_file_format(f) != pcb::PcbFileFormat::kNone) return true;
  return false;
}

bool input_exists(const std::string& input) {
  std::string side;
  bool directory = false;
  std::string stripped;
  const std::vector<std::string> files = expand_input(input, &side, &directory, &stripped);
  if (directory) return true;
  for (const std::string& f : files)
    if (!std::filesystem::exists(f)) return false;
  return !files.empty();
}

JobPlan plan_pcb_input(const std::string& input, const pcb::BoardArgs& args,
                       const pcb::BoardMachine& m, const CommandLog& log, PlannedBoard* board) {
  const bool probe_area = board != nullptr && board->with_probe_area;
  const BoardFiles b =
      read_board_input(input, args.side, probe_area && !args.alignment.holes.empty());
  log_board_notes(b, log);
  const pcb::BoardOptions o = board_options_for(args, m, b);
  const auto job =
      std::make_shared<const pcb::BoardJob>(plan_board_files(b, o, args.alignment.measured_mm));
  try {
    // Refused before a byte is sent (send) or the machine is simulated (run).
    const int tol_um = static_cast<int>(std::lround(m.chord_tol_mm * 1000));
    pcb::refuse_copper_hits(pcb::check_controller_isolation(*job, o, tol_um),
                            fmt::format("the controller's points at {} mm chords", m.chord_tol_mm));
  } catch (const pcb::CopperCutError& e) {
    throw CommandFailure(kExitCutsCopper, b.name + ": " + e.what());
  }
  const pcb::BoardReport& r = job->report;
  for (const std::string& n : r.notes) log("note: " + n);
  log(fmt::format("board {}: mount {} first; {}, {}, {}", b.name, r.first_tool,
                  counted(r.isolation_contours, "contour"), counted(r.holes, "hole"),
                  counted(r.tool_changes, "tool change")));
  for (const pcb::NarrowGap& g : r.narrow_gaps)
    log("warning: " + pcb::describe_gap(g, o.isolation));
  if (board) {
    board->job = job;
    board->title = b.name;
    board->check_tolerance_mm = pcb::isolation_check_tolerance_mm(o);
    board->isolation_z_mm = -o.isolation_depth_mm;
  }
  if (probe_area) {
    pcb::PcbLayer drill;  // the layers again: the bottom side is planned from them too
    board->probe_area = pcb::board_probe_area(b.layers.layers(&drill), o, *job);
  }
  return job->plan;
}

BoardPoints board_points(const std::string& input, const pcb::BoardArgs& args, double tol_mm,
                         const CommandLog& log) {
  pcb::BoardMachine m;
  // Points in the file frame: no work area applies, unless the job is turned and shifted
  // onto measured holes (machine positions): then `board`'s default work area, as it checks.
  const bool placed = !args.alignment.measured_mm.empty();
  if (!placed) m.work_w_mm = m.work_h_mm = 1e6;
  const BoardFiles b = read_board_input(input, args.side);
  log_board_notes(b, log);
  pcb::BoardOptions o = board_options_for(args, m, b);
  if (!placed) o.travel_width_mm = o.travel_height_mm = m.work_w_mm;
  BoardPoints out;
  out.job = plan_board_files(b, o, args.alignment.measured_mm);
  for (const std::string& n : out.job.report.notes) log("note: " + n);
  for (const pcb::NarrowGap& g : out.job.report.narrow_gaps)
    log("warning: " + pcb::describe_gap(g, o.isolation));
  out.paths = board_tool_paths(out.job, static_cast<int>(std::lround(tol_mm * 1000)));
  return out;
}

std::vector<BoardToolPath> board_tool_paths(const pcb::BoardJob& job, int chord_tolerance_um) {
  std::vector<BoardToolPath> out;
  const JobPlan& plan = job.plan;
  size_t tool = 0;
  int32_t z_um = 0;
  bool down = false;  // the tool below the surface: a new path starts at each change of z
  bool open = false;  // the last path in `out` takes the next points
  int last_curve = -1;
  Point2 at(0, 0);
  auto start = [&]() {
    BoardToolPath p;
    p.tool = tool;
    p.path = out.size();
    p.z_um = z_um;
    out.push_back(p);
    open = true;
  };
  auto add = [&](const Point2& machine) {
    if (!open) start();
    const Point2 f = job.frame.to_file(machine);
    std::vector<Point2>& pts = out.back().points_file_mm;
    if (pts.empty() || (pts.back() - f).norm() > 1e-9) pts.push_back(f);
  };
  for (const PlanStep& s : plan.steps) {
    switch (s.kind) {
      case PlanStep::kPause:
        if (tool + 1 < job.tools.size()) ++tool;
        open = false;
        break;
      case PlanStep::kPenDown:
      case PlanStep::kPenUp:
        z_um = s.z_um;
        down = s.z_um < 0;
        open = false;
        last_curve = -1;
        break;
      case PlanStep::kRapid:
        at = Point2(s.to.x_um * 1e-3, s.to.y_um * 1e-3);
        open = false;
        break;
      case PlanStep::kDrill: {
        const int32_t z = z_um;
        z_um = s.z_um;
        open = false;
        at = Point2(s.to.x_um * 1e-3, s.to.y_um * 1e-3);
        add(at);
        open = false;
        z_um = z;
        break;
      }
      case PlanStep::kFeed:
        if (!down) break;
        if (!open) add(at);
        at = Point2(s.to.x_um * 1e-3, s.to.y_um * 1e-3);
        add(at);
        break;
      case PlanStep::kSpline:
        if (!down || s.curve < 0 || s.curve == last_curve) break;
        last_curve = s.curve;
        for (const Point2& p :
             firmware_points_mm(plan.curves[s.curve].spline(), chord_tolerance_um))
          add(p);
        at = Point2(s.to.x_um * 1e-3, s.to.y_um * 1e-3);
        break;
      default:
        break;
    }
  }
  return out;
}

}  // namespace host::commands
