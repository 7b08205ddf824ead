// Height-map frames as they arrive (see map_reception.h).
#include "firmware/app/map_reception.h"

namespace app {

using proto::ErrorCode;

void MapReception::announced(uint16_t points) {
  points_ = points;
  expected_ = 0;
  span_.lowest = 0;  // the span counts the job's zero height too
  span_.highest = 0;
}

ErrorCode MapReception::check(const proto::HeightMapDataCmd& c, MapHeightsArgs* out, MapSpan* span,
                              uint8_t* detail) const {
  const uint16_t end = (uint16_t)(c.index + c.height_n);
  if (points_ == 0 || c.index != expected_ || end > points_) {
    *detail = proto::kHeightMapSequence;
    return ErrorCode::kHeightMap;
  }
  out->index = c.index;
  out->n = c.height_n;
  MapSpan s = span_;
  for (uint8_t i = 0; i < c.height_n; ++i) {
    const int16_t h = (int16_t)c.height_um[i];  // the codec kept it within +-1000
    out->height_um[i] = h;
    if (h < s.lowest) s.lowest = h;
    if (h > s.highest) s.highest = h;
  }
  if (end == points_ && s.highest - s.lowest > proto::kMaxHeightMapSpanUm) {
    *detail = proto::kHeightMapSpan;
    return ErrorCode::kHeightMap;
  }
  *span = s;
  return ErrorCode::kOk;
}

}  // namespace app
