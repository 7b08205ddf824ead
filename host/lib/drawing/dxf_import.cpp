// DXF import: dxflib parses and dispatches; this file checks every value it hands over
// (dxflib reports almost no errors), converts each entity to exact B-splines and expands
// block references.
#include "host/lib/drawing/dxf_import.h"

#include <dxflib/dl_creationadapter.h>  // DL_CreationAdapter
#include <dxflib/dl_dxf.h>              // DL_Dxf

#include <cerrno>     // errno
#include <climits>    // INT_MAX
#include <cmath>      // std::isfinite, std::fabs
#include <map>        // std::map
#include <memory>     // std::unique_ptr
#include <new>        // std::bad_alloc
#include <sstream>    // std::ostringstream
#include <streambuf>  // std::streambuf
#include <utility>    // std::move

#include <unsupported/Eigen/Splines>  // Eigen::SplineFitting (fit-point splines)

#include "host/lib/drawing/conics.h"
#include "host/lib/drawing/dxf_scan.h"
#include "host/lib/drawing/file_text.h"  // read_drawing_text

namespace host {

namespace {

const double kPi = 3.14159265358979323846;
const int kMaxInsertDepth = 16;
// Fit-point splines are interpolated with a dense solve (time ~ n^3, memory ~ n^2).
const size_t kMaxFitPoints = 1000;
// What block references may expand to: block copies made, control points copied (an array
// of arrays multiplies them; the bounds keep time and memory to seconds and megabytes).
const long kMaxBlockCopies = 20000;
const long kMaxExpandedControlPoints = 2000000;

// The $INSUNITS codes this tool converts (the DXF reference's numbering): the unit's name
// and its length in millimetres.
struct DxfUnit {
  int code;
  const char* name;
  double mm;
};
const DxfUnit kDxfUnits[] = {
    {0, "mm (assumed)", 1.0}, {1, "inch", 25.4}, {2, "foot", 304.8},        {4, "mm", 1.0},
    {5, "cm", 10.0},          {6, "m", 1000.0},  {8, "microinch", 25.4e-6}, {9, "mil", 0.0254},
    {13, "micron", 0.001},    {14, "dm", 100.0},
};

struct ExpansionBudget {
  long copies = 0;
  long control_points = 0;
};

// The raw groups of one DXF record (entity, table entry, header variable), as read.
struct RawRecord {
  std::string type;
  long line = 0;
  std::string handle;
  int ordinal = 0;  // n-th record of this type in the file, from 1
  std::vector<std::pair<int, std::string>> groups;
};

// What a block or model space holds: curves in its own frame, and references to blocks.
struct InsertRef {
  DL_InsertData data{"", 0, 0, 0, 1, 1, 1, 0, 1, 1, 0, 0};
  Point2 extrusion_sign{1, 1};
  std::string label;
};
struct Space {
  Point2 base{0, 0};
  std::vector<Curve> curves;
  std::vector<InsertRef> inserts;
};

// Consecutive LINEs of one space where each starts exactly where the previous one ended
// (how CAD programs and tracers write a contour) become one polyline, the last curve of
// that space: a million segments then take one curve, not a million.
struct LineChain {
  Space* space = nullptr;  // none: the next LINE starts a new curve
  Point2 end{0, 0};
  int lines = 0;
  BSpline polyline;  // the LINEs so far; set into the space's last curve when the chain ends
  std::string last;  // "#N (line L)" of the newest LINE in it
};

// A polyline being collected from addPolyline/addVertex calls.
struct OpenPolyline {
  bool active = false;
  bool closed = false;
  bool mirror = false;
  std::string label;
  const char* kind = "";  // "POLYLINE" or "LWPOLYLINE"
  std::vector<BulgeVertex> vertices;
  bool nonzero_z = false;
};

class DxfReader : public DL_CreationAdapter {
 public:
  explicit DxfReader(const std::string& path) : path_(path) {}

  Drawing finish();

