// Small DXF files written by the tests: header, blocks and entities from group lists.
#ifndef HOST_TESTS_HOST_DRAWING_DXF_BUILDER_H
#define HOST_TESTS_HOST_DRAWING_DXF_BUILDER_H

#include <gtest/gtest.h>  // testing::TempDir

#include <unistd.h>  // getpid

#include <fstream>  // std::ofstream
#include <sstream>  // std::ostringstream
#include <string>   // std::string
#include <vector>   // std::vector

namespace host::test {

// Group code/value pairs as DXF text.
class Groups {
 public:
  Groups& g(int code, const std::string& value) {
    s_ << code << "\n" << value << "\n";
    return *this;
  }
  Groups& g(int code, double value) {
    std::ostringstream v;
    v.precision(17);
    v << value;
    return g(code, v.str());
  }
  Groups& g(int code, int value) { return g(code, std::to_string(value)); }
  Groups& pt(int code, double x, double y) { return g(code, x).g(code + 10, y).g(code + 20, 0.0); }
  std::string str() const { return s_.str(); }

 private:
  std::ostringstream s_;
};

// A complete DXF: $INSUNITS (omitted when insunits < 0), blocks, entities, EOF.
inline std::string dxf_text(const std::string& entities, int insunits = 4,
                            const std::string& blocks = "") {
  Groups h;
  h.g(0, "SECTION").g(2, "HEADER");
  if (insunits >= 0) h.g(9, "$INSUNITS").g(70, insunits);
  h.g(0, "ENDSEC");
  if (!blocks.empty()) h.g(0, "SECTION").g(2, "BLOCKS");
  std::string out = h.str() + blocks;
  Groups e;
  if (!blocks.empty()) e.g(0, "ENDSEC");
  e.g(0, "SECTION").g(2, "ENTITIES");
  out += e.str() + entities;
  Groups t;
  t.g(0, "ENDSEC").g(0, "EOF");
  return out + t.str();
}

// Writes text to a fresh file in the test temp dir; returns its path. The process id in
// the name keeps tests that ctest runs in parallel apart.
inline std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + "/" + std::to_string(getpid()) + "-" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// A SPLINE entity from its parts (weights empty: none written).
inline std::string spline_entity(int degree, const std::vector<double>& knots,
                                 const std::vector<std::pair<double, double>>& ctrl,
                                 const std::vector<double>& weights = {}, int flags = 8,
                                 const std::string& handle = "2A") {
  Groups s;
  s.g(0, "SPLINE").g(5, handle).g(100, "AcDbEntity").g(8, "0").g(100, "AcDbSpline");
  s.g(70, flags).g(71, degree).g(72, static_cast<int>(knots.size()));
  s.g(73, static_cast<int>(ctrl.size())).g(74, 0);
  for (double k : knots) s.g(40, k);
  for (double w : weights) s.g(41, w);
  for (const auto& p : ctrl) s.pt(10, p.first, p.second);
  return s.str();
}

}  // namespace host::test

#endif  // HOST_TESTS_HOST_DRAWING_DXF_BUILDER_H
