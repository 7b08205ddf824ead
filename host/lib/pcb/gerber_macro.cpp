#include "host/lib/pcb/gerber_macro.h"

#include <cctype>   // std::isdigit
#include <cmath>    // std::isfinite, std::fabs, std::hypot
#include <cstdlib>  // std::strtod

#include "host/lib/pcb/gerber_shapes.h"

namespace host::pcb {

using ClipperLib::Path;
using ClipperLib::Paths;

namespace {

// Recursive descent over one expression.
class ExpressionParser {
 public:
  ExpressionParser(const std::string& text, const std::vector<double>& vars)
      : s_(text), vars_(vars) {}

  double parse() {
    if (s_.empty()) throw std::invalid_argument("empty expression");
    const double v = sum();
    if (pos_ != s_.size()) fail("unexpected '" + s_.substr(pos_, 1) + "'");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument(what + " in expression '" + s_ + "'");
  }
  bool eat(char c) {
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  double sum() {
    double v = product();
    for (;;) {
      if (eat('+')) {
        v += product();
      } else if (eat('-')) {
        v -= product();
      } else {
        return v;
      }
    }
  }
  double product() {
    double v = unary();
    for (;;) {
      if (eat('x') || eat('X')) {
        v *= unary();
      } else if (eat('/')) {
        const double d = unary();
        if (d == 0) fail("division by zero");
        v /= d;
      } else {
        return v;
      }
    }
  }
  double unary() {
    if (eat('-')) return -unary();
    if (eat('+')) return unary();
    return primary();
  }
  double primary() {
    if (++depth_ > 64) fail("too deeply nested");
    double v = 0;
    if (eat('(')) {
      v = sum();
      if (!eat(')')) fail("missing ')'");
    } else if (eat('$')) {
      size_t n = 0, start = pos_;
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_])) &&
             pos_ - start < 6) {
        n = n * 10 + static_cast<size_t>(s_[pos_++] - '0');
      }
      if (pos_ == start) fail("'$' without a variable number");
      v = n < vars_.size() ? vars_[n] : 0.0;  // an unset variable is 0, as gerbv reads it
    } else {
      const size_t start = pos_;
      while (pos_ < s_.size() &&
             (std::isdigit(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '.')) {
        ++pos_;
      }
      if (pos_ == start)
        fail(pos_ < s_.size() ? "unexpected '" + s_.substr(pos_, 1) + "'" : "missing number");
      const std::string num = s_.substr(start, pos_ - start);
      char* end = nullptr;
      v = std::strtod(num.c_str(), &end);
      if (*end != '\0') fail("bad number '" + num + "'");
    }
    --depth_;
    return v;
  }

  const std::string& s_;
  const std::vector<double>& vars_;
  size_t pos_ = 0;
  int depth_ = 0;
};

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> out;
  size_t start = 0;
  for (;;) {
    const size_t comma = s.find(',', start);
    out.push_back(s.substr(start, comma - start));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

// Rectangle of width w along the segment a-b (square ends).
Path line_rect(VecNm a, VecNm b, double w) {
  const double dx = b.x - a.x, dy = b.y - a.y, len = std::hypot(dx, dy);
  if (len == 0 || w <= 0) return {};
  const double nx = -dy / len * w / 2, ny = dx / len * w / 2;
  return {to_int({a.x - nx, a.y - ny}), to_int({b.x - nx, b.y - ny}), to_int({b.x + nx, b.y + ny}),
          to_int({a.x + nx, a.y + ny})};
}

void rotate_all(Paths& paths, double deg) {
  for (Path& p : paths) rotate_path(p, deg);
}

}  // namespace

double evaluate_macro_expression(const std::string& text, const std::vector<double>& vars) {
  const double v = ExpressionParser(text, vars).parse();
  if (!std::isfinite(v)) throw std::invalid_argument("value out of range in '" + text + "'");
  return v;
}