  // Every group passes here before dxflib handles it: keeps the raw record that dxflib is
  // about to dispatch (the previous one when a new group 0 or 9 arrives).
  void raw_group(const DxfGroup& g) {
    if (g.code == 0 || g.code == 9) {
      finished_ = pending_;
      pending_ = RawRecord();
      pending_.type = g.value;
      pending_.line = g.line;
      if (g.code == 0) pending_.ordinal = ++type_ordinal_[g.value];
      return;
    }
    if (g.code == 5) pending_.handle = g.value;
    pending_.groups.emplace_back(g.code, g.value);
  }

  void setVariableInt(const std::string& key, int value, int) override {
    if (key == "$INSUNITS") {
      insunits_ = value;
      have_insunits_ = true;
    }
  }

  void addBlock(const DL_BlockData& d) override {
    end_chain();
    flush_polyline();
    block_name_ = d.name;
    in_block_ = true;
    Space& s = blocks_[d.name];
    s.base = Point2(d.bpx, d.bpy);
    check_finite(d.bpx, d.bpy, "base point");
  }
  void endBlock() override {
    end_chain();
    flush_polyline();
    in_block_ = false;
  }

  void addLine(const DL_LineData& d) override {
    if (!take("LINE")) return;
    check_finite(d.x1, d.y1, "start point");
    check_finite(d.x2, d.y2, "end point");
    const Point2 a(d.x1, d.y1), b(d.x2, d.y2);
    if ((b - a).norm() < 1e-12) {
      warn("zero-length LINE skipped");
      return;
    }
    if (chain_.space == &space() && a == chain_.end) {
      // Continues the previous LINE: one more corner of its polyline.
      BSpline& s = chain_.polyline;
      s.control.push_back(b);
      s.knots.back() = static_cast<double>(s.control.size() - 1);
      s.knots.push_back(s.knots.back());
      ++chain_.lines;
      chain_.last = "#" + std::to_string(finished_.ordinal) + " (line " +
                    std::to_string(finished_.line) + ")";
    } else {
      end_chain();
      add_curve("LINE", line_spline(a, b));
      chain_.space = &space();
      chain_.lines = 1;
      chain_.polyline = line_spline(a, b);
    }
    chain_.end = b;
  }

  void addArc(const DL_ArcData& d) override {
    if (!take("ARC")) return;
    check_finite(d.cx, d.cy, "centre");
    check_number(d.radius, "radius");
    check_number(d.angle1, "start angle");
    check_number(d.angle2, "end angle");
    if (!(d.radius > 0)) fail("radius is " + num(d.radius) + " (must be positive)");
    double sweep = std::fmod(d.angle2 - d.angle1, 360.0);
    if (sweep <= 1e-12) sweep += 360.0;
    add_curve("ARC", ocs(arc_spline(Point2(d.cx, d.cy), d.radius, d.angle1 * kPi / 180,
                                    sweep * kPi / 180)));
  }

  void addCircle(const DL_CircleData& d) override {
    if (!take("CIRCLE")) return;
    check_finite(d.cx, d.cy, "centre");
    check_number(d.radius, "radius");
    if (!(d.radius > 0)) fail("radius is " + num(d.radius) + " (must be positive)");
    add_curve("CIRCLE", ocs(arc_spline(Point2(d.cx, d.cy), d.radius, 0.0, 2 * kPi)));
  }

  void addEllipse(const DL_EllipseData& d) override {
    if (!take("ELLIPSE")) return;
    check_finite(d.cx, d.cy, "centre");
    check_finite(d.mx, d.my, "major axis");
    check_number(d.ratio, "axis ratio");
    check_number(d.angle1, "start parameter");
    check_number(d.angle2, "end parameter");
    const Point2 major(d.mx, d.my);
    if (!(major.norm() > 0)) fail("major axis has zero length");
    if (!(d.ratio > 0 && d.ratio <= 1.0 + 1e-9)) {
      fail("axis ratio is " + num(d.ratio) + " (must be in (0, 1])");
    }
    // Minor axis = extrusion x major, scaled by the ratio (WCS; the sign of the extrusion
    // decides the side).
    const double ez = extrusion_z();
    const Point2 minor = Point2(-major.y(), major.x()) * d.ratio * (ez < 0 ? -1.0 : 1.0);
    double sweep = std::fmod(d.angle2 - d.angle1, 2 * kPi);
    if (sweep <= 1e-12) sweep += 2 * kPi;
    add_curve("ELLIPSE", ellipse_spline(Point2(d.cx, d.cy), major, minor, d.angle1, sweep));
  }

