#include "host/lib/pcb/gerber_reader.h"

#include <algorithm>      // std::min, std::max, std::count
#include <cctype>         // std::isdigit, std::isspace
#include <cmath>          // std::atan2, std::hypot, std::fabs
#include <cstdio>         // std::snprintf
#include <cstdlib>        // std::strtod
#include <map>            // std::map
#include <unordered_map>  // std::unordered_map
#include <utility>        // std::pair
#include <vector>         // std::vector

#include "host/lib/pcb/gerber_include.h"
#include "host/lib/pcb/gerber_macro.h"
#include "host/lib/pcb/gerber_outline.h"
#include "host/lib/pcb/gerber_reader_state.h"
#include "host/lib/pcb/gerber_shapes.h"
#include "host/lib/pcb/pcb_file_names.h"

namespace host::pcb {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

namespace {

using gerber::Aperture;
using gerber::ApertureDefinitionText;
using gerber::ApertureTable;
using gerber::Batch;
using gerber::CoordinateFormat;
using gerber::GerberDiagnostics;
using gerber::GerberDrawing;
using gerber::GerberUnits;
using gerber::GraphicsState;
using gerber::ImageParameters;
using gerber::OpenBlock;
using gerber::OpenKnockout;
using gerber::StepRepeat;

// How far an arc's end radius may be from its start radius (nm): the reader's limit, or for
// small arcs half the start radius, at most 1 mm (see GerberReadOptions).
double arc_mismatch_limit_nm(double start_radius_nm, double limit_nm) {
  return std::max(limit_nm, std::min(1e6, start_radius_nm / 2));
}

const double kPi = 3.14159265358979323846;
const double kMaxCoordNm = 1e10;    // 10 m: anything beyond is a broken file
const double kMaxApertureNm = 1e9;  // 1 m
// Start and end radii further apart than this make an arc ill-defined: drawn as both we and
// gerbv read it (closer, the two readings differ by less than the flattening of curves).
const double kIllDefinedArcNm = 1000;
const long kMaxStepRepeatCopies = 10000;

bool is_space(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}

std::string strip_all_space(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    if (!is_space(c)) out += c;
  }
  return out;
}

std::string trim(const std::string& s) {
  size_t a = 0, b = s.size();
  while (a < b && is_space(s[a])) ++a;
  while (b > a && is_space(s[b - 1])) --b;
  return s.substr(a, b - a);
}

std::string without_line_breaks(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c != '\r' && c != '\n') out += c;
  }
  return out;
}

bool starts_with(const std::string& s, const char* p) {
  return s.rfind(p, 0) == 0;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  size_t start = 0;
  for (;;) {
    const size_t at = s.find(sep, start);
    out.push_back(s.substr(start, at - start));
    if (at == std::string::npos) return out;
    start = at + 1;
  }
}

class GerberReader {
 public:
  GerberReader(const std::string& text, const std::string& path, const GerberOptions& options)
      : text_(text), opt_(options), diag_(path) {}

  PcbLayer read();

 private:
  void read_blocks();
  LayerKind layer_kind() const;
  void outline_loops(PcbLayer* layer) const;
  void negative_image(Paths* drawn);

  // Blocks.
  void extended_block(const std::string& body, int first_line);
  void extended_command(const std::string& cmd);
  void word_block(const std::string& word);
  void g_code(int g, const std::string& value);
  void d_code(int dn, const std::string& value, int* d);
  void m_code(int m, const std::string& value);
  void comment(const std::string& text);
  void attribute(const std::string& body);

  // Extended commands.
  void format_spec(const std::string& s);
  void aperture_definition(const std::string& s);
  void define_aperture(const std::string& s, size_t name_at, int number_d);
  void check_standard_sizes(const std::string& name, const std::vector<double>& params,
                            int number_d) const;
  Aperture standard_aperture(const std::string& name, const std::vector<double>& params,
                             int number_d, size_t* hole_at);
  void punch_hole(Aperture* ap, const std::vector<double>& params, size_t hole_at);
  Aperture macro_aperture(const std::string& name, const std::vector<double>& params, int number_d);
  void aperture_macro(const std::vector<std::string>& parts, const std::vector<int>& lines);
  void aperture_block(const std::string& arg);
  void step_repeat(const std::string& s);
  void close_step_repeat();
  bool copies_stand_alone(const std::vector<Batch>& block) const;
  Paths evaluate(std::vector<Batch>& batches);  // counts drawn_.reclipped

  // Deprecated parameters.
  bool deprecated_parameter(const std::string& code, const std::string& arg);
  void image_polarity(const std::string& arg);
  void mirror_image(const std::string& arg);
  void image_offset(const std::string& code, const std::string& arg);
  void image_justify(const std::string& arg);
  void justify_image(Paths* image, const BoxNm& drawn);
  void image_transform(const std::string& which, const char* what, bool identity);
  void transform_image(Paths& paths) const;
  void check_image_transforms(bool drawn);
  std::pair<double, double> axis_values(const std::string& arg, const char* what,
                                        double missing) const;
  void knockout(const std::string& arg);
  void open_knockout(const std::string& arg);
  void close_knockout();

  // Operations.
  cInt coordinate(const std::string& s, bool is_x);
  void operate(int d, const std::string* x, const std::string* y, const std::string* i,
               const std::string* j);
  void draw_line(IntPoint from, IntPoint to);
  void draw_arc(IntPoint from, IntPoint to, cInt i, cInt j, bool region);
  void arc_centre(const VecNm& a, const VecNm& b, bool same_point, cInt i, cInt j, VecNm* centre,
                  double* sweep);
  bool zero_radius_arc(double r0, double r1);
  void region_arc(IntPoint from, const Path& pts, const Path* theirs_if_ill);
  void stroke_arc(IntPoint from, const Path& pts, const Path* theirs_if_ill, const VecNm* centre);
  void stroke_arc_with_shape(IntPoint from, const Path& pts, const Path* theirs_if_ill,
                             const VecNm* centre);
  void flash(IntPoint at);
  const Aperture& current_aperture() const;
  void note_redefinition(int number_d, const Aperture& ap, const std::string& text);
  void add_object(Paths paths);
  void count_vertices(size_t n);
  void add_centre_line(IntPoint from, const Path& points, double width_nm);
  void finish_contour();
  Paths both_readings(const Paths& ours, const Paths& theirs) const;

  const std::string& text_;
  GerberOptions opt_;
  GerberDiagnostics diag_;
  int last_block_line_ = 1;
  CoordinateFormat fmt_;
  GerberUnits unit_;
  ApertureTable apertures_;
  GraphicsState gs_;
  GerberDrawing drawn_;
  StepRepeat sr_;
  std::vector<OpenBlock> blocks_;  // aperture blocks being read, innermost last
  ImageParameters image_;
  OpenKnockout knockout_;
  LayerKind x2_kind_ = LayerKind::kUnknown;
  bool x2_kind_given_ = false;
  // The second reading of a file with a D code redefined after it drew: its last definition
  // stands for every one.
  std::map<int, ApertureDefinitionText> last_definitions_;
};

PcbLayer GerberReader::read() {
  read_blocks();
  if (!apertures_.redefined_after_use.empty() && last_definitions_.empty()) {
    GerberReader again(text_, diag_.path, opt_);
    for (int n : apertures_.redefined_after_use) again.last_definitions_[n] = apertures_.last.at(n);
    return again.read();
  }
  PcbLayer layer;
  layer.path = diag_.path;
  layer.units = unit_.name;
  layer.apertures_or_tools = static_cast<int>(apertures_.defined.size());
  layer.arc_tolerance_nm = opt_.arc_tolerance_nm;
  layer.kind = layer_kind();
  if (layer.kind == LayerKind::kOutline) {
    outline_loops(&layer);
  } else {
    layer.polygons_nm = evaluate(drawn_.batches);
  }
  check_image_transforms(!layer.polygons_nm.empty());
  BoxNm drawn;  // gerbv justifies by the image's extent as drawn, before its transforms
  if (image_.justify)
    for (const Path& p : layer.polygons_nm) drawn.add(p);
  if (image_.offset_x != 0 || image_.offset_y != 0)
    translate_paths(layer.polygons_nm, image_.offset_x, image_.offset_y);
  transform_image(layer.polygons_nm);
  if (image_.negative && layer.kind != LayerKind::kOutline && !layer.polygons_nm.empty())
    negative_image(&layer.polygons_nm);
  justify_image(&layer.polygons_nm, drawn);
  if (drawn_.ill_defined_arcs > 0) {
    char msg[240];
    std::snprintf(msg, sizeof msg,
                  "warning: %d arcs whose end is not on their circle (start and end radii differ "
                  "by up to %.1f um): copper is where either reading puts it (through both end "
                  "points, and at the start radius as gerbv draws them)",
                  drawn_.ill_defined_arcs, drawn_.ill_defined_max_nm * 1e-3);
    layer.notes.push_back(msg);
  }
  for (const ImageParameters::Transform& t : image_.transforms)
    diag_.note_at("warning: " + t.which + " (deprecated " + t.what + ") applied", t.line);
  for (const std::string& s : diag_.lines()) layer.notes.push_back(s);
  return layer;
}

// Every block of the file up to M02, then what must hold at its end.
void GerberReader::read_blocks() {
  const size_t n = text_.size();
  // Gerber is printable text: a NUL before M02 is binary data (an executable, an image, a
  // zip), and would cut the message that quotes it short. NUL padding after M02 is not read.
  const size_t nul = text_.find('\0');
  auto refuse_binary = [&] {
    diag_.line = 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + nul, '\n'));
    diag_.fail("not a Gerber file: binary data (a NUL byte at byte " + std::to_string(nul) + ")");
  };
  size_t pos = 0;
  while (pos < n && !gs_.done) {
    const char c = text_[pos];
    if (pos == nul) refuse_binary();
    if (c == '\n') {
      ++diag_.line;
      ++pos;
    } else if (is_space(c)) {
      ++pos;
    } else {
      // A %..% extended block, or a data block up to its '*'.
      const bool extended = c == '%';
      const size_t end = extended ? text_.find('%', pos + 1) : text_.find('*', pos);
      if (nul != std::string::npos && nul > pos && (end == std::string::npos || nul < end))
        refuse_binary();
      if (end == std::string::npos && extended) diag_.fail("'%' block never closed with '%'");
      if (end == std::string::npos)
        diag_.fail("data block '" + trim(text_.substr(pos, 40)) + "' never ends with '*'");
      const std::string body =
          extended ? text_.substr(pos + 1, end - pos - 1) : text_.substr(pos, end - pos);
      const int first = diag_.line;
      last_block_line_ = first;
      if (extended)
        extended_block(body, first);
      else
        word_block(body);
      diag_.line = first + static_cast<int>(std::count(body.begin(), body.end(), '\n'));
      pos = end + 1;
    }
  }
  if (!gs_.done) {
    diag_.line = last_block_line_;
    diag_.fail("the file ends without M02 (end of file): it may be cut short, so it is not used");
  }
  close_knockout();
  for (size_t k = pos; k < n; ++k) {
    if (!is_space(text_[k]) && text_[k] != '\0' && text_[k] != '\x1a') {  // padding, Ctrl-Z
      diag_.note("text after M02 ignored");
      break;
    }
  }
  if (gs_.region) diag_.fail("G36 region still open at M02");
  for (const auto& bad : apertures_.refused)
    diag_.note("warning: aperture D" + std::to_string(bad.first) +
               " never used: its definition is left out (" + bad.second + ")");
  if (!blocks_.empty())
    diag_.fail("block aperture D" + std::to_string(blocks_.back().number_d) + " still open at M02");
}

