// Runs the PCB readers and the board planner over a corpus of real fabrication files and
// reports, per EDA program (named by the files' own X2 attributes or header comments), how
// many files read, how many agree with gerbv's rendering pixel by pixel, and how many boards
// plan and pass the geometric isolation check. Reads only the folder it is given; fetches
// nothing. Usage: pcb_corpus CORPUS_DIR [-v]   (docs/performance.md, "Real-file corpus").
#include <algorithm>   // std::max, std::transform
#include <cctype>      // std::tolower
#include <cstdio>      // std::printf
#include <cstdlib>     // std::getenv
#include <filesystem>  // std::filesystem
#include <fstream>     // std::ifstream
#include <map>         // std::map
#include <sstream>     // std::ostringstream
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/pcb/board_check.h"
#include "host/lib/pcb/board_files.h"
#include "host/lib/pcb/board_job.h"
#include "host/lib/pcb/excellon_reader.h"
#include "host/lib/pcb/gerber_reader.h"
#include "host/lib/pcb/pcb_file_names.h"
#include "host_tests/host/pcb/raster_compare.h"

namespace fs = std::filesystem;
using namespace host::pcb;

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// Fabrication data, not a read-me that happens to be named like a drill file: a Gerber
// format or aperture statement, an Excellon header, or Gerber operation codes.
bool looks_like_pcb(const std::string& text) {
  for (const char* mark : {"%FS", "%ADD", "M48", "D01", "D02", "D03", "G04"}) {
    if (text.find(mark) != std::string::npos) return true;
  }
  return false;
}

// The program a file names in its first 8 kB: X2 TF.GenerationSoftware, else a comment.
std::string program_of(const std::string& text) {
  const std::string head = lower(text.substr(0, 8192));
  struct Mark {
    const char* needle;
    const char* program;
  };
  // Most specific first ("pcb-rnd" before "pcb", "circuitmaker" before "altium").
  static const Mark marks[] = {
      {"kicad", "KiCad"},
      {"pcbnew", "KiCad"},
      {"eagle", "EAGLE"},
      {"circuitmaker", "CircuitMaker"},
      {"altium", "Altium"},
      {"protel", "Protel"},
      {"easyeda", "EasyEDA"},
      {"diptrace", "DipTrace"},
      {"pcb-rnd", "pcb-rnd"},
      {"fritzing", "Fritzing"},
      {"orcad", "OrCAD"},
      {"allegro", "Allegro"},
      {"cadence", "Allegro"},
      {"mentor", "Mentor"},
      {"boardstation", "Mentor"},
      {"expedition", "Mentor"},
      {"pads", "PADS"},
      {"p-cad", "P-CAD"},
      {"target 3001", "TARGET 3001!"},
      {"upverter", "Upverter"},
      {"fusion", "Fusion 360"},
      {"proteus", "Proteus"},
      {"designspark", "DesignSpark"},
      {"cam350", "CAM350"},
      {"fab 3000", "FAB 3000"},
      {"ucamco", "Ucamco"},
      {"geda", "gEDA"},
      {"gerbv", "gerbv (its export)"},
      {"creator: pcb", "gEDA"},
  };
  const size_t gen = head.find("%tf.generationsoftware,");
  if (gen != std::string::npos) {
    const std::string line = head.substr(gen, head.find('*', gen) - gen);
    for (const Mark& m : marks) {
      if (line.find(m.needle) != std::string::npos) return m.program;
    }
  }
  // Comments only: G04 lines (Gerber), ';' lines (Excellon).
  std::istringstream in(head);
  std::string l;
  std::string comments;
  while (std::getline(in, l)) {
    if (l.rfind("g04", 0) == 0 || l.rfind(";", 0) == 0 || l.rfind("%tf", 0) == 0) {
      comments += l + "\n";
    }
  }
  for (const Mark& m : marks) {
    if (comments.find(m.needle) != std::string::npos) return m.program;
  }
  return "";
}

struct Tally {
  int files = 0, read = 0, compared = 0, match = 0;
  int boards = 0, planned = 0, checked = 0, passed = 0;
};

struct Board {
  std::string dir;
  std::vector<fs::path> files;
};