  void addPolyline(const DL_PolylineData& d) override {
    flush_polyline();
    const char* kind = finished_.type == "POLYLINE" ? "POLYLINE" : "LWPOLYLINE";
    if (!take(kind)) return;
    if (d.flags & (16 | 64)) fail("polygon or polyface meshes are not drawings in the plane");
    if (d.flags & 4) {
      fail(
          "spline-fit polyline (flag 4): convert it to a SPLINE or explode it in the CAD "
          "program");
    }
    poly_.active = true;
    poly_.closed = (d.flags & 1) != 0;
    poly_.mirror = extrusion_z() < 0;
    poly_.label = label();
    poly_.kind = kind;
    poly_.vertices.clear();
    poly_.nonzero_z = false;
  }

  void addVertex(const DL_VertexData& d) override {
    if (!poly_.active) return;
    if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.bulge)) {
      throw ImportError(path_ + ": " + poly_.label + ": a vertex is not a finite number");
    }
    BulgeVertex v;
    v.p = Point2(d.x, d.y);
    v.bulge = d.bulge;
    if (d.z != 0.0) poly_.nonzero_z = true;
    poly_.vertices.push_back(v);
  }
  void endEntity() override {
    if (poly_.active && std::string(poly_.kind) == "LWPOLYLINE") flush_polyline();
  }
  void endSequence() override { flush_polyline(); }

  void addSpline(const DL_SplineData& d) override;
  void addControlPoint(const DL_ControlPointData&) override {}
  void addKnot(const DL_KnotData&) override {}

  void addInsert(const DL_InsertData& d) override {
    if (!take("INSERT")) return;
    check_finite(d.ipx, d.ipy, "insertion point");
    check_finite(d.sx, d.sy, "scale");
    check_number(d.angle, "rotation");
    check_finite(d.colSp, d.rowSp, "array spacing");
    if (d.sx == 0 || d.sy == 0) fail("scale factor of zero");
    if (d.cols < 1 || d.rows < 1 || d.cols * d.rows > 10000) {
      fail("array of " + std::to_string(d.cols) + " x " + std::to_string(d.rows) +
           " copies (must be 1..10000 in all)");
    }
    InsertRef r;
    r.data = d;
    r.extrusion_sign = Point2(extrusion_z() < 0 ? -1.0 : 1.0, 1.0);
    r.label = label();
    space().inserts.push_back(r);
  }

  // Annotations and solids: counted and reported, not engraved.
  void addText(const DL_TextData&) override { skip("TEXT"); }
  void addMText(const DL_MTextData&) override { skip("MTEXT"); }
  void addPoint(const DL_PointData&) override { skip("POINT"); }
  void addHatch(const DL_HatchData&) override { skip("HATCH"); }
  void addSolid(const DL_SolidData&) override { skip("SOLID"); }
  void addTrace(const DL_TraceData&) override { skip("TRACE"); }
  void add3dFace(const DL_3dFaceData&) override { skip("3DFACE"); }
  void addXLine(const DL_XLineData&) override { skip("XLINE"); }
  void addRay(const DL_RayData&) override { skip("RAY"); }
  void addImage(const DL_ImageData&) override { skip("IMAGE"); }
  void addLeader(const DL_LeaderData&) override { skip("LEADER"); }
  void addDimLinear(const DL_DimensionData&, const DL_DimLinearData&) override {
    skip("DIMENSION");
  }
  void addDimAlign(const DL_DimensionData&, const DL_DimAlignedData&) override {
    skip("DIMENSION");
  }
  void addDimRadial(const DL_DimensionData&, const DL_DimRadialData&) override {
    skip("DIMENSION");
  }
  void addDimDiametric(const DL_DimensionData&, const DL_DimDiametricData&) override {
    skip("DIMENSION");
  }
  void addDimAngular(const DL_DimensionData&, const DL_DimAngular2LData&) override {
    skip("DIMENSION");
  }
  void addDimAngular3P(const DL_DimensionData&, const DL_DimAngular3PData&) override {
    skip("DIMENSION");
  }
  void addDimOrdinate(const DL_DimensionData&, const DL_DimOrdinateData&) override {
    skip("DIMENSION");
  }

