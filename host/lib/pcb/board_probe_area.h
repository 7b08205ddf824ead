// Where a board job's height map is probed (issue 25): the area every command that probes
// for a board uses (`engraver probe`/`run --probe`/`send --probe` and the server's
// probe-first jobs), so both probe the same grid.
#ifndef HOST_LIB_PCB_BOARD_PROBE_AREA_H
#define HOST_LIB_PCB_BOARD_PROBE_AREA_H

#include <optional>  // std::optional

#include "host/lib/heightmap/surface_model.h"  // AreaMm
#include "host/lib/pcb/board_job.h"

namespace host::pcb {

// The flip axis of a double-sided board in the machine frame (x, mm, before a measured
// placement): the holes given off it stand beside it with their mirror images.
double flip_axis_machine_x_mm(const BoardJob& job);

// The extent (machine frame, mm) of everything `job` cuts; for the top side of a board with
// alignment holes also of what its bottom side cuts after the flip, planned from the same
// layers and options with side bottom: where it lands on the machine (a map kept with the
// table, height_map_flip=table) and its mirror about the flip axis (where those places lay
// before the flip, height_map_flip=blank). Without the bottom copper among the layers the
// bottom's isolation is not known: the mirror of the top's cuts stands in for it. Never
// below X 0. nullopt for a job that cuts nothing.
std::optional<heightmap::AreaMm> board_probe_area(const BoardLayers& layers,
                                                  const BoardOptions& options, const BoardJob& job);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_BOARD_PROBE_AREA_H