// The kind given by the caller, else the file's X2 file function, else its name.
LayerKind GerberReader::layer_kind() const {
  if (opt_.forced_kind != LayerKind::kUnknown) return opt_.forced_kind;
  if (x2_kind_given_) return x2_kind_;
  const LayerKind named = layer_kind_from_file_name(diag_.path);
  return named == LayerKind::kUnknown ? opt_.kind_if_unknown : named;
}

// Strokes of one width joined end to end; the width stays with each, so loops can be closed as
// the drawn strokes close them.
void GerberReader::outline_loops(PcbLayer* layer) const {
  std::map<double, std::vector<Path>> by_width;
  for (size_t k = 0; k < drawn_.strokes.size(); ++k)
    by_width[drawn_.stroke_widths_nm[k]].push_back(drawn_.strokes[k]);
  for (const auto& [width, strokes] : by_width) {
    for (Path& p : join_strokes(strokes, opt_.arc_tolerance_nm * 4 + 2000)) {
      layer->polygons_nm.push_back(std::move(p));
      layer->outline_widths_nm.push_back(static_cast<cInt>(width));
    }
  }
  layer->outline_paths_are_open = true;
}

// %IPNEG: the copper is the image's extent less what is drawn. gerbv fills its whole picture,
// which has a border of 5 % of the image's width and height (`gerbv -x png`'s default):
// copper out to there, so a shape drawn on the box's edge leaves no sliver between it and the
// edge.
void GerberReader::negative_image(Paths* drawn) {
  cInt x0 = (*drawn)[0][0].X, x1 = x0, y0 = (*drawn)[0][0].Y, y1 = y0;
  for (const Path& p : *drawn)
    for (const IntPoint& v : p) {
      x0 = std::min(x0, v.X), x1 = std::max(x1, v.X);
      y0 = std::min(y0, v.Y), y1 = std::max(y1, v.Y);
    }
  const cInt mx = (x1 - x0) / 20, my = (y1 - y0) / 20;
  const Path box = {{x0 - mx, y0 - my}, {x1 + mx, y0 - my}, {x1 + mx, y1 + my}, {x0 - mx, y1 + my}};
  *drawn = difference_of({box}, *drawn);
  diag_.note_at(
      "warning: %IPNEG (deprecated negative image) applied: copper is the image's bounding box "
      "with gerbv's 5 % border, less what is drawn",
      image_.negative_line);
}

Paths GerberReader::evaluate(std::vector<Batch>& batches) {
  Paths result;
  for (Batch& b : batches) {
    if (result.empty()) {
      if (b.dark) result = union_objects(b.paths, b.starts, {});
    } else {
      // Only the polygons whose boxes meet the batch's box can change (a hole's box lies in
      // its outer's, so a hole left out stays inside its outer and still cuts it).
      Paths touched, kept;
      split_by_box(result, box_of(b.paths), touched, kept);
      for (const Path& p : touched) drawn_.reclipped += p.size();
      if (drawn_.reclipped > opt_.max_reclipped_vertices) {
        diag_.fail("the polarity changes re-clip more than " +
                   std::to_string(opt_.max_reclipped_vertices) +
                   " copper vertices (overlapping step-and-repeat copies with clear objects?): too "
                   "complex to read");
      }
      if (b.dark) {
        touched = union_objects(b.paths, b.starts, touched);
      } else if (!touched.empty()) {
        touched = difference_of(touched, union_objects(b.paths, b.starts, {}));
      }
      result.swap(kept);
      result.insert(result.end(), std::make_move_iterator(touched.begin()),
                    std::make_move_iterator(touched.end()));
    }
    Paths().swap(b.paths);
  }
  return result;
}

// ---------------------------------------------------------------------------------------------
// Extended (%...%) commands

void GerberReader::extended_block(const std::string& body, int first_line) {
  // Split into '*'-terminated commands, each with its line.
  std::vector<std::string> parts;
  std::vector<int> lines;
  int line = first_line;
  std::string cur;
  int cur_line = line;
  bool started = false;
  for (char c : body) {
    if (c == '*') {
      parts.push_back(cur);
      lines.push_back(cur_line);
      cur.clear();
      started = false;
      continue;
    }
    if (!started && !is_space(c)) {
      started = true;
      cur_line = line;
    }
    if (c == '\n') ++line;
    cur += c;
  }
  const std::string rest = trim(cur);
  if (!rest.empty()) {
    diag_.line = cur_line;
    // "%ADD181C,.031*X.015%" (gerbv's polarity/6_vbat.gbr): a size after an aperture
    // definition's '*'. gerbv reads the definition and skips the rest; so does this (the
    // aperture without the hole the size may have meant: more copper, never less).
    const bool size_after_ad = !parts.empty() && starts_with(trim(parts.back()), "AD") &&
                               rest.size() > 1 && rest[0] == 'X' &&
                               rest.find_first_not_of("0123456789.", 1) == std::string::npos;
    if (!size_after_ad)
      diag_.fail("'" + rest.substr(0, 40) + "' in a '%' block does not end with '*'");
    diag_.note("warning: '" + rest +
               "' after the aperture definition's '*' ignored, as gerbv "
               "ignores it");
  }
  if (parts.empty()) return;
  diag_.line = lines[0];
  if (starts_with(trim(parts[0]), "AM")) {
    aperture_macro(parts, lines);
    return;
  }
  for (size_t k = 0; k < parts.size(); ++k) {
    diag_.line = lines[k];
    const std::string cmd = trim(without_line_breaks(parts[k]));
    if (!cmd.empty()) extended_command(cmd);
  }
}

void GerberReader::extended_command(const std::string& cmd) {
  if (cmd.size() < 2) diag_.fail("unknown extended command '%" + cmd + "'");
  const std::string code = cmd.substr(0, 2);
  const std::string arg = cmd.substr(2);
  if (code == "IF") {  // read_gerber_file put a file's includes in place (gerber_include.h)
    diag_.fail(
        "include file %IF" + arg.substr(0, 40) +
        ": an include is read only from a file on disk, from its folder (not from an upload)");
  } else if (code == "FS") {
    format_spec(arg);
  } else if (code == "MO") {
    if (arg != "MM" && arg != "IN") diag_.fail("unit '" + arg + "' is neither MM nor IN");
    unit_.set(diag_, arg == "MM" ? 1e6 : 25.4e6, arg == "MM" ? "MOMM" : "MOIN");
  } else if (code == "AD") {
    aperture_definition(arg);
  } else if (code == "LP") {
    if (arg != "D" && arg != "C") diag_.fail("polarity '" + arg + "' is neither D nor C");
    gs_.dark = arg == "D";
  } else if (code == "SR") {
    step_repeat(arg);
  } else if (code == "TF" || code == "TA" || code == "TO" || code == "TD") {
    attribute(cmd);
  } else if (code == "LM" || code == "LR" || code == "LS") {
    const bool identity = (code == "LM" && arg == "N") ||
                          (code == "LR" && diag_.number(arg, "rotation") == 0) ||
                          (code == "LS" && diag_.number(arg, "scale") == 1);
    if (!identity) {
      diag_.fail("aperture transformation %" + cmd + " is not supported (only LMN, LR0, LS1)");
    }
  } else if (code == "AB") {
    aperture_block(arg);
  } else if (!deprecated_parameter(code, arg)) {
    diag_.fail("unknown extended command '%" + cmd.substr(0, 20) + "'");
  }
}

// The image parameters the specification deprecated, each as it says and as gerbv draws it;
// false if `code` is none of them.
bool GerberReader::deprecated_parameter(const std::string& code, const std::string& arg) {
  if (code == "IP") {
    image_polarity(arg);
  } else if (code == "IC") {
    // Input code: ASCII is what every reader reads (OrCAD, P-CAD, Mentor write %ICAS*%).
    if (arg != "AS") diag_.fail("input code %IC" + arg + " is not supported (only ASCII, %ICAS)");
    diag_.note("warning: %ICAS (deprecated input code: ASCII) ignored");
  } else if (code == "IN" || code == "LN") {
    diag_.note("%" + code + " (deprecated name) ignored");
  } else if (code == "MI") {
    mirror_image(arg);
  } else if (code == "SF") {
    const std::pair<double, double> ab = axis_values(arg, "scale factor", 1);
    if (!(ab.first > 0 && ab.first <= 1000 && ab.second > 0 && ab.second <= 1000))
      diag_.fail("scale factor %SF" + arg + " must be above 0 and at most 1000");
    image_.scale_a = ab.first;
    image_.scale_b = ab.second;
    image_transform("%SF" + arg, "scale factor", ab.first == 1 && ab.second == 1);
    if (ab.first == 1 && ab.second == 1) diag_.note("%SF with scale 1 (deprecated) ignored");
  } else if (code == "OF" || code == "IO") {
    image_offset(code, arg);
  } else if (code == "IR") {
    const double deg = diag_.number(arg, "image rotation");
    if (deg != 0 && deg != 90 && deg != 180 && deg != 270)
      diag_.fail("image rotation %IR" + arg + " must be 0, 90, 180 or 270");
    image_.rotation_deg = static_cast<int>(deg);
    image_transform("%IR" + arg, "image rotation", image_.rotation_deg == 0);
    if (image_.rotation_deg == 0) diag_.note("%IR0 (deprecated) ignored");
  } else if (code == "AS") {
    // Axis select: AYBX sends the file's X to the output's B (y) axis: x and y swap.
    if (arg != "AXBY" && arg != "AYBX")
      diag_.fail("axis select %AS" + arg + " is neither AXBY nor AYBX");
    image_.swap_ab = arg == "AYBX";
    image_transform("%AS" + arg, "axis select", !image_.swap_ab);
    if (!image_.swap_ab) diag_.note("%ASAXBY (deprecated) ignored");
  } else if (code == "KO") {
    if (arg.empty() && !knockout_.open)
      diag_.note("warning: %KO (deprecated knockout, off) ignored");
    if (arg.empty()) close_knockout();
    if (!arg.empty()) knockout(arg);
  } else if (code == "IJ") {
    image_justify(arg);
  } else if (code == "RO") {
    const double deg = diag_.number(arg, "layer rotation");
    if (!(std::fabs(deg) <= 360))
      diag_.fail("layer rotation %RO" + arg + " must be -360 .. 360 degrees");
    image_.layer_rotation_deg = deg;
    image_transform("%RO" + arg, "layer rotation", deg == 0);
    if (deg == 0) diag_.note("%RO0 (deprecated) ignored");
  } else {
    return false;
  }
  return true;
}