 private:
  // Counts the entity; false when it is to be ignored (paper space). Flushes a pending
  // polyline (its SEQEND may be missing).
  bool take(const std::string& kind) {
    if (kind != "LINE") end_chain();
    if (kind != "POLYLINE" && kind != "LWPOLYLINE") flush_polyline();
    if (!in_block_) ++counts_[kind];
    if (paper_space()) {
      end_chain();
      if (!in_block_) ++paper_space_skipped_;
      return false;
    }
    check_extrusion();
    return true;
  }

  void skip(const std::string& kind) {
    end_chain();
    flush_polyline();
    if (in_block_) return;
    ++counts_[kind];
    ++skipped_[kind];
  }

  bool paper_space() const {
    if (in_block_ &&
        (block_name_.rfind("*Paper_Space", 0) == 0 || block_name_.rfind("*PAPER_SPACE", 0) == 0)) {
      return true;
    }
    for (const auto& g : finished_.groups) {
      if (g.first == 67 && std::atoi(g.second.c_str()) == 1) return true;
    }
    return false;
  }

  // Entity extrusion direction z (the OCS normal); tilted planes are refused.
  double extrusion_z() {
    double e[3] = {0, 0, 1};
    getExtrusion()->getDirection(e);
    return e[2];
  }
  void check_extrusion() {
    double e[3] = {0, 0, 1};
    getExtrusion()->getDirection(e);
    if (!std::isfinite(e[0]) || !std::isfinite(e[1]) || !std::isfinite(e[2]) ||
        std::fabs(e[0]) > 1e-9 || std::fabs(e[1]) > 1e-9 || std::fabs(e[2]) < 1e-9) {
      std::ostringstream o;
      o << "lies in a tilted plane (extrusion " << e[0] << ", " << e[1] << ", " << e[2]
        << "); only drawings in the XY plane can be engraved";
      fail(o.str());
    }
  }

  // Maps a curve built in the entity's OCS to the WCS: the only OCS allowed besides the
  // WCS is the one seen from below (extrusion 0,0,-1), where x is mirrored.
  BSpline ocs(const BSpline& s) {
    if (extrusion_z() > 0) return s;
    Eigen::Matrix2d m;
    m << -1, 0, 0, 1;
    return transformed(s, m, Point2(0, 0));
  }

  Space& space() { return in_block_ ? blocks_[block_name_] : model_; }

  std::string label() const {
    std::ostringstream o;
    o << finished_.type << " #" << finished_.ordinal << " (";
    if (!finished_.handle.empty()) o << "handle " << finished_.handle << ", ";
    o << "line " << finished_.line;
    if (in_block_) o << ", block '" << block_name_ << "'";
    o << ")";
    return o.str();
  }

  void add_curve(const char* kind, const BSpline& s) {
    const std::string problem = check_bspline(s);
    if (!problem.empty()) fail(problem);
    Curve c;
    c.set_spline(s);
    c.kind = kind;
    c.source = label();
    space().curves.push_back(std::move(c));
  }

  // The polyline of chained LINEs is complete: its source names the first and last LINE.
  void end_chain() {
    if (chain_.space != nullptr && chain_.lines > 1) {
      const int more = chain_.lines - 1;
      chain_.space->curves.back().set_spline(std::move(chain_.polyline));
      chain_.space->curves.back().source +=
          (more == 1 ? std::string(" and the LINE that continues it, ")
                     : " and the " + std::to_string(more) + " LINEs that continue it, to ") +
          chain_.last;
    }
    chain_ = LineChain();
  }

