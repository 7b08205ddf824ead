// The parts of open tool-centre paths that come within reach of copper or run inside it:
// the isolation check sweeps only these (a clean job's centres keep their distance
// everywhere, and sweeping them all cost half the check on A64-OlinuXino).
#ifndef HOST_LIB_PCB_NEAR_COPPER_H
#define HOST_LIB_PCB_NEAR_COPPER_H

#include <polyclipping/clipper.hpp>  // ClipperLib::Paths

namespace host::pcb {

// Runs of consecutive segments of `centres` (open paths, nm) each of which comes closer than
// reach_nm to an edge of `copper` (closed paths, nm, inside by even-odd), or lies inside
// copper; each run keeps its end vertices. A segment left out is farther than reach_nm from
// all copper, so a disc of radius up to reach_nm swept along it touches none.
ClipperLib::Paths runs_near_copper(const ClipperLib::Paths& centres,
                                   const ClipperLib::Paths& copper, double reach_nm);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_NEAR_COPPER_H