// %IPPOS / %IPNEG: one polarity per image; a later %IP replaces an earlier (gerbv keeps the
// last).
void GerberReader::image_polarity(const std::string& arg) {
  if (arg == "NEG") {
    // What is drawn is clear, the rest copper. The copper's extent is not defined: here the
    // image's bounding box with gerbv's border, as gerbv fills its picture; isolation then
    // keeps the tool inside each drawn (clear) shape, off the copper around it.
    if (image_.negative)
      diag_.note("warning: %IPNEG replaced by the later %IPNEG (only the last applies)");
    image_.negative_line = diag_.line;
    image_.negative = true;
    return;
  }
  if (arg != "POS") diag_.fail("image polarity '" + arg + "' is neither POS nor NEG");
  if (image_.negative)
    diag_.note("warning: %IPNEG replaced by the later %IPPOS (only the last applies)");
  image_.negative = false;
  diag_.note("%IPPOS (deprecated image polarity) ignored");
}

// %MIA<0|1>B<0|1>: mirror x (A) and y (B) about the origin.
void GerberReader::mirror_image(const std::string& arg) {
  const std::string a = strip_all_space(arg);
  for (const char axis : {'A', 'B'}) {
    const size_t at = a.find(axis);
    if (at == std::string::npos) continue;
    const std::string v = a.substr(at + 1, 1);
    if (v != "0" && v != "1") diag_.fail("mirror image '%MI" + a + "': A and B take 0 or 1");
    (axis == 'A' ? image_.mirror_a : image_.mirror_b) = v == "1";
  }
  image_transform("%MI" + a, "mirror image", !image_.mirror_a && !image_.mirror_b);
  if (!image_.mirror_a && !image_.mirror_b)
    diag_.note("%MI without mirroring (deprecated) ignored");
}

// %IJ (image justify), as gerbv reads it: each axis L (lower left, the default), C (centre)
// or an offset in the current units (the axis then lower left); "AC" is gerbv's centre.
void GerberReader::image_justify(const std::string& arg) {
  image_.justify_a = image_.justify_b = 'L';
  image_.justify_offset_a_nm = image_.justify_offset_b_nm = 0;
  size_t k = 0;
  while (k < arg.size()) {
    const char axis = arg[k++];
    if ((axis != 'A' && axis != 'B') || k >= arg.size())
      diag_.fail("image justify %IJ" + arg + ": expected A or B, then L, C or an offset");
    char& type = axis == 'A' ? image_.justify_a : image_.justify_b;
    if (arg[k] == 'L' || arg[k] == 'C') {
      type = arg[k++];
      continue;
    }
    const size_t end = end_of_number(arg, k);
    const double v = diag_.number(arg.substr(k, end - k), "image justify offset");
    if (v != 0) unit_.need(diag_, "%IJ");
    (axis == 'A' ? image_.justify_offset_a_nm : image_.justify_offset_b_nm) = v * unit_.nm;
    k = end;
  }
  image_.justify = true;
  image_.justify_line = diag_.line;
  image_.justify_text = "%IJ" + arg.substr(0, 20);
}

// %IJ applied to the finished image: gerbv moves it by -min (L) or by half its extent (C,
// gerbv's reading: not onto the origin) of the drawn image's box, each axis, plus the offset.
void GerberReader::justify_image(Paths* image, const BoxNm& drawn) {
  if (!image_.justify || image->empty()) return;
  const auto shift = [](char type, double min, double max, double offset) {
    return (type == 'C' ? (max - min) / 2 : -min) + offset;
  };
  const double dx = shift(image_.justify_a, static_cast<double>(drawn.min_x),
                          static_cast<double>(drawn.max_x), image_.justify_offset_a_nm);
  const double dy = shift(image_.justify_b, static_cast<double>(drawn.min_y),
                          static_cast<double>(drawn.max_y), image_.justify_offset_b_nm);
  translate_paths(*image, static_cast<cInt>(std::llround(dx)), static_cast<cInt>(std::llround(dy)));
  char msg[200];
  std::snprintf(msg, sizeof msg,
                " (deprecated image justify) applied as gerbv does: the image moved by %.3f, "
                "%.3f mm",
                dx * 1e-6, dy * 1e-6);
  diag_.note_at("warning: " + image_.justify_text + msg, image_.justify_line);
}

// %OFA<a>B<b> (offset) and %IOA<a>B<b> (image offset): the image moved by a, b in the units
// current where it stands. A zero offset is an identity, which undoes an earlier one.
void GerberReader::image_offset(const std::string& code, const std::string& arg) {
  const std::pair<double, double> ab =
      axis_values(arg, code == "OF" ? "offset" : "image offset", 0);
  const bool none = ab.first == 0 && ab.second == 0;
  if (!none) unit_.need(diag_, "%" + code);
  bool replaces = false;
  for (const ImageParameters::Transform& t : image_.transforms)
    replaces = replaces || t.which.compare(1, 2, code) == 0;
  if (!none || replaces) {
    image_.offset_x = static_cast<cInt>(std::llround(ab.first * unit_.nm));
    image_.offset_y = static_cast<cInt>(std::llround(ab.second * unit_.nm));
  }
  image_transform("%" + code + arg, "image offset", none);
  if (none) diag_.note("%" + code + " without offset (deprecated) ignored");
}

// A deprecated transform of the whole image (identity: it does nothing). Of one parameter
// given twice the last applies (gerbv keeps the last value); the specification does not say in
// which order different ones combine, so a file with two is refused rather than guessed.
void GerberReader::image_transform(const std::string& which, const char* what, bool identity) {
  for (size_t k = 0; k < image_.transforms.size(); ++k) {
    if (image_.transforms[k].which.compare(0, 3, which, 0, 3) != 0) continue;
    diag_.note("warning: " + image_.transforms[k].which + " replaced by the later " + which +
               " (only the last applies)");
    if (identity)
      image_.transforms.erase(image_.transforms.begin() + static_cast<long>(k));
    else
      image_.transforms[k] = {which, what, diag_.line};
    return;
  }
  if (identity) return;
  image_.transforms.push_back({which, what, diag_.line});
}

// Two different transforms still in force at the end (each parameter acts on the whole image,
// so only the last value of each counts: a later identity undoes an earlier one) are refused
// at the later one, unless nothing is drawn.
void GerberReader::check_image_transforms(bool drawn) {
  if (image_.transforms.size() < 2 || !drawn) return;
  std::vector<ImageParameters::Transform> in_order = image_.transforms;
  std::sort(in_order.begin(), in_order.end(),
            [](const auto& a, const auto& b) { return a.line < b.line; });
  std::string names;
  for (size_t k = 0; k < in_order.size(); ++k)
    names += (k == 0 ? "" : k + 1 == in_order.size() ? " and " : ", ") + in_order[k].which;
  diag_.line = in_order.back().line;
  diag_.fail("the deprecated image transforms " + names +
             " together are not supported (the order they combine in is not defined)");
}

// "A<a>B<b>" (either may be left out: `missing`), decimal numbers.
std::pair<double, double> GerberReader::axis_values(const std::string& arg, const char* what,
                                                    double missing) const {
  double a = missing, b = missing;
  // Anything else (%IOX1Y2, a letter twice) is a parameter the file does not say: refused, not
  // read as no offset.
  if ((!arg.empty() && arg[0] != 'A' && arg[0] != 'B') ||
      std::count(arg.begin(), arg.end(), 'A') > 1 || std::count(arg.begin(), arg.end(), 'B') > 1)
    diag_.fail(std::string("bad ") + what + " '" + arg.substr(0, 20) + "': expected A<a>B<b>");
  for (const char axis : {'A', 'B'}) {
    const size_t at = arg.find(axis);
    if (at == std::string::npos) continue;
    size_t end = at + 1;
    while (end < arg.size() && arg[end] != 'A' && arg[end] != 'B') ++end;
    (axis == 'A' ? a : b) = diag_.number(arg.substr(at + 1, end - at - 1), what);
  }
  return {a, b};
}

// %KOCX<x>Y<y>I<w>J<h>: the box from (x, y), w wide and h high (current units), cleared (C)
// or filled (D) where it stands in the drawing order, as gerbv draws it. Without a box the
// knockout surrounds the objects that follow by a border: refused.
void GerberReader::knockout(const std::string& arg) {
  const char polarity = arg[0];
  if (polarity != 'C' && polarity != 'D')
    diag_.fail("%KO" + arg.substr(0, 20) +
               " (deprecated knockout): the polarity is neither C nor D");
  close_knockout();  // a knockout ends where the next begins
  const size_t letters_given =
      (arg.find('X') != std::string::npos) + (arg.find('Y') != std::string::npos) +
      (arg.find('I') != std::string::npos) + (arg.find('J') != std::string::npos);
  if (arg.size() == 1) {
    // Neither a box nor a border: the specification gives it no area, gerbv draws nothing.
    diag_.note("warning: %KO" + arg +
               " without a box or a border (deprecated knockout) ignored, as gerbv reads it");
    return;
  }
  if (letters_given == 0) {
    open_knockout(arg);
    return;
  }
  if (letters_given != 4)
    diag_.fail("%KO" + arg.substr(0, 20) +
               " (deprecated knockout): a box needs all of X, Y, I and J, a border alone K");
  double v[4] = {0, 0, 0, 0};
  const char* letters = "XYIJ";
  for (int k = 0; k < 4; ++k) {
    const size_t at = arg.find(letters[k]);
    size_t end = at + 1;
    while (end < arg.size() && std::string("XYIJ").find(arg[end]) == std::string::npos) ++end;
    v[k] = diag_.number(arg.substr(at + 1, end - at - 1), "knockout box");
  }
  unit_.need(diag_, "%KO");
  if (!(v[2] > 0 && v[3] > 0))
    diag_.fail("%KO" + arg.substr(0, 20) + ": the box needs a size above 0");
  for (double x : v)
    if (!(std::fabs(x * unit_.nm) <= kMaxApertureNm * 10)) diag_.fail("%KO box beyond 10 m");
  const bool dark = gs_.dark;
  gs_.dark = polarity == 'D';
  add_object({rect_path({(v[0] + v[2] / 2) * unit_.nm, (v[1] + v[3] / 2) * unit_.nm},
                        v[2] * unit_.nm, v[3] * unit_.nm)});
  gs_.dark = dark;
  diag_.note(polarity == 'C'
                 ? "warning: %KOC box (deprecated knockout) applied: cleared where it "
                   "stands in the drawing order"
                 : "warning: %KOD box (deprecated knockout, dark) applied: copper where "
                   "it stands in the drawing order");
}