  void flush_polyline() {
    if (!poly_.active) return;
    poly_.active = false;
    if (poly_.nonzero_z) {
      warnings_.push_back(path_ + ": " + poly_.label + ": vertex z ignored (drawn in plan view)");
    }
    BSpline s = polyline_spline(poly_.vertices, poly_.closed);
    if (s.control.empty()) {
      warnings_.push_back(path_ + ": " + poly_.label + ": " +
                          std::to_string(poly_.vertices.size()) +
                          " vertices and no segment of non-zero length: nothing to draw, skipped");
      return;
    }
    if (poly_.mirror) {
      Eigen::Matrix2d m;
      m << -1, 0, 0, 1;
      s = transformed(s, m, Point2(0, 0));
    }
    Curve c;
    c.set_spline(s);
    c.kind = poly_.kind;
    c.source = poly_.label;
    space().curves.push_back(c);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw ImportError(path_ + ": " + label() + ": " + what);
  }
  void warn(const std::string& what) { warnings_.push_back(path_ + ": " + label() + ": " + what); }

  // An integer group's value. The scan checked syntax and range; checked again here
  // because a cast of an out-of-range value would be undefined.
  int group_int(int code, const std::string& v) const {
    errno = 0;
    char* end = nullptr;
    const long long n = std::strtoll(v.c_str(), &end, 10);
    if (end == v.c_str() || *end != '\0' || errno == ERANGE || n < -INT_MAX || n > INT_MAX) {
      fail("group " + std::to_string(code) + " value '" + v.substr(0, 40) +
           "' is not an integer in range");
    }
    return static_cast<int>(n);
  }

  void check_number(double v, const char* what) const {
    if (!std::isfinite(v)) fail(std::string(what) + " is not a finite number");
  }
  void check_finite(double x, double y, const char* what) const {
    check_number(x, what);
    check_number(y, what);
  }
  static std::string num(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
  }

  void expand(const Space& s, const Eigen::Matrix2d& a, const Point2& b, int depth,
              const std::string& via, ExpansionBudget& budget, std::vector<Curve>& out) const;

  // A SPLINE record's groups (addSpline).
  struct SplineGroups {
    int flags = 0, degree = -1;
    long n_knots = -1, n_control = -1, n_fit = -1;
    std::vector<double> knots, weights;
    std::vector<Point2> control, fit;
    std::vector<double> control_z;
    bool has_end_tangent = false;
  };
  SplineGroups spline_groups() const;
  void check_count(long announced, size_t listed, const char* what, int code) const;
  BSpline fit_point_spline(const SplineGroups& g);
  BSpline control_point_spline(const SplineGroups& g) const;
  void set_units(Drawing& dr);
  std::vector<Curve> expanded_curves(double unit_to_mm);

  std::string path_;
  RawRecord pending_, finished_;
  std::map<std::string, int> type_ordinal_;
  int insunits_ = 0;
  bool have_insunits_ = false;
  bool in_block_ = false;
  std::string block_name_;
  std::map<std::string, Space> blocks_;
  Space model_;
  OpenPolyline poly_;
  LineChain chain_;
  std::map<std::string, int> counts_;
  std::map<std::string, int> skipped_;
  int paper_space_skipped_ = 0;
  std::vector<std::string> warnings_;
};

// SPLINE: the counts and values are taken from the raw groups (dxflib silently pads or
// drops knots and control points that do not match the announced counts).
void DxfReader::addSpline(const DL_SplineData&) {
  if (!take("SPLINE")) return;
  const SplineGroups g = spline_groups();
  if (g.degree < 1 || g.degree > 3) {
    fail("degree " + std::to_string(g.degree) + " (group 71); the machine takes degree 1 to 3");
  }
  check_count(g.n_knots, g.knots.size(), "knots", 72);
  check_count(g.n_control, g.control.size(), "control points", 73);
  check_count(g.n_fit, g.fit.size(), "fit points", 74);
  for (double z : g.control_z) {
    if (z != 0.0) {
      warn("control point z ignored (drawn in plan view)");
      break;
    }
  }
  const BSpline s = g.control.empty() ? fit_point_spline(g) : control_point_spline(g);
  const std::string problem = check_bspline(s);
  if (!problem.empty()) fail(problem);
  if ((g.flags & 1) && (start_point(s) - end_point(s)).norm() > 1e-6 * (1 + s.control[0].norm())) {
    warn("flagged closed but its ends are " + num((start_point(s) - end_point(s)).norm()) +
         " apart; drawn as stored");
  }
  add_curve("SPLINE", s);
}

