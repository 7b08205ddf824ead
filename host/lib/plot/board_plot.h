// SVG and PNG plot of a planned board job: copper, the isolation paths drawn with the tool's
// width (so a user sees at a glance that every net is separated), holes and slots, the
// cut-out with the cutter's width, narrow gaps circled in red, optionally the simulated path.
#ifndef HOST_LIB_PLOT_BOARD_PLOT_H
#define HOST_LIB_PLOT_BOARD_PLOT_H

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/lib/pcb/board_job.h"
#include "host/lib/plan/pen_path.h"
#include "host/lib/plot/plot.h"  // PlotFrame

namespace host {

struct BoardPlotInput {
  std::string title;
  const pcb::BoardJob* job = nullptr;
  PenPath simulated;    // machine frame; empty: not drawn
  int width_px = 1400;  // the height follows the board's aspect
};

// How machine mm map to pixels in the plot, and its height for the given width.
PlotFrame board_plot_frame(const pcb::BoardJob& job, int width_px, int* height_px);

// Writes the plot; an empty path skips that file. Throws std::runtime_error naming the file
// when it cannot be written.
void write_board_plot(const BoardPlotInput& in, const std::string& svg_path,
                      const std::string& png_path);

}  // namespace host

#endif  // HOST_LIB_PLOT_BOARD_PLOT_H
