// The outline of an open path swept by a disc, built directly: one closed polygon whose
// non-zero filling is the swept region (round ends, round outside corners), for a Clipper
// union to clean up. Clipper's own round offset builds every inside corner as a spike back
// to the path's vertex, so a densely sampled curve (a tool path) gives a union with as many
// crossings as vertices; here an inside corner is the two offset edges' crossing wherever it
// lies on both, the spike only where it does not (a corner sharper than its edges are long).
#ifndef HOST_LIB_PCB_DISC_OUTLINE_H
#define HOST_LIB_PCB_DISC_OUTLINE_H

#include <clipper.hpp>  // ClipperLib::Path

namespace host::pcb {

// path: open, in nm (repeated points are skipped; a single point gives a disc). radius_nm >
// 0. Arcs are chords within arc_tolerance_nm of the circle, inside it, as Clipper's (at most
// a quarter of the radius). The polygon runs clockwise: its winding is negative exactly on
// the swept region (to the chords and the nanometre rounding), so outlines of many paths
// unite under the non-zero rule; it crosses itself where the path does.
ClipperLib::Path disc_sweep_outline(const ClipperLib::Path& path, double radius_nm,
                                    double arc_tolerance_nm);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_DISC_OUTLINE_H