// The SPLINE record's groups, as listed (the counts as announced, -1 when absent).
DxfReader::SplineGroups DxfReader::spline_groups() const {
  SplineGroups s;
  for (const auto& g : finished_.groups) {
    const bool is_int = g.first >= 70 && g.first <= 74;
    const double v = is_int ? 0.0 : std::strtod(g.second.c_str(), 0);  // syntax checked
    switch (g.first) {
      case 70:
        s.flags = group_int(g.first, g.second);
        break;
      case 71:
        s.degree = group_int(g.first, g.second);
        break;
      case 72:
        s.n_knots = group_int(g.first, g.second);
        break;
      case 73:
        s.n_control = group_int(g.first, g.second);
        break;
      case 74:
        s.n_fit = group_int(g.first, g.second);
        break;
      case 40:
        s.knots.push_back(v);
        break;
      case 41:
        s.weights.push_back(v);
        break;
      case 10:
        s.control.emplace_back(v, 0.0);
        s.control_z.push_back(0.0);
        break;
      case 20:
        if (!s.control.empty()) s.control.back().y() = v;
        break;
      case 30:
        if (!s.control_z.empty()) s.control_z.back() = v;
        break;
      case 11:
        s.fit.emplace_back(v, 0.0);
        break;
      case 21:
        if (!s.fit.empty()) s.fit.back().y() = v;
        break;
      case 12:
      case 13:
        s.has_end_tangent = true;  // start (12) or end (13) tangent: not used
        break;
      default:
        break;
    }
  }
  return s;
}

// A count the record announces (group `code`; -1: none) against what it lists.
void DxfReader::check_count(long announced, size_t listed, const char* what, int code) const {
  if (announced >= 0 && announced != static_cast<long>(listed)) {
    fail("announces " + std::to_string(announced) + " " + what + " (group " + std::to_string(code) +
         ") but lists " + std::to_string(listed));
  }
}

// A spline given by fit points only: interpolated (chord-length parameters, averaged knots).
// CAD programs may also honour end tangents and their own knot rule: say so.
BSpline DxfReader::fit_point_spline(const SplineGroups& g) {
  if (g.fit.size() < 2) fail("has neither control points nor at least two fit points");
  if (g.fit.size() > kMaxFitPoints) {
    fail(std::to_string(g.fit.size()) + " fit points and no control points (at most " +
         std::to_string(kMaxFitPoints) +
         " are interpolated; save the spline with its control points)");
  }
  const int deg = std::min<int>(g.degree, static_cast<int>(g.fit.size()) - 1);
  Eigen::MatrixXd pts(2, g.fit.size());
  for (size_t i = 0; i < g.fit.size(); ++i) pts.col(i) = g.fit[i];
  typedef Eigen::Spline<double, 2> EigenSpline;
  const EigenSpline e = Eigen::SplineFitting<EigenSpline>::Interpolate(pts, deg);
  BSpline s;
  s.degree = deg;
  for (Eigen::Index i = 0; i < e.ctrls().cols(); ++i) s.control.push_back(e.ctrls().col(i));
  for (Eigen::Index i = 0; i < e.knots().size(); ++i) s.knots.push_back(e.knots()(i));
  std::string note = "defined by " + std::to_string(g.fit.size()) +
                     " fit points only: interpolated with a degree " + std::to_string(deg) +
                     " B-spline through them (chord-length parameters)";
  if (g.has_end_tangent) note += "; the end tangents in the file are not used";
  warn(note + "; the CAD program's curve may differ slightly between fit points");
  return s;
}

// A spline given by its control points and knots; weights kept when they make it rational
// (any weight other than 1, or flag 4).
BSpline DxfReader::control_point_spline(const SplineGroups& g) const {
  BSpline s;
  s.degree = g.degree;
  s.control = g.control;
  s.knots = g.knots;
  if (!g.weights.empty()) {
    if (g.weights.size() != g.control.size()) {
      fail(std::to_string(g.weights.size()) + " weights (group 41) for " +
           std::to_string(g.control.size()) + " control points");
    }
    bool all_one = true;
    for (double w : g.weights) all_one = all_one && w == 1.0;
    if (!all_one || (g.flags & 4)) s.weights = g.weights;
  }
  return s;
}