// %KOC[K<border>] or %KOD[K<border>] without a box: the objects that follow, up to the next
// %KO, get a box around them, grown by the border (current units), cleared (C) or filled (D)
// before them, as gerbv draws it.
void GerberReader::open_knockout(const std::string& arg) {
  double border = 0;
  const size_t k = arg.find('K');
  if (k != std::string::npos)
    border = diag_.number(arg.substr(k + 1), "knockout border");
  else if (arg.size() > 1)
    diag_.fail("%KO" + arg.substr(0, 20) + " (deprecated knockout): bad parameters");
  unit_.need(diag_, "%KO");
  if (!(border >= 0 && border * unit_.nm <= kMaxApertureNm))
    diag_.fail("%KO" + arg.substr(0, 20) + ": the border must be 0 .. 1 m");
  if (sr_.active || !blocks_.empty())
    diag_.fail("a knockout around objects (%KO" + arg.substr(0, 20) +
               ") inside a step-and-repeat or a block aperture is not supported");
  knockout_.open = true;
  knockout_.dark = arg[0] == 'D';
  knockout_.border_nm = border * unit_.nm;
  knockout_.line = diag_.line;
  knockout_.start = drawn_.batches.size();
  drawn_.batches.push_back(
      {gs_.dark, {}, {}});  // the objects it surrounds start a batch of their own
}

// Ends an open knockout: its box goes in before the objects it surrounds.
void GerberReader::close_knockout() {
  if (!knockout_.open) return;
  knockout_.open = false;
  if (sr_.active || !blocks_.empty())
    diag_.fail(
        "a knockout around objects that ends inside a step-and-repeat or a block aperture is "
        "not supported");
  bool any = false;
  cInt x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  for (size_t b = knockout_.start; b < drawn_.batches.size(); ++b)
    for (const Path& p : drawn_.batches[b].paths)
      for (const IntPoint& v : p) {
        x0 = any ? std::min(x0, v.X) : v.X, x1 = any ? std::max(x1, v.X) : v.X;
        y0 = any ? std::min(y0, v.Y) : v.Y, y1 = any ? std::max(y1, v.Y) : v.Y;
        any = true;
      }
  if (!any) return;
  const cInt m = static_cast<cInt>(std::llround(knockout_.border_nm));
  Batch box;
  box.dark = knockout_.dark;
  box.paths = {{{x0 - m, y0 - m}, {x1 + m, y0 - m}, {x1 + m, y1 + m}, {x0 - m, y1 + m}}};
  box.starts = {0};
  count_vertices(4);
  drawn_.batches.insert(drawn_.batches.begin() + static_cast<long>(knockout_.start),
                        std::move(box));
  diag_.note_at(std::string("warning: %KO") + (knockout_.dark ? "D" : "C") +
                    " around the objects that follow (deprecated knockout) applied: their box "
                    "grown by the border " +
                    (knockout_.dark ? "filled" : "cleared") + " before them",
                knockout_.line);
}

// Scale, mirror, rotate about the origin; exact for the quarter turns and mirrors.
void GerberReader::transform_image(Paths& paths) const {
  if (image_.layer_rotation_deg != 0) {
    // %RO, alone (image_transform() refuses it with another): any angle, rounded to 1 nm.
    const double a = image_.layer_rotation_deg * M_PI / 180, c = std::cos(a), s = std::sin(a);
    for (Path& p : paths)
      for (IntPoint& v : p) {
        const double x = static_cast<double>(v.X), y = static_cast<double>(v.Y);
        v = IntPoint(static_cast<cInt>(std::llround(c * x - s * y)),
                     static_cast<cInt>(std::llround(s * x + c * y)));
      }
    return;
  }
  if (image_.swap_ab) {
    // Alone (image_transform() refuses it with another); a mirror: the orientation flips.
    for (Path& p : paths) {
      for (IntPoint& v : p) v = IntPoint(v.Y, v.X);
      ClipperLib::ReversePath(p);
    }
    return;
  }
  if (image_.rotation_deg == 0 && !image_.mirror_a && !image_.mirror_b && image_.scale_a == 1 &&
      image_.scale_b == 1)
    return;
  for (Path& p : paths) {
    for (IntPoint& v : p) {
      cInt x = image_.scale_a == 1 ? v.X : static_cast<cInt>(std::llround(v.X * image_.scale_a));
      cInt y = image_.scale_b == 1 ? v.Y : static_cast<cInt>(std::llround(v.Y * image_.scale_b));
      if (image_.mirror_a) x = -x;
      if (image_.mirror_b) y = -y;
      switch (image_.rotation_deg) {
        case 90:
          v = IntPoint(-y, x);
          break;
        case 180:
          v = IntPoint(-x, -y);
          break;
        case 270:
          v = IntPoint(y, -x);
          break;
        default:
          v = IntPoint(x, y);
      }
    }
    if (image_.mirror_a != image_.mirror_b)
      ClipperLib::ReversePath(p);  // a mirror flips orientation
  }
}

// %ABDnn*% opens a block aperture, %AB*% closes the innermost one: the objects drawn between
// become aperture Dnn, flashed like any aperture (at the flash point, their polarities kept,
// or all inverted when flashed with clear polarity).
void GerberReader::aperture_block(const std::string& arg) {
  if (sr_.active) diag_.fail("a block aperture (%AB) inside a step-and-repeat is not supported");
  if (!arg.empty()) {
    if (arg[0] != 'D' || arg.size() < 3 ||
        arg.find_first_not_of("0123456789", 1) != std::string::npos)
      diag_.fail("block aperture '%AB" + arg + "' needs an aperture number Dnn (10 or more)");
    const int n = std::stoi(arg.substr(1, 7));
    if (n < 10)
      diag_.fail("block aperture '%AB" + arg + "' needs an aperture number of 10 or more");
    if (blocks_.size() >= 16) diag_.fail("block apertures nested more than 16 deep");
    blocks_.push_back({n, drawn_.batches.size(), gs_.dark});
    drawn_.batches.push_back({gs_.dark, {}, {}});  // its objects start a batch of their own
    return;
  }
  if (blocks_.empty()) diag_.fail("%AB closes a block aperture that was never opened");
  const OpenBlock b = blocks_.back();
  blocks_.pop_back();
  Aperture ap;
  ap.type = 'B';
  ap.block.assign(
      std::make_move_iterator(drawn_.batches.begin() + static_cast<long>(b.batch_start)),
      std::make_move_iterator(drawn_.batches.end()));
  drawn_.batches.resize(b.batch_start);
  gs_.dark = b.dark;
  if (apertures_.defined.count(b.number_d))
    diag_.note("aperture D" + std::to_string(b.number_d) +
               " redefined by a block aperture: the block from here on");
  // Its uses are the block's; earlier %AD uses are still read with the last %AD (gerbv
  // draws those so and knows no blocks).
  apertures_.used.erase(b.number_d);
  apertures_.defined[b.number_d] = std::move(ap);
}

void GerberReader::format_spec(const std::string& s) {
  // [L|T|D][A|I][Nn][Gn]XabYab[Dn][Mn]
  size_t k = 0;
  fmt_.omit_trailing = false;
  fmt_.incremental = false;
  if (k < s.size() && (s[k] == 'L' || s[k] == 'T' || s[k] == 'D')) {
    fmt_.omit_trailing = s[k] == 'T';
    if (fmt_.omit_trailing) diag_.note("trailing-zero omission in %FS (deprecated)");
    ++k;
  }
  if (k < s.size() && (s[k] == 'A' || s[k] == 'I')) {
    fmt_.incremental = s[k] == 'I';
    if (fmt_.incremental) diag_.note("incremental coordinates in %FS (deprecated)");
    ++k;
  }
  while (k < s.size() && (s[k] == 'N' || s[k] == 'G')) {  // sequence and G-code digits (old)
    k += 2;
  }
  auto digits = [&](char axis, int& integer, int& decimals) {
    if (k + 2 >= s.size() + 0 || s[k] != axis ||
        !std::isdigit(static_cast<unsigned char>(s[k + 1])) ||
        !std::isdigit(static_cast<unsigned char>(s[k + 2]))) {
      diag_.fail("format '%FS" + s + "' needs " + axis + " with two digits (like X46)");
    }
    integer = s[k + 1] - '0';
    decimals = s[k + 2] - '0';
    if (decimals > 7 || integer + decimals > 14) diag_.fail("format '%FS" + s + "' out of range");
    k += 3;
  };
  digits('X', fmt_.x_int, fmt_.x_dec);
  digits('Y', fmt_.y_int, fmt_.y_dec);
  fmt_.given = true;
}

// A definition whose parameters cannot be read (old writers' "R,0.03260.326") is refused
// where the aperture is used, as gerbv leaves an unusable aperture out: a file that never
// uses it reads, with a warning.
void GerberReader::aperture_definition(const std::string& s) {
  // D<n><template>[,<p1>X<p2>...]
  if (s.empty() || s[0] != 'D') diag_.fail("aperture definition '%AD" + s + "' without D number");
  size_t k = 1;
  while (k < s.size() && std::isdigit(static_cast<unsigned char>(s[k]))) ++k;
  if (k == 1 || k > 8) diag_.fail("aperture definition '%AD" + s + "' has a bad D number");
  const int number_d = std::stoi(s.substr(1, k - 1));
  apertures_.refused.erase(number_d);
  const auto last = last_definitions_.find(number_d);
  try {
    define_aperture(last == last_definitions_.end() ? s : last->second.text, k, number_d);
  } catch (const PcbReadError& e) {
    if (s.find(',', k) == std::string::npos) throw;  // no parameters: nothing to defer
    apertures_.defined.erase(number_d);
    std::string why = e.what();  // "PATH:LINE: what": kept as "line LINE: what"
    if (why.compare(0, diag_.path.size() + 1, diag_.path + ":") == 0)
      why = "line " + why.substr(diag_.path.size() + 1);
    apertures_.refused[number_d] = why;
  }
}

void GerberReader::define_aperture(const std::string& s, size_t k, int number_d) {
  const size_t comma = s.find(',', k);
  const std::string name =
      trim(s.substr(k, comma == std::string::npos ? std::string::npos : comma - k));
  std::vector<double> params;
  if (comma != std::string::npos) {
    std::vector<std::string> words = split(s.substr(comma + 1), 'X');
    const bool standard = name == "C" || name == "R" || name == "O" || name == "P";
    if (standard && words.size() > 1 && trim(words.back()).empty()) {
      // "%ADD14C,0.1X*%" (gerbv's exposure/example.grb): gerbv splits with strtok, which
      // skips the empty parameter.
      diag_.note("warning: aperture D" + std::to_string(number_d) +
                 ": an empty last parameter ignored, as gerbv does");
      words.pop_back();
    }
    for (const std::string& p : words) {
      params.push_back(diag_.number(trim(p), "aperture parameter"));
    }
    if (name == "P" && params.size() == 6) {
      // "P,0.040X10X25X0.025X0.025X0.0150" (gerbv's test-aperture-polygon-flash-1.gbx):
      // gerbv reads five parameters (the last two a rectangular hole) and ignores the sixth.
      diag_.note("warning: polygon aperture D" + std::to_string(number_d) +
                 ": a sixth parameter ignored, as gerbv does");
      params.pop_back();
    }
  }
  if (name.empty()) diag_.fail("aperture D" + std::to_string(number_d) + " has no template name");
  unit_.need(diag_, "aperture D" + std::to_string(number_d));
  Aperture ap;
  if (name == "C" || name == "R" || name == "O" || name == "P") {
    check_standard_sizes(name, params, number_d);
    size_t hole_at = 0;
    ap = standard_aperture(name, params, number_d, &hole_at);
    if (params.size() > hole_at) punch_hole(&ap, params, hole_at);
  } else {
    ap = macro_aperture(name, params, number_d);
  }
  note_redefinition(number_d, ap, s);
  apertures_.defined[number_d] = std::move(ap);
}

