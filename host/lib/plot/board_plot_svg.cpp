// The board plot as plain SVG text (see board_plot_svg.h). Each part is drawn as
// board_plot.cpp's cairo renderer draws it, in the same order and colours.
#include "host/lib/plot/board_plot_svg.h"

#include <algorithm>  // std::max
#include <sstream>    // std::ostringstream

#include "host/lib/pcb/pcb_geometry.h"
#include "host/lib/plot/board_plot_style.h"
#include "host/lib/plot/cairo_plot.h"  // nice_length
#include "host/lib/plot/svg_text.h"

namespace host {

namespace {

using namespace board_plot_style;  // NOLINT: the layout and colours

// The document, with board_plot_style's colours.
class Svg : public SvgText {
 public:
  Svg& colour(const Rgba& c) {
    SvgText::colour(c.r, c.g, c.b);
    return *this;
  }
};

// One ring or polyline as path data: "M x y L x y x y ..."
template <typename Points, typename ToPx>
void path_data(Svg& svg, const Points& pts, ToPx to_px) {
  for (size_t i = 0; i < pts.size(); ++i) {
    svg << (i == 0 ? "M" : i == 1 ? " L" : " ");
    svg.point(to_px(pts[i]));
  }
}

void polygons(Svg& svg, const PlotFrame& f, const ClipperLib::Paths& paths, const Rgba& c) {
  if (paths.empty()) return;
  svg << "<path fill=\"";
  svg.colour(c) << "\" fill-rule=\"evenodd\" d=\"";
  for (const auto& p : paths) {
    if (p.empty()) continue;
    path_data(svg, p, [&f](const ClipperLib::IntPoint& q) { return f.to_px(pcb::to_mm(q)); });
    svg << "Z";
  }
  svg << "\"/>\n";
}

void polyline(Svg& svg, const PlotFrame& f, const std::vector<Point2>& pts) {
  path_data(svg, pts, [&f](const Point2& q) { return f.to_px(q); });
  if (pts.size() == 1) svg << " l0.01 0";  // a dot: cairo strokes it as a round cap too
}

// Strokes of one colour in one group painted with the colour's alpha: where they overlap
// the colour stays even (cairo's push_group / paint_with_alpha).
void stroke_group(Svg& svg, const PlotFrame& f, const std::vector<std::vector<Point2>>& paths,
                  double width_px, const Rgba& c) {
  if (paths.empty()) return;
  svg << "<g opacity=\"" << c.a << "\" fill=\"none\" stroke=\"";
  svg.colour(c) << "\" stroke-width=\"" << std::max(width_px, 0.5)
                << "\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
  for (const auto& p : paths) {
    if (p.empty()) continue;
    svg << "<path d=\"";
    polyline(svg, f, p);
    svg << "\"/>\n";
  }
  svg << "</g>\n";
}

void circle(Svg& svg, const Point2& c, double r) {
  svg << "<circle cx=\"" << c.x() << "\" cy=\"" << c.y() << "\" r=\"" << r << "\"/>\n";
}

// The holes as dots, the slots as strokes of their width.
void holes(Svg& svg, const pcb::BoardJob& job, const PlotFrame& f) {
  const double s = f.scale_px_per_mm;
  if (!job.holes_machine.empty()) {
    svg << "<g fill=\"";
    svg.colour(kHole) << "\">\n";
    for (const pcb::Hole& h : job.holes_machine)
      circle(svg, f.to_px(pcb::to_mm(ClipperLib::IntPoint(h.at.x, h.at.y))),
             std::max(0.5, h.diameter_nm / 2e6 * s));
    svg << "</g>\n";
  }
  for (const pcb::Slot& sl : job.slots_machine) {
    svg << "<path fill=\"none\" stroke=\"";
    svg.colour(kHole) << "\" stroke-width=\"" << std::max(1.0, sl.diameter_nm / 1e6 * s)
                      << "\" stroke-linecap=\"round\" d=\"";
    polyline(svg, f,
             {pcb::to_mm(ClipperLib::IntPoint(sl.from.x, sl.from.y)),
              pcb::to_mm(ClipperLib::IntPoint(sl.to.x, sl.to.y))});
    svg << "\"/>\n";
  }
}

// A ring around each narrow gap.
void gaps(Svg& svg, const pcb::BoardJob& job, const PlotFrame& f) {
  if (job.report.narrow_gaps.empty()) return;
  const double s = f.scale_px_per_mm;
  svg << "<g fill=\"none\" stroke-width=\"2\" stroke=\"";
  svg.colour(kGap) << "\">\n";
  for (const pcb::NarrowGap& g : job.report.narrow_gaps)
    circle(svg,
           f.to_px(job.frame.to_machine(Point2(g.at.x / pcb::kNmPerMm, g.at.y / pcb::kNmPerMm))),
           std::max(8.0, 0.5 * s));
  svg << "</g>\n";
}

void text_at(Svg& svg, double x, double y, const std::string& s) {
  svg << "<text x=\"" << x << "\" y=\"" << y << "\">";
  svg.text(s) << "</text>\n";
}

void legend_box(Svg& svg, double x, double y, const Rgba& c, const std::string& label) {
  svg << "<rect x=\"" << x << "\" y=\"" << y - 8 << "\" width=\"24\" height=\"12\" fill=\"";
  svg.colour(c) << "\" fill-opacity=\"" << c.a << "\"/>\n";
  text_at(svg, x + 30, y + 3, label);
}

// Title, legend, scale bar (as draw_scale_bar draws it).
void labels(Svg& svg, const BoardPlotInput& in, const PlotFrame& f, int height_px) {
  svg << "<g font-family=\"sans-serif\" font-weight=\"bold\" font-size=\"16\">\n";
  text_at(svg, kSideMarginPx, kTitleBaselinePx, in.title);
  svg << "</g>\n<g font-family=\"sans-serif\" font-size=\"12\">\n";
  const double y = height_px - kBottomBandPx / 2;
  LegendEntry shown[kLegendSize];
  const int n = legend_shown(!in.simulated.empty(), !in.job->cutout_paths_mm.empty(), shown);
  for (int i = 0; i < n; ++i)
    legend_box(svg, kSideMarginPx + shown[i].x_px, y, shown[i].colour, shown[i].label);
  const double s = f.scale_px_per_mm;
  const double bar_mm = nice_length(in.width_px / 6.0 / s);
  const double x1 = in.width_px - kSideMarginPx, x0 = x1 - bar_mm * s;
  svg << "<path fill=\"none\" stroke=\"rgb(0,0,0)\" stroke-width=\"2\" d=\"M" << x0 << " " << y - 5
      << " L" << x0 << " " << y << " " << x1 << " " << y << " " << x1 << " " << y - 5 << "\"/>\n";
  std::ostringstream label;
  label << bar_mm << " mm";
  text_at(svg, x0, y + 16, label.str());
  svg << "</g>\n";
}

}  // namespace

std::string board_plot_svg(const BoardPlotInput& in, const PlotFrame& f, int height_px) {
  const pcb::BoardJob& job = *in.job;
  Svg svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << in.width_px << "pt\" height=\""
      << height_px << "pt\" viewBox=\"0 0 " << in.width_px << " " << height_px << "\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"rgb(255,255,255)\"/>\n";
  polygons(svg, f, job.board_machine_nm, kBoard);
  polygons(svg, f, pcb::copper_paths(job.copper_machine), kCopper);
  const double s = f.scale_px_per_mm;
  stroke_group(svg, f, job.clearing_paths_mm, 2 * job.clearing_tool_radius_mm * s, kIsolation);
  stroke_group(svg, f, job.clearing_paths_mm, 0.6, kIsolationCentre);
  stroke_group(svg, f, job.isolation_paths_mm, 2 * job.tool_radius_mm * s, kIsolation);
  stroke_group(svg, f, job.isolation_paths_mm, 0.6, kIsolationCentre);
  stroke_group(svg, f, job.cutout_paths_mm, 2 * job.cutter_radius_mm * s, kCutout);
  stroke_group(svg, f, job.cutout_paths_mm, 0.6, kCutoutCentre);
  stroke_group(svg, f, job.tab_paths_mm, 2 * job.cutter_radius_mm * s, kTab);
  holes(svg, job, f);
  if (!in.simulated.empty()) {
    const std::vector<std::vector<Point2>> down = pen_down_pieces(in.simulated);
    stroke_group(svg, f, down, 0.5, kSimulated);
  }
  gaps(svg, job, f);
  labels(svg, in, f, height_px);
  svg << "</svg>\n";
  return svg.out;
}

void write_board_plot_svg(const BoardPlotInput& in, const PlotFrame& f, int height_px,
                          const std::string& path) {
  write_svg_file(board_plot_svg(in, f, height_px), path);
}

}  // namespace host