// Appends the curves of a space mapped by x -> a x + b, expanding its block references.
void DxfReader::expand(const Space& s, const Eigen::Matrix2d& a, const Point2& b, int depth,
                       const std::string& via, ExpansionBudget& budget,
                       std::vector<Curve>& out) const {
  budget.copies += 1;
  for (const Curve& c : s.curves) {
    budget.control_points += static_cast<long>(c.held.control_count());
  }
  if (budget.copies > kMaxBlockCopies || budget.control_points > kMaxExpandedControlPoints) {
    throw ImportError(path_ + ": block references expand to more than " +
                      std::to_string(kMaxBlockCopies) + " block copies or " +
                      std::to_string(kMaxExpandedControlPoints) +
                      " control points (arrays of arrays of blocks?)" +
                      (via.empty() ? std::string() : ", last" + via));
  }
  for (const Curve& c : s.curves) {
    Curve t = c;
    t.set_spline(transformed(c.spline(), a, b));
    t.source = c.source + via;
    out.push_back(std::move(t));
  }
  for (const InsertRef& r : s.inserts) {
    const DL_InsertData& d = r.data;
    auto it = blocks_.find(d.name);
    if (it == blocks_.end()) {
      throw ImportError(path_ + ": " + r.label + ": refers to block '" + d.name +
                        "', which the file does not define");
    }
    if (depth >= kMaxInsertDepth) {
      throw ImportError(path_ + ": " + r.label + ": block references nested deeper than " +
                        std::to_string(kMaxInsertDepth) + " (a block that contains itself?)");
    }
    const double ang = d.angle * kPi / 180;
    Eigen::Matrix2d rot;
    rot << std::cos(ang), -std::sin(ang), std::sin(ang), std::cos(ang);
    Eigen::Matrix2d mirror = Eigen::Matrix2d::Identity();
    mirror(0, 0) = r.extrusion_sign.x();
    const Eigen::Matrix2d scale = Eigen::Vector2d(d.sx, d.sy).asDiagonal();
    for (int row = 0; row < d.rows; ++row) {
      for (int col = 0; col < d.cols; ++col) {
        // OCS: p' = ip + R (S (p - base) + array offset); then OCS -> WCS (mirror).
        const Point2 offset(col * d.colSp, row * d.rowSp);
        const Eigen::Matrix2d local_a = mirror * rot * scale;
        const Point2 local_b =
            mirror * (Point2(d.ipx, d.ipy) + rot * (offset - scale * it->second.base));
        expand(it->second, a * local_a, a * local_b + b, depth + 1,
               " via " + r.label.substr(0, r.label.find(" (")) + " of '" + d.name + "'", budget,
               out);
      }
    }
  }
}

Drawing DxfReader::finish() {
  end_chain();
  flush_polyline();
  Drawing dr;
  dr.path = path_;
  dr.format = "DXF";
  set_units(dr);
  dr.curves = expanded_curves(dr.unit_to_mm);
  dr.entity_counts = counts_;
  for (const auto& k : skipped_) {
    warnings_.push_back(path_ + ": " + std::to_string(k.second) + " " + k.first + " entit" +
                        (k.second == 1 ? "y" : "ies") +
                        " not engraved (only lines, arcs, circles, ellipses, polylines, "
                        "splines and block references are; convert text to outlines)");
  }
  if (paper_space_skipped_ > 0) {
    warnings_.push_back(path_ + ": " + std::to_string(paper_space_skipped_) +
                        " paper-space entities ignored (only model space is engraved)");
  }
  dr.warnings = warnings_;
  return dr;
}

// The drawing's unit from $INSUNITS (none or 0: millimetres, with a warning).
void DxfReader::set_units(Drawing& dr) {
  const int code = have_insunits_ ? insunits_ : 0;
  std::string supported;
  for (const DxfUnit& u : kDxfUnits) {
    if (u.code == code) {
      dr.units = u.name;
      dr.unit_to_mm = u.mm;
      if (code == 0) {
        warnings_.push_back(
            path_ +
            (have_insunits_ ? ": $INSUNITS is 0 (unitless)" : ": no $INSUNITS in the header") +
            ": coordinates taken as millimetres");
      }
      return;
    }
    supported += (supported.empty() ? "" : ", ") + std::to_string(u.code) + " " +
                 (u.code == 0 ? "unitless = mm" : u.name);
  }
  throw ImportError(path_ + ": $INSUNITS " + std::to_string(insunits_) +
                    " is a unit this tool does not convert (supported: " + supported + ")");
}