// A D code defined twice: gerbv (and pcb2gcode, which reads with it) draws every use with the
// last definition, those before it too. Said which one is used; a definition that changes
// the aperture after it drew is read again from the start (read()) so that it is gerbv's.
void GerberReader::note_redefinition(int number_d, const Aperture& ap, const std::string& text) {
  const std::string d = "aperture D" + std::to_string(number_d);
  const auto last = last_definitions_.find(number_d);
  const auto earlier = apertures_.defined.find(number_d);
  apertures_.last[number_d] = ApertureDefinitionText{text, diag_.line};
  if (earlier == apertures_.defined.end()) {
    if (last != last_definitions_.end())
      diag_.note(d + " defined again at line " + std::to_string(last->second.line) +
                 " after it drew: every use takes that last definition, those before it too, "
                 "as gerbv draws them");
    apertures_.used.erase(number_d);
    return;
  }
  if (last != last_definitions_.end()) return;  // the last definition everywhere: said above
  const Aperture& was = earlier->second;
  if (was.type == ap.type && was.circle_d_nm == ap.circle_d_nm && was.shape == ap.shape &&
      was.has_hole == ap.has_hole && was.block.empty() && ap.block.empty()) {
    diag_.note(d + " defined again, the same as before: nothing changes");
    return;
  }
  if (apertures_.used.count(number_d)) {
    apertures_.redefined_after_use.insert(number_d);
  } else {
    diag_.note(d +
               " redefined before anything was drawn with it: this later definition is "
               "used, as gerbv uses it");
  }
  apertures_.used.erase(number_d);
}

// Only lengths are sizes: a polygon's vertex count and rotation are not (nor a macro's
// parameters, angles among them: 45 deg is not 1.1 m in an inch file; a macro's shape is
// checked once evaluated).
void GerberReader::check_standard_sizes(const std::string& name, const std::vector<double>& params,
                                        int number_d) const {
  for (size_t i = 0; i < params.size(); ++i) {
    const bool length = name != "P" || i == 0 || i >= 3;
    if (length && !(std::fabs(params[i] * unit_.nm) <= kMaxApertureNm)) {
      diag_.fail("aperture D" + std::to_string(number_d) + " is larger than 1 m");
    }
    if (!std::isfinite(params[i]))
      diag_.fail("aperture D" + std::to_string(number_d) + ": bad number");
  }
}

// C, R, O or P; *hole_at: where its hole's parameters start.
Aperture GerberReader::standard_aperture(const std::string& name, const std::vector<double>& params,
                                         int number_d, size_t* hole_at_out) {
  const double u = unit_.nm, tol = opt_.arc_tolerance_nm;
  Aperture ap;
  auto need = [&](size_t lo, size_t hi) {
    if (params.size() < lo || params.size() > hi) {
      diag_.fail("aperture D" + std::to_string(number_d) + " " + name + " takes " +
                 std::to_string(lo) + (lo == hi ? "" : " to " + std::to_string(hi)) +
                 " parameters, got " + std::to_string(params.size()));
    }
    for (size_t i = 0; i < params.size(); ++i) {
      // A polygon's rotation (its third parameter) may be negative: clockwise.
      if (params[i] < 0 && !(name == "P" && i == 2))
        diag_.fail("aperture D" + std::to_string(number_d) + " has a negative size");
    }
  };
  size_t hole_at = 0;
  if (name == "C") {
    need(1, 3);
    ap.type = 'C';
    ap.circle_d_nm = params[0] * u;
    if (ap.circle_d_nm > 0) ap.shape.push_back(circle_path({0, 0}, ap.circle_d_nm, tol));
    hole_at = 1;
  } else if ((name == "R" || name == "O") && params.size() == 1) {
    // One size: the specification wants X and Y; gerbv draws a rectangle of no height
    // (nothing). Read as the square (or circle) it most likely is: more copper, never less,
    // so the isolation keeps off whatever the writer meant.
    ap.type = name[0];
    const double w = params[0] * u;
    if (w < 0) diag_.fail("aperture D" + std::to_string(number_d) + " has a negative size");
    if (w > 0)
      ap.shape.push_back(name == "R" ? rect_path({0, 0}, w, w) : circle_path({0, 0}, w, tol));
    diag_.note("warning: aperture D" + std::to_string(number_d) + " " + name +
               " has one size, not X and Y: read as " + (name == "R" ? "a square" : "a circle") +
               " of that size (gerbv draws nothing)");
    hole_at = 1;
  } else if (name == "R" || name == "O") {
    need(2, 4);
    ap.type = name[0];
    const double w = params[0] * u, h = params[1] * u;
    if (w > 0 && h > 0) {
      ap.shape.push_back(name == "R" ? rect_path({0, 0}, w, h) : obround_path({0, 0}, w, h, tol));
    }
    hole_at = 2;
  } else if (name == "P") {
    need(2, 5);
    ap.type = 'P';
    const double vertices = params[1];
    if (!(vertices >= 3 && vertices <= 12) || vertices != std::floor(vertices)) {
      diag_.fail("polygon aperture D" + std::to_string(number_d) + " needs 3 to 12 vertices");
    }
    const double rot = params.size() > 2 ? params[2] : 0;
    if (params[0] > 0) {
      ap.shape.push_back(
          regular_polygon_path({0, 0}, params[0] * u, static_cast<int>(vertices), rot));
    }
    hole_at = 3;
  }
  *hole_at_out = hole_at;
  return ap;
}

// A standard aperture's hole: a circle (one parameter) or a rectangle (two, deprecated).
void GerberReader::punch_hole(Aperture* ap, const std::vector<double>& params, size_t hole_at) {
  const double u = unit_.nm, tol = opt_.arc_tolerance_nm;
  Path hole;
  if (params.size() == hole_at + 1) {
    hole = circle_path({0, 0}, params[hole_at] * u, tol);
  } else {
    hole = rect_path({0, 0}, params[hole_at] * u, params[hole_at + 1] * u);
    diag_.note("rectangular aperture hole (deprecated)");
  }
  if (params[hole_at] > 0) {
    ap->shape = difference_of(ap->shape, {hole});
    ap->has_hole = true;
  }
}

// An aperture from a macro defined before it, its shape checked once evaluated.
Aperture GerberReader::macro_aperture(const std::string& name, const std::vector<double>& params,
                                      int number_d) {
  const double u = unit_.nm, tol = opt_.arc_tolerance_nm;
  Aperture ap;
  auto m = apertures_.macros.find(name);
  if (m == apertures_.macros.end()) {
    diag_.fail("aperture D" + std::to_string(number_d) + " uses '" + name +
               "', which is neither C, R, O, P nor a macro defined before it");
  }
  ap.type = 'M';
  try {
    ap.shape = evaluate_macro(m->second, params, u, tol);
  } catch (const MacroError& e) {
    diag_.fail(std::string(e.what()) + " (macro statement at line " + std::to_string(e.line) + ")");
  }
  for (const Path& p : ap.shape) {
    for (const IntPoint& v : p) {
      if (std::fabs(static_cast<double>(v.X)) > kMaxApertureNm ||
          std::fabs(static_cast<double>(v.Y)) > kMaxApertureNm)
        diag_.fail("aperture D" + std::to_string(number_d) + " is larger than 1 m");
    }
  }
  return ap;
}

void GerberReader::aperture_macro(const std::vector<std::string>& parts,
                                  const std::vector<int>& lines) {
  ApertureMacro m;
  m.name = trim(without_line_breaks(parts[0])).substr(2);
  m.line = lines[0];
  if (m.name.empty()) diag_.fail("aperture macro without a name");
  for (size_t k = 1; k < parts.size(); ++k) {
    const std::string st = strip_all_space(parts[k]);
    if (st.empty()) continue;
    if (st[0] == '0' &&
        (st.size() == 1 || st[1] == ' ' || !std::isdigit(static_cast<unsigned char>(st[1])))) {
      continue;  // comment primitive
    }
    const std::string raw = trim(parts[k]);
    if (raw.size() > 1 && raw[0] == '0' && is_space(raw[1])) continue;
    m.statements.push_back({lines[k], st});
  }
  apertures_.macros[m.name] = std::move(m);
}

void GerberReader::step_repeat(const std::string& s) {
  if (sr_.active) close_step_repeat();
  if (s.empty()) return;
  if (!blocks_.empty())
    diag_.fail("a step-and-repeat inside a block aperture (%AB) is not supported");
  double x = 1, y = 1, i = 0, j = 0;
  size_t k = 0;
  while (k < s.size()) {
    const char axis = s[k];
    size_t end = k + 1;
    while (end < s.size() && !std::isalpha(static_cast<unsigned char>(s[end]))) ++end;
    const double v = diag_.number(s.substr(k + 1, end - k - 1), "step-and-repeat value");
    if (axis == 'X') {
      x = v;
    } else if (axis == 'Y') {
      y = v;
    } else if (axis == 'I') {
      i = v;
    } else if (axis == 'J') {
      j = v;
    } else {
      diag_.fail("step-and-repeat '%SR" + s + "': unexpected '" + std::string(1, axis) + "'");
    }
    k = end;
  }
  if (!(x >= 1 && y >= 1) || x != std::floor(x) || y != std::floor(y)) {
    diag_.fail("step-and-repeat '%SR" + s + "' needs whole repeat counts of at least 1");
  }
  if (x * y > kMaxStepRepeatCopies) {
    diag_.fail("step-and-repeat '%SR" + s + "' makes more than " +
               std::to_string(kMaxStepRepeatCopies) + " copies");
  }
  if (x == 1 && y == 1) return;
  unit_.need(diag_, "step-and-repeat");
  if (!(std::fabs(i * unit_.nm * x) <= kMaxCoordNm && std::fabs(j * unit_.nm * y) <= kMaxCoordNm)) {
    diag_.fail("step-and-repeat '%SR" + s + "' reaches beyond 10 m");
  }
  sr_.active = true;
  sr_.x = static_cast<long>(x);
  sr_.y = static_cast<long>(y);
  sr_.x_saved = sr_.x;
  sr_.y_saved = sr_.y;
  sr_.i = static_cast<cInt>(std::llround(i * unit_.nm));
  sr_.j = static_cast<cInt>(std::llround(j * unit_.nm));
  drawn_.batches.push_back({gs_.dark, {}, {}});
  sr_.batch_start = drawn_.batches.size() - 1;
  sr_.stroke_start = drawn_.strokes.size();
  drawn_.stroke_open = false;
}

