// Board outlines are drawn as separate strokes in any order (EasyEDA writes them shuffled,
// with 1 um gaps): join the centre lines end to end into as few paths as possible.
#ifndef HOST_LIB_PCB_GERBER_OUTLINE_H
#define HOST_LIB_PCB_GERBER_OUTLINE_H

#include <clipper.hpp>  // ClipperLib::Paths

#include <vector>  // std::vector

namespace host::pcb {

// Joins strokes whose ends lie within `join_nm` of each other (reversing where needed). A
// chain that comes back to its start is closed: its last point is set to its first.
ClipperLib::Paths join_strokes(const std::vector<ClipperLib::Path>& strokes, double join_nm);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_GERBER_OUTLINE_H