// Every curve in millimetres, block references expanded; none beyond 10 km.
std::vector<Curve> DxfReader::expanded_curves(double unit_to_mm) {
  ExpansionBudget budget;
  const Eigen::Matrix2d to_mm = Eigen::Matrix2d::Identity() * unit_to_mm;
  // The model space's own curves are scaled in place and the vector moved, not copied (a
  // million-line drawing held them three times over, then twice while a second vector was
  // filled); blocks may be inserted many times, so expand() copies those. It counts the
  // model space's copy and checks the budget with these control points in it.
  for (Curve& c : model_.curves) {
    budget.control_points += static_cast<long>(c.held.control_count());
    if (unit_to_mm != 1.0) c.set_spline(transformed(c.spline(), to_mm, Point2(0, 0)));
  }
  std::vector<Curve> curves = std::move(model_.curves);
  model_.curves = std::vector<Curve>();
  expand(model_, to_mm, Point2(0, 0), 0, "", budget, curves);
  for (const Curve& c : curves) {
    c.held.each_control([&](const Point2& p) {
      if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || std::fabs(p.x()) > 1e7 ||
          std::fabs(p.y()) > 1e7) {
        throw ImportError(path_ + ": " + c.source +
                          ": a coordinate is beyond 10 km after block and unit scaling");
      }
    });
  }
  return curves;
}

// Serves the checked groups to dxflib as text, one group per underflow(), and hands each
// group to the reader's raw_group() just before dxflib reads it: dxflib processes a group
// only after reading both its lines, so the reader's raw record is always the one dxflib is
// about to dispatch. dxflib stops at the end of the stream, which is the closing 0/EOF.
// The groups are scanned again as they are served (the whole file was checked before),
// so they are never all held at once.
class GroupFeed : public std::streambuf {
 public:
  GroupFeed(DxfScanner& groups, DxfReader& reader, const WorkProgress& progress, size_t bytes)
      : groups_(groups), reader_(reader), progress_(progress), bytes_(bytes) {}

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    if (!groups_.next(&group_)) return traits_type::eof();
    if (progress_ && ++groups_read_ % 65536 == 0) progress_("bytes read", groups_.pos(), bytes_);
    reader_.raw_group(group_);
    text_ = std::to_string(group_.code) + "\n" + group_.value + "\n";
    setg(&text_[0], &text_[0], &text_[0] + text_.size());
    return traits_type::to_int_type(*gptr());
  }

 private:
  DxfScanner& groups_;
  DxfReader& reader_;
  DxfGroup group_;
  std::string text_;
  const WorkProgress& progress_;
  size_t bytes_;  // of the whole text
  size_t groups_read_ = 0;
};

}  // namespace

Drawing import_dxf_text(const std::string& text, const std::string& path) {
  return import_dxf_text_reporting(text, path, nullptr);
}

Drawing import_dxf_text_reporting(const std::string& text, const std::string& path,
                                  const WorkProgress& progress) {
  try {
    check_dxf(text, path, progress);  // the whole file, before dxflib reads any of it
    DxfScanner groups(text, path);
    DxfReader reader(path);
    GroupFeed feed(groups, reader, progress, text.size());
    std::istream stream(&feed);
    // dxflib loops until end-of-file: an exception in underflow() must not leave the stream
    // merely bad (no eof, an endless loop) but reach the handlers below. No line it reads is
    // longer than its 1023-character buffer (kMaxDxfValueChars), which would do the same.
    stream.exceptions(std::ios::badbit);
    DL_Dxf dxf;
    dxf.in(stream, &reader);
    if (progress) progress("bytes read", text.size(), text.size());
    return reader.finish();
  } catch (const std::exception&) {
    rethrow_as_import_error(path, "the DXF drawing");
  }
}

Drawing import_dxf(const std::string& path, const WorkProgress& progress) {
  return import_dxf_text_reporting(read_drawing_text(path), path, progress);
}

}  // namespace host
