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
      const std::string& code = fields[0];
      auto need = [&](size_t n, const char* what) {
        if (m.size() < n) {
          bad(std::string(what) + " needs " + std::to_string(n) + " modifiers, got " +
              std::to_string(m.size()));
        }
      };
      auto len = [&](double v) {
        const double nm = v * unit_nm;
        if (!(std::fabs(nm) <= 1e10)) bad("a size or position beyond 10 m");
        return nm;
      };
      // 0 off, 1 on, 2 toggle (old spec); anything else is refused before any cast.
      auto exposure_of = [&](double v) {
        if (v != 0 && v != 1 && v != 2) bad("exposure must be 0 or 1, not " + fields[1]);
        return static_cast<int>(v);
      };
      Paths prim;
      int exposure = 1;
      double rot = 0;
      if (code == "1") {
        need(4, "circle (1)");
        exposure = exposure_of(m[0]);
        if (m[1] > 0) prim.push_back(circle_path({len(m[2]), len(m[3])}, len(m[1]), tol_nm));
        rot = m.size() > 4 ? m[4] : 0;
      } else if (code == "2" || code == "20") {
        need(7, "vector line (20)");
        exposure = exposure_of(m[0]);
        Path p = line_rect({len(m[2]), len(m[3])}, {len(m[4]), len(m[5])}, len(m[1]));
        if (!p.empty()) prim.push_back(p);
        rot = m[6];
      } else if (code == "21" || code == "22") {
        need(6, code == "21" ? "center line (21)" : "lower-left line (22)");
        exposure = exposure_of(m[0]);
        const double w = len(m[1]), h = len(m[2]);
        VecNm c{len(m[3]), len(m[4])};
        if (code == "22") c = {c.x + w / 2, c.y + h / 2};
        if (w > 0 && h > 0) prim.push_back(rect_path(c, w, h));
        rot = m[5];
      } else if (code == "4") {
        need(2, "outline (4)");
        exposure = exposure_of(m[0]);
        const double n = m[1];
        if (!(n >= 1 && n <= 100000) || n != std::floor(n)) bad("outline with a bad vertex count");
        const size_t count = static_cast<size_t>(n);
        need(2 + 2 * (count + 1) + 1, "outline (4)");
        Path p;
        for (size_t i = 0; i <= count; ++i) {
          p.push_back(to_int({len(m[2 + 2 * i]), len(m[3 + 2 * i])}));
        }
        if (p.front() == p.back()) p.pop_back();  // closed as the spec asks
        make_positive(p);
        prim.push_back(p);
        rot = m[2 + 2 * (count + 1)];
      } else if (code == "5") {
        need(5, "polygon (5)");
        exposure = exposure_of(m[0]);
        if (!(m[1] >= 3 && m[1] <= 12)) bad("polygon needs 3 to 12 vertices");
        if (m[4] > 0) {
          prim.push_back(
              regular_polygon_path({len(m[2]), len(m[3])}, len(m[4]), static_cast<int>(m[1]), 0));
        }
        rot = m.size() > 5 ? m[5] : 0;
      } else if (code == "6") {
        need(9, "moire (6)");
        const VecNm c{len(m[0]), len(m[1])};
        const double thick = len(m[3]), gap = len(m[4]);
        double d = len(m[2]);
        Paths rings;
        for (int i = 0; i < static_cast<int>(std::fmax(0.0, std::fmin(m[5], 1000.0))) && d > 0;
             ++i) {
          Paths ring{circle_path(c, d, tol_nm)};
          if (d - 2 * thick > 0)
            ring = difference_of(ring, {circle_path(c, d - 2 * thick, tol_nm)});
          rings.insert(rings.end(), ring.begin(), ring.end());
          d -= 2 * (thick + gap);
        }
        const double ct = len(m[6]), cl = len(m[7]);
        if (ct > 0 && cl > 0) {
          rings.push_back(rect_path(c, cl, ct));
          rings.push_back(rect_path(c, ct, cl));
        }
        prim = union_of(rings);
        rot = m[8];
      } else if (code == "7") {
        need(5, "thermal (7)");
        const VecNm c{len(m[0]), len(m[1])};
        const double outer = len(m[2]), inner = len(m[3]), gap = len(m[4]);
        if (!(outer > inner) || inner < 0 || gap < 0) bad("thermal needs outer > inner >= 0");
        Paths ring{circle_path(c, outer, tol_nm)};
        Paths cut;
        if (inner > 0) cut.push_back(circle_path(c, inner, tol_nm));
        if (gap > 0) {
          cut.push_back(rect_path(c, 2 * outer, gap));
          cut.push_back(rect_path(c, gap, 2 * outer));
        }
        prim = difference_of(ring, cut);
        rot = m.size() > 5 ? m[5] : 0;
      } else {
        bad("unknown primitive '" + code + "'");
      }
      rotate_all(prim, rot);
      if (exposure == 1) {
        prim.insert(prim.end(), shape.begin(), shape.end());
        shape = union_of(prim);
      } else if (exposure == 0) {
        shape = difference_of(shape, prim);
      } else if (exposure == 2) {  // toggle (old spec)
        ClipperLib::Clipper c;
        c.AddPaths(shape, ClipperLib::ptSubject, true);
        c.AddPaths(prim, ClipperLib::ptClip, true);
        c.Execute(ClipperLib::ctXor, shape, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
      } else {
        bad("exposure must be 0 or 1, not " + std::to_string(exposure));
      }
    } catch (const std::invalid_argument& e) {
      bad(e.what());
    }
  }
  return shape;
}

}  // namespace host::pcb
