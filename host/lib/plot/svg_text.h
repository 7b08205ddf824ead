// SVG documents written as plain text (the board plot, the plan plot): numbers at 1/100
// pixel, XML-escaped text, and the file written whole. No cairo: a plot's SVG should not
// load cairo and fontconfig (a command's start-up, issue 24).
#ifndef HOST_LIB_PLOT_SVG_TEXT_H
#define HOST_LIB_PLOT_SVG_TEXT_H

#include <string>  // std::string

#include "host/lib/drawing/bspline.h"  // Point2

namespace host {

// Appends numbers and text to the document.
class SvgText {
 public:
  std::string out;
  SvgText& operator<<(const char* s) {
    out += s;
    return *this;
  }
  SvgText& operator<<(const std::string& s) {
    out += s;
    return *this;
  }
  // Pixels to 1/100 px, trailing zeros dropped.
  SvgText& operator<<(double v);
  SvgText& point(const Point2& q) { return *this << q.x() << " " << q.y(); }
  // "rgb(r,g,b)" of components 0..1.
  SvgText& colour(double r, double g, double b);
  // s with <, >, & and " escaped.
  SvgText& text(const std::string& s);
};

// Writes doc to path; throws std::runtime_error naming path when it cannot.
void write_svg_file(const std::string& doc, const std::string& path);

}  // namespace host

#endif  // HOST_LIB_PLOT_SVG_TEXT_H
