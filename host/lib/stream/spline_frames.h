// The data frames of one spline (after its #B): #Q contour frames for lines and arcs
// (firmware/protocol/contour_spline.h), compact #K frames (differences, compact_spline.h)
// or fixed-width #D frames; and the way back from such frames to the spline, for host code
// that follows a job's frames.
#ifndef HOST_LIB_STREAM_SPLINE_FRAMES_H
#define HOST_LIB_STREAM_SPLINE_FRAMES_H

#include <cstdint>  // uint8_t
#include <vector>   // std::vector

#include "firmware/core/spline.h"         // core::Spline
#include "host/lib/stream/job_encoder.h"  // QueuedCommand

namespace host {

// Appends the frames carrying sp's control points, then its knots, each frame as full as
// max_payload allows, marked with step and curve, in the given encoding (SplineFrames).
// Throws PlanError for knots that decrease.
void append_spline_data(const core::Spline& sp, int step, int curve, unsigned max_payload,
                        SplineFrames encoding, std::vector<QueuedCommand>* out);

// True for the frames that fill the open spline (the message table's kSplineData role: #D,
// #K, #Q): no queue slot and no job command of their own on the controller.
bool is_spline_data(uint8_t letter);
// Adds the values of a #D, #K or #Q frame to s, as the controller's store does (s holds the
// #B's degree, rationality and counts, and the values before this frame); false for any
// other frame or one that does not decode.
bool add_spline_data(const QueuedCommand& command, core::Spline* s);

}  // namespace host

#endif  // HOST_LIB_STREAM_SPLINE_FRAMES_H