// gerbv's picture and ours over one window, at the finest of these resolutions that keeps
// the window under 16 million pixels. strokes: the file read as an outline, when strokes
// narrower than a pixel are to be drawn as gerbv draws them (nullptr: not).
bool matches_gerbv(const std::string& path, const PcbLayer& layer, bool drill, std::string& why,
                   const PcbLayer* strokes = nullptr) {
  ClipperLib::Paths shapes = drill ? test::drill_shapes(layer) : layer.polygons_nm;
  // A negative image's copper is its box less what is drawn; gerbv fills its whole picture:
  // compared inside the box (2 pixels in from it: the window starts and ends on whole pixels,
  // which gerbv fills and our box only partly covers).
  bool negative = false;
  for (const std::string& n : layer.notes) {
    if (n.find("%IPNEG (deprecated negative image) applied") != std::string::npos) negative = true;
  }
  test::Window win;
  for (double dpi : {2000.0, 1000.0, 500.0, 250.0, 100.0}) {
    win = test::window_around(layer, negative ? -2 * 25.4 / dpi : 0.5, dpi);
    if (static_cast<double>(win.w) * win.h <= 16e6) break;
  }
  size_t thin = 0;
  if (strokes) {
    const ClipperLib::Paths hair = test::hairlines(*strokes, win.pixel_mm);
    thin = hair.size();
    shapes.insert(shapes.end(), hair.begin(), hair.end());
  }
  const test::Raster ours = test::rasterise(shapes, win);
  const test::Raster ref = test::gerbv_render(path, win);
  const test::Agreement a = test::compare(ours, ref);
  // PCB_CORPUS_DIFF=DIR: a picture of each file's differences (black both, red ours only,
  // blue gerbv's only), to look at a mismatch.
  if (const char* diff_dir = std::getenv("PCB_CORPUS_DIFF")) {
    test::write_difference(ours, ref,
                           (fs::path(diff_dir) / fs::path(path).filename()).string() + ".ppm");
  }
  std::ostringstream o;
  o << 100 * a.of_all() << " % of " << a.pixels << " px at " << win.dpi() << " dpi agree, "
    << a.beyond_edge << " of " << a.dark_either << " copper px differ beyond an edge";
  if (strokes)
    o << " (with " << thin << " outlines of strokes thinner than a pixel drawn 1 px wide)";
  why = o.str();
  // Pixels that differ only at an edge are gerbv snapping strokes to its pixel grid (more of
  // them at the coarser resolutions of large boards); a real difference leaves pixels with
  // nothing alike next to them. Agreement: at most 1 in 2000 copper pixels like that.
  return a.beyond_edge <= a.dark_either / 2000;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: pcb_corpus CORPUS_DIR [-v]\n");
    return 2;
  }
  const bool verbose = argc > 2 && std::string(argv[2]) == "-v";
  if (!test::gerbv_available()) std::fprintf(stderr, "gerbv not found: no comparisons\n");

  // Every folder holding files is one board.
  std::map<std::string, Board> boards;
  for (const auto& e :
       fs::recursive_directory_iterator(argv[1], fs::directory_options::follow_directory_symlink)) {
    if (!e.is_regular_file()) continue;
    Board& b = boards[e.path().parent_path().string()];
    b.dir = e.path().parent_path().string();
    b.files.push_back(e.path());
  }

  std::map<std::string, Tally> by_program;
  for (auto& [dir, board] : boards) {
    std::sort(board.files.begin(), board.files.end());
    struct File {
      fs::path path;
      std::string text, program;
      PcbFileFormat format;
    };
    std::vector<File> files;
    std::map<std::string, int> votes;
    for (const fs::path& p : board.files) {
      std::ifstream in(p, std::ios::binary);
      std::ostringstream ss;
      ss << in.rdbuf();
      File f{p, ss.str(), "", PcbFileFormat::kNone};
      f.format = board_file_format(p.filename().string(), f.text);
      if (f.format == PcbFileFormat::kNone || !looks_like_pcb(f.text)) continue;
      f.program = program_of(f.text);
      if (!f.program.empty()) ++votes[f.program];
      files.push_back(std::move(f));
    }
    if (files.empty()) continue;
    // Files that name no program (most drill files) belong to the board's program. A folder
    // may say whose files it holds in a file EDA_PROGRAM (one line), which wins: where the
    // files name no program but their names do (EAGLE's .cmp/.sol), or a reader's test files.
    std::string board_program = "(not named)";
    int best = 0;
    for (const auto& [p, n] : votes) {
      if (n > best) best = n, board_program = p;
    }
    std::ifstream named(fs::path(dir) / "EDA_PROGRAM");
    std::string given;
    if (named && std::getline(named, given) && !given.empty()) {
      board_program = given;
      for (File& f : files) f.program = given;
    }
    BoardFileSet set;
    for (File& f : files) {
      if (f.program.empty()) f.program = board_program;
      Tally& t = by_program[f.program];
      ++t.files;
      const std::string path = f.path.string();
      PcbLayer layer;
      try {
        layer = read_board_file(path, LayerKind::kUnknown);
        ++t.read;
      } catch (const std::exception& e) {
        if (verbose) std::printf("  unread  %s: %s\n", path.c_str(), e.what());
        continue;
      }
      if (verbose) {
        for (const std::string& n : layer.notes) {
          if (n.find("not on their circle") != std::string::npos) {
            std::printf("  arcs    %s: %s\n", path.c_str(), n.c_str());
          }
        }
      }
      const bool drill = f.format == PcbFileFormat::kExcellon;
      if (test::gerbv_available()) {
        try {
          GerberOptions as_copper;  // outlines too: the picture of what was drawn
          as_copper.forced_kind = LayerKind::kCopperTop;
          const PcbLayer picture = drill ? layer : read_gerber_file(path, as_copper);
          if (!picture.polygons_nm.empty() || !picture.holes.empty() || !picture.slots.empty()) {
            ++t.compared;
            std::string why;
            bool ok = matches_gerbv(path, picture, drill, why);
            if (!ok && !drill) {
              // gerbv widens strokes thinner than a pixel (zero-width outlines, no copper)
              // to one pixel: drawn so in our picture too, where they are what differs.
              GerberOptions as_strokes;
              as_strokes.forced_kind = LayerKind::kOutline;
              const PcbLayer strokes = read_gerber_file(path, as_strokes);
              std::string why_thin;
              ok = matches_gerbv(path, picture, drill, why_thin, &strokes);
              why = ok ? why_thin : why + "; " + why_thin;
            }
            t.match += ok;
            if (verbose)
              std::printf("  %s %s: %s\n", ok ? "gerbv=" : "gerbv!", path.c_str(), why.c_str());
          }
        } catch (const std::exception& e) {
          ++t.compared;
          if (verbose) std::printf("  gerbv!  %s: %s\n", path.c_str(), e.what());
        }
      }
      set.add(std::move(layer));
    }

    // The board: its copper (top, else bottom), drilling and outline, planned at the
    // defaults with a 0.2 mm tool; narrow gaps are planned anyway (reported), as the check
    // then shows whether the tool would cut copper.
    if (set.copper_top.empty() && set.copper_bottom.empty()) continue;
    Tally& t = by_program[board_program];
    ++t.boards;
    try {
      PcbLayer drill_storage;
      const BoardLayers layers = set.layers(&drill_storage);
      BoardOptions o;
      o.side = set.copper_top.empty() ? BoardSide::kBottom : BoardSide::kTop;
      o.allow_narrow_gaps = true;
      const BoardJob job = plan_board(layers, o);
      ++t.planned;
      const IsolationCheck c = check_planned_isolation(job, o);
      ++t.checked;
      t.passed += c.hits.empty();
      if (verbose) {
        std::printf("  board   %s (%s): planned, %zu copper hits, %zu islands not separated\n",
                    dir.c_str(), board_program.c_str(), c.hits.size(), c.unseparated.size());
      }
    } catch (const std::exception& e) {
      if (verbose)
        std::printf("  board   %s (%s): not planned: %s\n", dir.c_str(), board_program.c_str(),
                    e.what());
    }
  }

  std::printf("| program | files | read | match gerbv | boards | planned | no copper cut |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
  Tally all;
  for (const auto& [p, t] : by_program) {
    std::printf("| %s | %d | %d | %d of %d | %d | %d | %d of %d |\n", p.c_str(), t.files, t.read,
                t.match, t.compared, t.boards, t.planned, t.passed, t.checked);
    all.files += t.files, all.read += t.read, all.compared += t.compared, all.match += t.match;
    all.boards += t.boards, all.planned += t.planned, all.checked += t.checked;
    all.passed += t.passed;
  }
  std::printf("| all | %d | %d | %d of %d | %d | %d | %d of %d |\n", all.files, all.read, all.match,
              all.compared, all.boards, all.planned, all.passed, all.checked);
  return 0;
}