void GerberReader::close_step_repeat() {
  sr_.active = false;
  std::vector<Batch> block(drawn_.batches.begin() + static_cast<long>(sr_.batch_start),
                           drawn_.batches.end());
  drawn_.batches.resize(sr_.batch_start);
  std::vector<Path> block_strokes(drawn_.strokes.begin() + static_cast<long>(sr_.stroke_start),
                                  drawn_.strokes.end());
  drawn_.strokes.resize(sr_.stroke_start);
  std::vector<double> block_widths(
      drawn_.stroke_widths_nm.begin() + static_cast<long>(sr_.stroke_start),
      drawn_.stroke_widths_nm.end());
  drawn_.stroke_widths_nm.resize(sr_.stroke_start);
  if (copies_stand_alone(block)) {
    // Each copy's clear objects can only clear its own dark ones: evaluate the block once
    // and add the copies as dark objects (the polarity changes are not repeated per copy).
    Batch copies{true, {}, {}};
    const Paths shape = evaluate(block);
    for (long iy = 0; iy < sr_.y; ++iy) {
      for (long ix = 0; ix < sr_.x; ++ix) {
        if (ix != 0 || iy != 0) {
          for (const Path& p : shape) count_vertices(p.size());
        }
        Paths copy = shape;
        translate_paths(copy, sr_.i * ix, sr_.j * iy);
        copies.starts.push_back(copies.paths.size());
        copies.paths.insert(copies.paths.end(), copy.begin(), copy.end());
      }
    }
    block.clear();
    if (!copies.paths.empty()) block.push_back(std::move(copies));
    sr_.x = sr_.y = 1;  // the loop below now adds the one batch and the strokes' copies
    for (long iy = 0; iy < sr_.y_saved; ++iy) {
      for (long ix = 0; ix < sr_.x_saved; ++ix) {
        if (ix != 0 || iy != 0) {
          for (const Path& p : block_strokes) count_vertices(p.size());
        }
        Paths copy(block_strokes.begin(), block_strokes.end());
        translate_paths(copy, sr_.i * ix, sr_.j * iy);
        drawn_.strokes.insert(drawn_.strokes.end(), copy.begin(), copy.end());
        drawn_.stroke_widths_nm.insert(drawn_.stroke_widths_nm.end(), block_widths.begin(),
                                       block_widths.end());
      }
    }
    block_strokes.clear();
    block_widths.clear();
  }
  for (long iy = 0; iy < sr_.y; ++iy) {
    for (long ix = 0; ix < sr_.x; ++ix) {
      for (const Batch& b : block) {
        if (ix != 0 || iy != 0) {
          for (const Path& p : b.paths) count_vertices(p.size());
        }
        Paths copy = b.paths;
        translate_paths(copy, sr_.i * ix, sr_.j * iy);
        if (drawn_.batches.empty() || drawn_.batches.back().dark != b.dark) {
          drawn_.batches.push_back({b.dark, {}, {}});
        }
        Batch& dst = drawn_.batches.back();
        for (size_t start : b.starts) dst.starts.push_back(dst.paths.size() + start);
        dst.paths.insert(dst.paths.end(), copy.begin(), copy.end());
      }
      Paths copy(block_strokes.begin(), block_strokes.end());
      if (ix != 0 || iy != 0) {
        for (const Path& p : copy) count_vertices(p.size());
      }
      translate_paths(copy, sr_.i * ix, sr_.j * iy);
      drawn_.strokes.insert(drawn_.strokes.end(), copy.begin(), copy.end());
      drawn_.stroke_widths_nm.insert(drawn_.stroke_widths_nm.end(), block_widths.begin(),
                                     block_widths.end());
    }
  }
  drawn_.stroke_open = false;
}

// True when the copies cannot touch each other or what was drawn before the block (their
// boxes are apart), so that polarity inside the block only acts within each copy.
bool GerberReader::copies_stand_alone(const std::vector<Batch>& block) const {
  bool has_clear = false;
  for (const Batch& b : block) has_clear |= !b.dark;
  if (!has_clear) return false;  // all dark: the ordinary path is already linear
  struct Box {
    bool empty = true;
    cInt x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    void add(const IntPoint& p) {
      if (empty) {
        x0 = x1 = p.X, y0 = y1 = p.Y, empty = false;
        return;
      }
      x0 = std::min(x0, p.X), x1 = std::max(x1, p.X), y0 = std::min(y0, p.Y),
      y1 = std::max(y1, p.Y);
    }
  };
  Box blk;
  for (const Batch& b : block) {
    for (const Path& p : b.paths) {
      for (const IntPoint& q : p) blk.add(q);
    }
  }
  if (blk.empty) return false;
  const cInt w = blk.x1 - blk.x0, h = blk.y1 - blk.y0;
  if (sr_.x > 1 && std::llabs(sr_.i) <= w) return false;
  if (sr_.y > 1 && std::llabs(sr_.j) <= h) return false;
  // The whole array against everything drawn before it.
  const cInt ax0 = blk.x0 + std::min<cInt>(0, sr_.i * (sr_.x - 1));
  const cInt ax1 = blk.x1 + std::max<cInt>(0, sr_.i * (sr_.x - 1));
  const cInt ay0 = blk.y0 + std::min<cInt>(0, sr_.j * (sr_.y - 1));
  const cInt ay1 = blk.y1 + std::max<cInt>(0, sr_.j * (sr_.y - 1));
  Box before;
  for (size_t k = 0; k < sr_.batch_start; ++k) {
    for (const Path& p : drawn_.batches[k].paths) {
      for (const IntPoint& q : p) before.add(q);
    }
  }
  return before.empty || before.x1 < ax0 || before.x0 > ax1 || before.y1 < ay0 || before.y0 > ay1;
}

void GerberReader::attribute(const std::string& body) {
  // TF.FileFunction,Copper,L1,Top  (also from "G04 #@! TF...")
  if (!starts_with(body, "TF.FileFunction") && !starts_with(body, "TF,.FileFunction")) return;
  const size_t comma = body.find(',', 3);
  if (comma == std::string::npos) return;
  std::vector<std::string> f = split(body.substr(comma + 1), ',');
  std::string value;
  for (const std::string& field : f) value += (value.empty() ? "" : ",") + trim(field);
  diag_.note("X2 TF.FileFunction " + value);
  x2_kind_given_ = true;
  x2_kind_ = layer_kind_from_file_function(value);
  if (trim(f[0]) == "Copper" && x2_kind_ == LayerKind::kUnknown)
    diag_.note("an inner copper layer: this machine engraves the outer ones");
}

// ---------------------------------------------------------------------------------------------
// Data blocks

void GerberReader::comment(const std::string& text) {
  // KiCad 5 writes X2 attributes as comments: "G04 #@! TF.FileFunction,Copper,L1,Top".
  const std::string t = trim(text);
  if (starts_with(t, "#@!")) attribute(trim(t.substr(3)));
}

void GerberReader::word_block(const std::string& raw) {
  const std::string lead = trim(raw);
  if (starts_with(lead, "G04") ||
      (starts_with(lead, "G4") &&
       (lead.size() == 2 || !std::isdigit(static_cast<unsigned char>(lead[2]))))) {
    comment(lead.substr(lead[2] == '4' ? 3 : 2));
    return;
  }
  const std::string w = strip_all_space(raw);
  if (w.empty()) return;
  const std::string *x = nullptr, *y = nullptr, *i = nullptr, *j = nullptr;
  std::string xs, ys, is, js;
  int d = -1;
  size_t k = 0;
  while (k < w.size()) {
    const char letter = w[k];
    const size_t end = end_of_number(w, k + 1);
    const std::string value = w.substr(k + 1, end - k - 1);
    if (value.empty()) {
      diag_.fail("unexpected '" + std::string(1, letter) + "' in '" + w.substr(0, 40) + "'");
    }
    auto code = [&]() {
      if (value.size() > 6 || value.find_first_not_of("0123456789") != std::string::npos) {
        diag_.fail("bad code '" + std::string(1, letter) + value + "'");
      }
      return std::stoi(value);
    };
    switch (letter) {
      case 'G':
        g_code(code(), value);
        break;
      case 'D':
        d_code(code(), value, &d);
        break;
      case 'M':
        m_code(code(), value);
        break;
      case 'X':
        xs = value;
        x = &xs;
        break;
      case 'Y':
        ys = value;
        y = &ys;
        break;
      case 'I':
        is = value;
        i = &is;
        break;
      case 'J':
        js = value;
        j = &js;
        break;
      default:
        diag_.fail("unexpected '" + std::string(1, letter) + "' in '" + w.substr(0, 40) + "'");
    }
    k = end;
  }
  if (d == -1 && (x || y || i || j)) {
    if (gs_.last_d == 0) {
      // Undefined by the spec; gerbv's aperture starts off, so these only move the point.
      diag_.note(
          "warning: coordinates without D01/D02/D03 before any operation: read as a move "
          "(D02), as gerbv reads them");
      d = 2;
    } else {
      diag_.note("coordinates without an operation code: the previous D0" +
                 std::to_string(gs_.last_d) + " repeats (deprecated)");
      d = gs_.last_d;
    }
  }
  if (d != -1) operate(d, x, y, i, j);
}

// A G code of a data block: interpolation, regions, quadrants, and the deprecated ones.
void GerberReader::g_code(int g, const std::string& value) {
  if (g == 1 || g == 2 || g == 3) {
    gs_.interpolation = g;
  } else if (g == 36) {
    if (gs_.region) diag_.fail("G36 inside a region (missing G37)");
    gs_.region = true;
    gs_.contour.clear();
    gs_.contour_as_gerbv.clear();
  } else if (g == 37) {
    if (!gs_.region) diag_.fail("G37 without G36");
    finish_contour();
    gs_.region = false;
  } else if (g == 74 || g == 75) {
    gs_.quadrant = g;
    if (g == 74) diag_.note("G74 single-quadrant arcs (deprecated)");
  } else if (g == 54 || g == 55) {
    diag_.note("G" + value + " before an aperture number (deprecated) ignored");
  } else if (g == 70 || g == 71) {
    diag_.note(g == 70 ? "G70 inch units (deprecated)" : "G71 millimetre units (deprecated)");
    unit_.set(diag_, g == 70 ? 25.4e6 : 1e6, g == 70 ? "G70" : "G71");
  } else if (g == 90 || g == 91) {
    fmt_.incremental = g == 91;
    diag_.note(g == 90 ? "G90 absolute coordinates (deprecated)"
                       : "G91 incremental coordinates (deprecated)");
  } else {
    diag_.fail("unknown or unsupported G code G" + value);
  }
}

// D01/D02/D03 (the block's operation, into *d), or an aperture selected.
void GerberReader::d_code(int dn, const std::string& value, int* d) {
  if (dn >= 1 && dn <= 3) {
    if (*d != -1) diag_.fail("two operations (D01/D02/D03) in one block");
    *d = dn;
    return;
  }
  // Select an aperture (D10 and up; lower numbers in old files).
  if (apertures_.refused.count(dn))
    diag_.fail("D" + value +
               " selects an aperture whose definition was refused: " + apertures_.refused[dn]);
  if (!apertures_.defined.count(dn))
    diag_.fail("D" + value + " selects an aperture that is not defined");
  if (gs_.region) diag_.note("an aperture selected inside a region (not allowed by the spec)");
  gs_.aperture = dn;
}

