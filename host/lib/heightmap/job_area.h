// Where a job cuts (the area a height map must cover) and the refusal of a job that leaves
// its map before anything is sent.
#ifndef HOST_LIB_HEIGHTMAP_JOB_AREA_H
#define HOST_LIB_HEIGHTMAP_JOB_AREA_H

#include <optional>  // std::optional

#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/surface_model.h"  // AreaMm
#include "host/lib/plan/job_plan.h"

namespace host::heightmap {

// The extent of every place the tool is down: the curves, straight feeds and drilled holes
// (machine frame, mm); nullopt for a job that never cuts.
std::optional<AreaMm> cutting_area(const JobPlan& plan);

// Throws HeightMapError (naming `what`, the map's file) when the job cuts outside the map:
// the controller would hold the edge's height there, not the blank's.
void refuse_job_outside_map(const JobPlan& plan, const HeightMap& map, const std::string& what);

}  // namespace host::heightmap

#endif  // HOST_LIB_HEIGHTMAP_JOB_AREA_H