namespace {

// A primitive statement's modifiers, evaluated, and the checks every primitive makes.
struct PrimitiveArgs {
  const ApertureMacro& macro;
  const MacroStatement& st;
  std::vector<std::string> fields;  // the code, then the modifiers as written
  std::vector<double> m;            // the modifiers' values
  double unit_nm, tol_nm;
  const std::string& code() const { return fields[0]; }
  [[noreturn]] void bad(const std::string& what) const {
    throw MacroError(st.line, "macro " + macro.name + ": " + what);
  }
  void need(size_t n, const char* what) const {
    if (m.size() < n) {
      bad(std::string(what) + " needs " + std::to_string(n) + " modifiers, got " +
          std::to_string(m.size()));
    }
  }
  double len(double v) const {
    const double nm = v * unit_nm;
    if (!(std::fabs(nm) <= 1e10)) bad("a size or position beyond 10 m");
    return nm;
  }
  // 0 off, 1 on, 2 toggle (old spec); anything else is refused before any cast.
  int exposure_of(double v) const {
    if (v != 0 && v != 1 && v != 2) bad("exposure must be 0 or 1, not " + fields[1]);
    return static_cast<int>(v);
  }
};

// A primitive's shape before its rotation, its exposure and its rotation (degrees).
struct Primitive {
  Paths paths;
  int exposure = 1;
  double rot = 0;
};

// 1: a circle.
Primitive circle(const PrimitiveArgs& a) {
  Primitive p;
  a.need(4, "circle (1)");
  p.exposure = a.exposure_of(a.m[0]);
  if (a.m[1] > 0)
    p.paths.push_back(circle_path({a.len(a.m[2]), a.len(a.m[3])}, a.len(a.m[1]), a.tol_nm));
  p.rot = a.m.size() > 4 ? a.m[4] : 0;
  return p;
}

// 2, 20: a line of a width between two points.
Primitive vector_line(const PrimitiveArgs& a) {
  Primitive p;
  a.need(7, "vector line (20)");
  p.exposure = a.exposure_of(a.m[0]);
  Path path =
      line_rect({a.len(a.m[2]), a.len(a.m[3])}, {a.len(a.m[4]), a.len(a.m[5])}, a.len(a.m[1]));
  if (!path.empty()) p.paths.push_back(path);
  p.rot = a.m[6];
  return p;
}

// 21: a rectangle by its centre; 22: by its lower-left corner.
Primitive box_line(const PrimitiveArgs& a) {
  Primitive p;
  a.need(6, a.code() == "21" ? "center line (21)" : "lower-left line (22)");
  p.exposure = a.exposure_of(a.m[0]);
  const double w = a.len(a.m[1]), h = a.len(a.m[2]);
  VecNm c{a.len(a.m[3]), a.len(a.m[4])};
  if (a.code() == "22") c = {c.x + w / 2, c.y + h / 2};
  if (w > 0 && h > 0) p.paths.push_back(rect_path(c, w, h));
  p.rot = a.m[5];
  return p;
}

// 4: a closed outline of n + 1 points.
Primitive outline(const PrimitiveArgs& a) {
  Primitive p;
  a.need(2, "outline (4)");
  p.exposure = a.exposure_of(a.m[0]);
  const double n = a.m[1];
  if (!(n >= 1 && n <= 100000) || n != std::floor(n)) a.bad("outline with a bad vertex count");
  const size_t count = static_cast<size_t>(n);
  a.need(2 + 2 * (count + 1) + 1, "outline (4)");
  Path path;
  for (size_t i = 0; i <= count; ++i) {
    path.push_back(to_int({a.len(a.m[2 + 2 * i]), a.len(a.m[3 + 2 * i])}));
  }
  if (path.front() == path.back()) path.pop_back();  // closed as the spec asks
  make_positive(path);
  p.paths.push_back(path);
  p.rot = a.m[2 + 2 * (count + 1)];
  return p;
}

// 5: a regular polygon.
Primitive polygon(const PrimitiveArgs& a) {
  Primitive p;
  a.need(5, "polygon (5)");
  p.exposure = a.exposure_of(a.m[0]);
  if (!(a.m[1] >= 3 && a.m[1] <= 12)) a.bad("polygon needs 3 to 12 vertices");
  if (a.m[4] > 0) {
    p.paths.push_back(regular_polygon_path({a.len(a.m[2]), a.len(a.m[3])}, a.len(a.m[4]),
                                           static_cast<int>(a.m[1]), 0));
  }
  p.rot = a.m.size() > 5 ? a.m[5] : 0;
  return p;
}

// 6: rings and a cross hair.
Primitive moire(const PrimitiveArgs& a) {
  Primitive p;
  a.need(9, "moire (6)");
  const VecNm c{a.len(a.m[0]), a.len(a.m[1])};
  const double thick = a.len(a.m[3]), gap = a.len(a.m[4]);
  double d = a.len(a.m[2]);
  Paths rings;
  for (int i = 0; i < static_cast<int>(std::fmax(0.0, std::fmin(a.m[5], 1000.0))) && d > 0; ++i) {
    Paths ring{circle_path(c, d, a.tol_nm)};
    if (d - 2 * thick > 0) ring = difference_of(ring, {circle_path(c, d - 2 * thick, a.tol_nm)});
    rings.insert(rings.end(), ring.begin(), ring.end());
    d -= 2 * (thick + gap);
  }
  const double ct = a.len(a.m[6]), cl = a.len(a.m[7]);
  if (ct > 0 && cl > 0) {
    rings.push_back(rect_path(c, cl, ct));
    rings.push_back(rect_path(c, ct, cl));
  }
  p.paths = union_of(rings);
  p.rot = a.m[8];
  return p;
}

// 7: a ring cut by a cross.
Primitive thermal(const PrimitiveArgs& a) {
  Primitive p;
  a.need(5, "thermal (7)");
  const VecNm c{a.len(a.m[0]), a.len(a.m[1])};
  const double outer = a.len(a.m[2]), inner = a.len(a.m[3]), gap = a.len(a.m[4]);
  if (!(outer > inner) || inner < 0 || gap < 0) a.bad("thermal needs outer > inner >= 0");
  Paths ring{circle_path(c, outer, a.tol_nm)};
  Paths cut;
  if (inner > 0) cut.push_back(circle_path(c, inner, a.tol_nm));
  if (gap > 0) {
    cut.push_back(rect_path(c, 2 * outer, gap));
    cut.push_back(rect_path(c, gap, 2 * outer));
  }
  p.paths = difference_of(ring, cut);
  p.rot = a.m.size() > 5 ? a.m[5] : 0;
  return p;
}

Primitive primitive(const PrimitiveArgs& a) {
  const std::string& code = a.code();
  if (code == "1") return circle(a);
  if (code == "2" || code == "20") return vector_line(a);
  if (code == "21" || code == "22") return box_line(a);
  if (code == "4") return outline(a);
  if (code == "5") return polygon(a);
  if (code == "6") return moire(a);
  if (code == "7") return thermal(a);
  a.bad("unknown primitive '" + code + "'");
}

// The primitive, rotated, added to the shape, cut from it or toggled in it.
void expose(const PrimitiveArgs& a, Primitive prim, Paths* shape) {
  rotate_all(prim.paths, prim.rot);
  if (prim.exposure == 1) {
    prim.paths.insert(prim.paths.end(), shape->begin(), shape->end());
    *shape = union_of(prim.paths);
  } else if (prim.exposure == 0) {
    *shape = difference_of(*shape, prim.paths);
  } else if (prim.exposure == 2) {  // toggle (old spec)
    ClipperLib::Clipper c;
    c.AddPaths(*shape, ClipperLib::ptSubject, true);
    c.AddPaths(prim.paths, ClipperLib::ptClip, true);
    c.Execute(ClipperLib::ctXor, *shape, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  } else {
    a.bad("exposure must be 0 or 1, not " + std::to_string(prim.exposure));
  }
}

}  // namespace

Paths evaluate_macro(const ApertureMacro& macro, const std::vector<double>& params, double unit_nm,
                     double tol_nm) {
  std::vector<double> vars(1, 0.0);
  vars.insert(vars.end(), params.begin(), params.end());
  Paths shape;
  for (const MacroStatement& st : macro.statements) {
    auto bad = [&](const std::string& what) {
      throw MacroError(st.line, "macro " + macro.name + ": " + what);
    };
    try {
      if (st.text[0] == '$') {  // $n=expression
        const size_t eq = st.text.find('=');
        if (eq == std::string::npos) bad("'" + st.text + "' is neither a primitive nor $n=...");
        const std::string num = st.text.substr(1, eq - 1);
        if (num.empty() || num.size() > 4 ||
            num.find_first_not_of("0123456789") != std::string::npos) {
          bad("bad variable name '$" + num + "'");
        }
        const size_t n = static_cast<size_t>(std::stoi(num));
        if (vars.size() <= n) vars.resize(n + 1, 0.0);
        vars[n] = evaluate_macro_expression(st.text.substr(eq + 1), vars);
        continue;
      }
      const std::vector<std::string> fields = split_commas(st.text);
      std::vector<double> m;
      for (size_t i = 1; i < fields.size(); ++i) {
        m.push_back(evaluate_macro_expression(fields[i], vars));
      }
      PrimitiveArgs a{macro, st, fields, m, unit_nm, tol_nm};
      expose(a, primitive(a), &shape);
    } catch (const std::invalid_argument& e) {
      bad(e.what());
    }
  }
  return shape;
}

}  // namespace host::pcb