// M02 ends the file; M00/M01 (stops) are ignored.
void GerberReader::m_code(int m, const std::string& value) {
  if (m == 2) {
    if (sr_.active) close_step_repeat();
    gs_.done = true;
  } else if (m == 0 || m == 1) {
    diag_.note("M0" + value.substr(value.size() - 1) + " (deprecated stop) ignored");
  } else {
    diag_.fail("unknown M code M" + value);
  }
}

cInt GerberReader::coordinate(const std::string& s, bool is_x) {
  if (!fmt_.given) diag_.fail("coordinates before the format (%FS)");
  unit_.need(diag_, "coordinates");
  const int integer = is_x ? fmt_.x_int : fmt_.y_int, decimals = is_x ? fmt_.x_dec : fmt_.y_dec;
  double nm = 0;
  if (s.find('.') != std::string::npos) {
    nm = diag_.number(s, "coordinate") * unit_.nm;
  } else {
    size_t k = 0;
    bool negative = false;
    if (k < s.size() && (s[k] == '+' || s[k] == '-')) negative = s[k++] == '-';
    std::string digits = s.substr(k);
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos ||
        digits.size() > 15) {
      diag_.fail(std::string("bad ") + (is_x ? "X" : "Y") + " coordinate '" + s + "'");
    }
    if (fmt_.omit_trailing) {
      while (static_cast<int>(digits.size()) < integer + decimals) digits += '0';
    }
    const long long v = std::stoll(digits);
    nm = static_cast<double>(v) * unit_.nm;
    for (int q = 0; q < decimals; ++q) nm /= 10;
    if (negative) nm = -nm;
  }
  if (!(std::fabs(nm) <= kMaxCoordNm)) diag_.fail("coordinate '" + s + "' is beyond 10 m");
  return static_cast<cInt>(std::llround(nm));
}

const Aperture& GerberReader::current_aperture() const {
  if (gs_.aperture < 0) diag_.fail("drawing or flashing before any aperture is selected (Dnn)");
  return apertures_.defined.at(gs_.aperture);
}

void GerberReader::count_vertices(size_t n) {
  drawn_.vertices += n;
  if (drawn_.vertices > opt_.max_vertices) {
    diag_.fail("the copper needs more than " + std::to_string(opt_.max_vertices) +
               " polygon vertices: too complex to read");
  }
}

void GerberReader::add_object(Paths paths) {
  if (paths.empty()) return;
  size_t n = 0;
  for (const Path& p : paths) n += p.size();
  count_vertices(n);
  if (drawn_.batches.empty() || drawn_.batches.back().dark != gs_.dark)
    drawn_.batches.push_back({gs_.dark, {}, {}});
  drawn_.batches.back().starts.push_back(drawn_.batches.back().paths.size());
  Paths& dst = drawn_.batches.back().paths;
  if (dst.empty()) {
    dst = std::move(paths);
  } else {
    dst.insert(dst.end(), std::make_move_iterator(paths.begin()),
               std::make_move_iterator(paths.end()));
  }
}

void GerberReader::add_centre_line(IntPoint from, const Path& points, double width_nm) {
  if (!drawn_.stroke_open || drawn_.strokes.empty() || drawn_.strokes.back().back() != from ||
      drawn_.stroke_widths_nm.back() != width_nm) {
    drawn_.strokes.push_back({from});
    drawn_.stroke_widths_nm.push_back(width_nm);
  }
  Path& s = drawn_.strokes.back();
  s.insert(s.end(), points.begin(), points.end());
  count_vertices(points.size() + 1);
  drawn_.stroke_open = true;
}

void GerberReader::operate(int d, const std::string* xs, const std::string* ys,
                           const std::string* is, const std::string* js) {
  IntPoint to = gs_.at;
  if (fmt_.incremental) {
    if (xs) to.X += coordinate(*xs, true);
    if (ys) to.Y += coordinate(*ys, false);
  } else {
    if (xs) to.X = coordinate(*xs, true);
    if (ys) to.Y = coordinate(*ys, false);
  }
  if (std::fabs(static_cast<double>(to.X)) > kMaxCoordNm ||
      std::fabs(static_cast<double>(to.Y)) > kMaxCoordNm) {
    diag_.fail("position beyond 10 m");
  }
  const cInt i = is ? coordinate(*is, true) : 0;
  const cInt j = js ? coordinate(*js, false) : 0;
  gs_.last_d = d;
  const IntPoint from = gs_.at;
  gs_.at = to;
  if ((d == 1 && !gs_.region) || d == 3) apertures_.used.insert(gs_.aperture);
  if (d == 1) {
    if (gs_.interpolation == 1) {
      if (gs_.region) {
        if (gs_.contour.empty()) gs_.contour.push_back(from);
        gs_.contour.push_back(to);
        if (!gs_.contour_as_gerbv.empty()) gs_.contour_as_gerbv.push_back(to);
      } else {
        draw_line(from, to);
      }
    } else {
      draw_arc(from, to, i, j, gs_.region);
    }
  } else if (d == 2) {
    if (gs_.region) finish_contour();
    drawn_.stroke_open = false;
  } else {
    if (gs_.region) diag_.fail("flash (D03) inside a region (G36/G37)");
    flash(to);
  }
}

void GerberReader::flash(IntPoint at) {
  const Aperture& ap = current_aperture();
  if (ap.type == 'B') {
    const bool dark = gs_.dark;
    for (const Batch& b : ap.block) {
      gs_.dark = dark ? b.dark : !b.dark;
      for (size_t k = 0; k < b.starts.size(); ++k) {
        const size_t end = k + 1 < b.starts.size() ? b.starts[k + 1] : b.paths.size();
        Paths object(b.paths.begin() + static_cast<long>(b.starts[k]),
                     b.paths.begin() + static_cast<long>(end));
        translate_paths(object, at.X, at.Y);
        add_object(std::move(object));
      }
    }
    gs_.dark = dark;
    return;
  }
  Paths copy = ap.shape;
  translate_paths(copy, at.X, at.Y);
  add_object(std::move(copy));
}

// The width a stroke draws: the circle's diameter, the smaller side of a rectangle or obround.
double stroke_width_nm(const Aperture& ap) {
  if (ap.type == 'C') return ap.circle_d_nm;
  if (ap.shape.empty() || ap.type == 'B') return 0;
  BoxNm b;
  for (const Path& p : ap.shape) b.add(p);
  return static_cast<double>(std::min(b.max_x - b.min_x, b.max_y - b.min_y));
}

void GerberReader::draw_line(IntPoint from, IntPoint to) {
  const Aperture& ap = current_aperture();
  if (ap.type == 'B')
    diag_.fail("block aperture D" + std::to_string(gs_.aperture) + " can only be flashed (D03)");
  add_centre_line(from, {to}, stroke_width_nm(ap));
  if (ap.shape.empty()) return;  // zero-size aperture: a line of no width
  const VecNm a{static_cast<double>(from.X), static_cast<double>(from.Y)};
  const VecNm b{static_cast<double>(to.X), static_cast<double>(to.Y)};
  if (ap.has_hole) diag_.note("a draw with an aperture that has a hole: the hole is ignored");
  if (ap.type == 'C') {
    if (from == to) {
      add_object({circle_path(a, ap.circle_d_nm, opt_.arc_tolerance_nm)});
    } else {
      add_object({capsule_path(a, b, ap.circle_d_nm, opt_.arc_tolerance_nm)});
    }
    return;
  }
  if (ap.type != 'M') {  // convex: the hull of the shape at both ends
    if (ap.type == 'R')
      diag_.note("a draw with a rectangular aperture (deprecated)");
    else
      diag_.note("a draw with a non-circular aperture (not allowed by the current spec)");
    Path pts;
    for (const IntPoint& p : ap.shape[0]) {
      pts.push_back({p.X + from.X, p.Y + from.Y});
      pts.push_back({p.X + to.X, p.Y + to.Y});
    }
    if (ap.type == 'O') {
      // gerbv strokes an obround as a circle of its X size: copper where either puts it.
      diag_.note(
          "warning: a draw with an obround aperture: copper where the obround swept along it "
          "or gerbv's stroke as wide as its X size with round ends puts it");
      BoxNm box;
      box.add(ap.shape[0]);
      const double d_nm = static_cast<double>(box.max_x - box.min_x);
      add_object(both_readings({convex_hull(pts)},
                               {from == to ? circle_path(a, d_nm, opt_.arc_tolerance_nm)
                                           : capsule_path(a, b, d_nm, opt_.arc_tolerance_nm)}));
      return;
    }
    add_object({convex_hull(pts)});
    return;
  }
  diag_.note("a draw with a macro aperture (not allowed by the current spec): swept shape used");
  Paths swept;
  for (const Path& outer : ap.shape) {
    if (!ClipperLib::Orientation(outer)) continue;
    Paths part;
    ClipperLib::MinkowskiSum(outer, Path{from, to}, part, false);
    swept.insert(swept.end(), part.begin(), part.end());
    Path end_copy = outer;
    for (IntPoint& p : end_copy) p = {p.X + to.X, p.Y + to.Y};
    swept.push_back(end_copy);
  }
  add_object(union_of(swept));
}

// The sweep from a to b about c (radians; negative: clockwise); a full turn when they meet and
// full_if_same.
double arc_sweep(const VecNm& a, const VecNm& b, const VecNm& c, bool clockwise,
                 bool full_if_same) {
  const double a0 = std::atan2(a.y - c.y, a.x - c.x);
  const double a1 = std::atan2(b.y - c.y, b.x - c.x);
  double s = a1 - a0;
  if (clockwise) {
    if (s > 0 || (s == 0 && full_if_same)) s -= 2 * kPi;
  } else {
    if (s < 0 || (s == 0 && full_if_same)) s += 2 * kPi;
  }
  return s;
}

void GerberReader::draw_arc(IntPoint from, IntPoint to, cInt i, cInt j, bool region) {
  const VecNm a{static_cast<double>(from.X), static_cast<double>(from.Y)};
  const VecNm b{static_cast<double>(to.X), static_cast<double>(to.Y)};
  VecNm c;
  double sweep = 0;
  arc_centre(a, b, from == to, i, j, &c, &sweep);
  const double r0 = std::hypot(a.x - c.x, a.y - c.y), r1 = std::hypot(b.x - c.x, b.y - c.y);
  const bool degenerate = zero_radius_arc(r0, r1);
  // An ill-defined arc (its centre rounded, as 3-decimal inch I/J are): we draw it through
  // both end points, gerbv keeps the start radius up to the end angle. Copper is where
  // either reading puts it, so no tool cuts where a common viewer shows copper.
  const double mismatch_nm = degenerate ? 0 : std::fabs(r0 - r1);
  const bool ill_defined = mismatch_nm > kIllDefinedArcNm;
  if (ill_defined) {
    ++drawn_.ill_defined_arcs;
    drawn_.ill_defined_max_nm = std::max(drawn_.ill_defined_max_nm, mismatch_nm);
  }
  Path pts, at_start_radius;
  const double a0 = std::atan2(a.y - c.y, a.x - c.x);
  if (degenerate) {
    if (from != to) pts.push_back(to);
  } else if (from != to || sweep != 0) {
    append_arc(pts, c, r0, r1, a0, sweep, opt_.arc_tolerance_nm);
    if (!pts.empty()) pts.back() = to;
    if (ill_defined) append_arc(at_start_radius, c, r0, r0, a0, sweep, opt_.arc_tolerance_nm);
  }
  if (region)
    region_arc(from, pts, ill_defined ? &at_start_radius : nullptr);
  else
    stroke_arc(from, pts, ill_defined ? &at_start_radius : nullptr, degenerate ? nullptr : &c);
}

