// The board plot's layout and colours, shared by its SVG writer and its PNG (cairo) renderer
// so the two pictures stay the same.
#ifndef HOST_LIB_PLOT_BOARD_PLOT_STYLE_H
#define HOST_LIB_PLOT_BOARD_PLOT_STYLE_H

#include "host/lib/plot/plot_layout.h"

namespace host {
namespace board_plot_style {

using namespace plot_layout;  // NOLINT: the bands, the same as the plan plot's

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
// Some entries are drawn only when the plot shows what they name.
enum class Shown { kAlways, kWithCutout, kWithSimulated };
struct LegendEntry {
  double x_px;
  Rgba colour;
  const char* label;
  Shown shown;
};
const LegendEntry kLegend[] = {{0, kCopper, "copper", Shown::kAlways},
                               {100, kIsolation, "isolation (tool width)", Shown::kAlways},
                               {280, kCutout, "cut-out (cutter width)", Shown::kWithCutout},
                               {460, kTab, "tabs", Shown::kWithCutout},
                               {540, kHole, "holes", Shown::kAlways},
                               {630, kGap, "narrow gap", Shown::kAlways},
                               {750, kSimulated, "simulated tool", Shown::kWithSimulated}};
const int kLegendSize = sizeof kLegend / sizeof kLegend[0];
// The entries a plot shows, into shown[kLegendSize], each moved left over those left out (a
// board without a cut-out shows no cut-out or tabs). Returns how many.
inline int legend_shown(bool simulated, bool cutout, LegendEntry* shown) {
  int n = 0;
  double left_out_px = 0;
  for (int i = 0; i < kLegendSize; ++i) {
    const Shown when = kLegend[i].shown;
    if ((when == Shown::kWithCutout && !cutout) || (when == Shown::kWithSimulated && !simulated)) {
      if (i + 1 < kLegendSize) left_out_px += kLegend[i + 1].x_px - kLegend[i].x_px;
      continue;
    }
    shown[n] = kLegend[i];
    shown[n++].x_px -= left_out_px;
  }
  return n;
}

}  // namespace board_plot_style
}  // namespace host

#endif  // HOST_LIB_PLOT_BOARD_PLOT_STYLE_H
