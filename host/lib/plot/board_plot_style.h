// The board plot's layout and colours, shared by its SVG writer and its PNG (cairo) renderer
// so the two pictures stay the same.
#ifndef HOST_LIB_PLOT_BOARD_PLOT_STYLE_H
#define HOST_LIB_PLOT_BOARD_PLOT_STYLE_H

namespace host {
namespace board_plot_style {

const double kTitleBandPx = 40.0;
const double kBottomBandPx = 60.0;
const double kSideMarginPx = 20.0;

struct Rgba {
  double r, g, b, a;
};
const Rgba kBoard = {0.86, 0.90, 0.80, 1.0};       // substrate inside the outline
const Rgba kCopper = {0.85, 0.55, 0.20, 1.0};      // copper
const Rgba kIsolation = {0.15, 0.35, 0.90, 0.45};  // swept V-bit
const Rgba kIsolationCentre = {0.05, 0.15, 0.55, 1.0};
const Rgba kCutout = {0.10, 0.60, 0.20, 0.40};  // swept cutter
const Rgba kCutoutCentre = {0.05, 0.35, 0.10, 1.0};
const Rgba kTab = {0.55, 0.25, 0.65, 0.9};  // cutter lifted over a holding tab
const Rgba kHole = {0.12, 0.12, 0.12, 1.0};
const Rgba kGap = {0.90, 0.00, 0.00, 1.0};
const Rgba kSimulated = {0.75, 0.05, 0.05, 0.9};

// The legend, left to right in the bottom band, each entry `x_px` right of the side margin.
// The last entry is drawn only when the plot shows a simulated tool.
struct LegendEntry {
  double x_px;
  Rgba colour;
  const char* label;
};
const LegendEntry kLegend[] = {{0, kCopper, "copper"},
                               {100, kIsolation, "isolation (tool width)"},
                               {280, kCutout, "cut-out (cutter width)"},
                               {460, kTab, "tabs"},
                               {540, kHole, "holes"},
                               {630, kGap, "narrow gap"},
                               {750, kSimulated, "simulated tool"}};
inline int legend_entries(bool simulated) {
  const int all = sizeof kLegend / sizeof kLegend[0];
  return simulated ? all : all - 1;
}

}  // namespace board_plot_style
}  // namespace host

#endif  // HOST_LIB_PLOT_BOARD_PLOT_STYLE_H