// The arc's centre and sweep from its I, J: signed offsets (G75), or unsigned ones whose signs
// give an arc of at most 90 degrees with the closest radii (G74).
void GerberReader::arc_centre(const VecNm& a, const VecNm& b, bool same_point, cInt i, cInt j,
                              VecNm* centre, double* sweep_out) {
  const bool clockwise = gs_.interpolation == 2;
  VecNm c;
  double sweep = 0;
  if (gs_.quadrant == 0) {
    diag_.note("an arc before G74/G75: single-quadrant mode assumed (the old default)");
    gs_.quadrant = 74;
  }
  if (gs_.quadrant == 75) {
    c = {a.x + static_cast<double>(i), a.y + static_cast<double>(j)};
    sweep = arc_sweep(a, b, c, clockwise, same_point);
  } else {
    // Single quadrant: I and J are unsigned; the centre is the one giving an arc of at most
    // 90 degrees with the closest radii.
    double best = -1;
    for (int sx = -1; sx <= 1; sx += 2) {
      for (int sy = -1; sy <= 1; sy += 2) {
        const VecNm cc{a.x + sx * std::fabs(static_cast<double>(i)),
                       a.y + sy * std::fabs(static_cast<double>(j))};
        const double s = arc_sweep(a, b, cc, clockwise, false);
        if (std::fabs(s) > kPi / 2 + 1e-6) continue;
        const double err =
            std::fabs(std::hypot(a.x - cc.x, a.y - cc.y) - std::hypot(b.x - cc.x, b.y - cc.y));
        if (best < 0 || err < best) {
          best = err;
          c = cc;
          sweep = s;
        }
      }
    }
    if (best < 0) diag_.fail("single-quadrant arc (G74) with no centre giving 90 degrees or less");
  }
  *centre = c;
  *sweep_out = sweep;
}

// True for a zero-radius arc (a centre on its start or end point), which gerbv and pcb2gcode
// draw as the straight line between its ends (a point when they meet); refuses an arc whose
// end lies too far off its circle.
bool GerberReader::zero_radius_arc(double r0, double r1) {
  const bool degenerate = std::min(r0, r1) <= 1000.0;
  if (degenerate) {
    diag_.note(
        "warning: an arc whose centre is its own start or end point (zero radius) drawn as "
        "a straight line");
  } else if (std::fabs(r0 - r1) > arc_mismatch_limit_nm(r0, opt_.max_arc_radius_mismatch_nm)) {
    char msg[200];
    std::snprintf(msg, sizeof msg,
                  "arc end point is not on its circle (radius %.3f mm at the start, %.3f mm at "
                  "the end; more than %.3f mm apart is not an arc a reader can trust)",
                  r0 * 1e-6, r1 * 1e-6,
                  arc_mismatch_limit_nm(r0, opt_.max_arc_radius_mismatch_nm) * 1e-6);
    diag_.fail(msg);
  }
  return degenerate;
}

// An arc in a region's contour; theirs: the same arc as gerbv draws it (at its start radius),
// for an ill-defined arc.
void GerberReader::region_arc(IntPoint from, const Path& pts, const Path* theirs_if_ill) {
  const bool ill_defined = theirs_if_ill != nullptr;
  if (gs_.contour.empty()) gs_.contour.push_back(from);
  // gerbv's contour: a line to the arc's start, the arc at the start radius, and the next
  // segment from where that arc ends.
  if (ill_defined && gs_.contour_as_gerbv.empty()) gs_.contour_as_gerbv = gs_.contour;
  if (!gs_.contour_as_gerbv.empty()) {
    if (gs_.contour_as_gerbv.back() != from) gs_.contour_as_gerbv.push_back(from);
    const Path& theirs = ill_defined ? *theirs_if_ill : pts;
    gs_.contour_as_gerbv.insert(gs_.contour_as_gerbv.end(), theirs.begin(), theirs.end());
  }
  gs_.contour.insert(gs_.contour.end(), pts.begin(), pts.end());
}

// An arc stroked with the current (circular) aperture; for an ill-defined arc, copper where
// either reading puts it. centre: the arc's (nullptr: a zero-radius arc, a straight line).
void GerberReader::stroke_arc(IntPoint from, const Path& pts, const Path* theirs_if_ill,
                              const VecNm* centre) {
  const Aperture& ap = current_aperture();
  if (ap.type == 'R' || ap.type == 'O') {
    stroke_arc_with_shape(from, pts, theirs_if_ill, centre);
    return;
  }
  if (ap.type != 'C') {
    diag_.fail("an arc drawn with a non-circular aperture D" + std::to_string(gs_.aperture));
  }
  add_centre_line(from, pts, ap.circle_d_nm);
  if (ap.circle_d_nm <= 0) return;
  Path line{from};
  line.insert(line.end(), pts.begin(), pts.end());
  ClipperLib::ClipperOffset off;
  off.ArcTolerance = opt_.arc_tolerance_nm;
  off.AddPath(line, ClipperLib::jtRound, ClipperLib::etOpenRound);
  Paths out;
  off.Execute(out, ap.circle_d_nm / 2);
  if (theirs_if_ill) {
    Path theirs{from};
    theirs.insert(theirs.end(), theirs_if_ill->begin(), theirs_if_ill->end());
    out = both_readings(out, sweep_open({theirs}, ap.circle_d_nm / 2, opt_.arc_tolerance_nm));
  }
  add_object(std::move(out));
}

// An arc drawn with a rectangle or obround, which the spec does not allow (gerbv's tests
// test-aperture-rectangle-1.gbx, -obround-1.gbx): drawn as gerbv draws it, a stroke as wide
// as the aperture's X size with square (rectangle) or round (obround) ends; an ill-defined
// arc, where either reading puts it.
void GerberReader::stroke_arc_with_shape(IntPoint from, const Path& pts, const Path* theirs_if_ill,
                                         const VecNm* centre) {
  const Aperture& ap = current_aperture();
  diag_.note(std::string("warning: an arc drawn with ") +
             (ap.type == 'R' ? "a rectangular" : "an obround") + " aperture D" +
             std::to_string(gs_.aperture) +
             " (not allowed by the spec): drawn as gerbv draws it, a stroke as wide as its X "
             "size with " +
             (ap.type == 'R' ? "square" : "round") + " ends");
  BoxNm box;
  for (const Path& p : ap.shape) box.add(p);
  const double width_nm = ap.shape.empty() ? 0 : static_cast<double>(box.max_x - box.min_x);
  add_centre_line(from, pts, width_nm);
  if (width_nm <= 0) return;
  // Square ends at right angles to the arc's own tangent, as cairo's square cap: the line runs
  // on half the width along the tangent past each end, then ends butt. (Clipper's square end
  // is square to the last chord, turned from the tangent by half the chord's angle: its
  // corners stood out and in by up to width/2 x that angle, 5-10 um.)
  const bool square = ap.type == 'R';
  const auto past_end = [&](IntPoint end, IntPoint inner) {
    double tx = static_cast<double>(end.X - inner.X), ty = static_cast<double>(end.Y - inner.Y);
    if (centre) {  // the tangent, pointing the way the chord does
      const double rx = end.X - centre->x, ry = end.Y - centre->y;
      const double sign = (-ry * tx + rx * ty) < 0 ? -1 : 1;
      tx = -ry * sign, ty = rx * sign;
    }
    const double len = std::hypot(tx, ty);
    return IntPoint(end.X + static_cast<cInt>(std::llround(tx / len * width_nm / 2)),
                    end.Y + static_cast<cInt>(std::llround(ty / len * width_nm / 2)));
  };
  const auto stroke = [&](const Path& arc) {
    Path line{from};
    line.insert(line.end(), arc.begin(), arc.end());
    bool squared = false;  // the ends run on along the tangent
    if (square && line.size() >= 2) {
      size_t k = 1;  // the first point apart from `from`, the last apart from the end
      while (k + 1 < line.size() && line[k] == from) ++k;
      size_t m = line.size() - 2;
      while (m > 0 && line[m] == line.back()) --m;
      if (line[k] != from && line[m] != line.back()) {
        const IntPoint before = past_end(from, line[k]);
        line.push_back(past_end(line.back(), line[m]));
        line.insert(line.begin(), before);
        squared = true;
      }
    }
    const ClipperLib::EndType ends = squared  ? ClipperLib::etOpenButt
                                     : square ? ClipperLib::etOpenSquare
                                              : ClipperLib::etOpenRound;
    ClipperLib::ClipperOffset off;
    off.ArcTolerance = opt_.arc_tolerance_nm;
    off.AddPath(line, ClipperLib::jtRound, ends);
    Paths out;
    off.Execute(out, width_nm / 2);
    return out;
  };
  Paths out = stroke(pts);
  if (theirs_if_ill) out = both_readings(out, stroke(*theirs_if_ill));
  add_object(std::move(out));
}

Paths GerberReader::both_readings(const Paths& ours, const Paths& theirs) const {
  // Dark: copper under either reading. Clear: only what both readings clear.
  if (!gs_.dark) return intersection_of(ours, theirs);
  Paths both = ours;
  both.insert(both.end(), theirs.begin(), theirs.end());
  return union_of(both);
}

void GerberReader::finish_contour() {
  Path c;
  c.swap(gs_.contour);
  if (c.size() < 2) return;
  if (c.front() != c.back()) {
    const double gap = std::hypot(static_cast<double>(c.front().X - c.back().X),
                                  static_cast<double>(c.front().Y - c.back().Y));
    if (gap > 1000) diag_.note("a region contour that does not end at its start: closed");
  }
  Path stroke = c;
  if (stroke.front() != stroke.back()) stroke.push_back(stroke.front());
  count_vertices(stroke.size());
  drawn_.strokes.push_back(stroke);
  drawn_.stroke_widths_nm.push_back(0);
  drawn_.stroke_open = false;
  if (c.front() == c.back()) c.pop_back();
  Path theirs;
  theirs.swap(gs_.contour_as_gerbv);
  if (c.size() < 3) return;
  make_positive(c);
  if (theirs.size() >= 3) {
    make_positive(theirs);
    add_object(both_readings({c}, {theirs}));
    return;
  }
  add_object({c});
}

}  // namespace

PcbLayer read_gerber_text(const std::string& text, const std::string& path,
                          const GerberOptions& options) {
  return GerberReader(text, path, options).read();
}

PcbLayer read_gerber_file(const std::string& path, const GerberOptions& options) {
  return read_gerber_text(expand_gerber_includes(read_pcb_file_text(path), path), path, options);
}

}  // namespace host::pcb
