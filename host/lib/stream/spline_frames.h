// The data frames of one spline (after its #B): compact #K frames (differences, see
// firmware/protocol/compact_spline.h) or fixed-width #D frames; and the way back from such
// frames to the spline, for host code that follows a job's frames.
#ifndef HOST_LIB_STREAM_SPLINE_FRAMES_H
#define HOST_LIB_STREAM_SPLINE_FRAMES_H

#include <cstdint>  // uint8_t
#include <vector>   // std::vector

#include "firmware/core/spline.h"         // core::Spline
#include "host/lib/stream/job_encoder.h"  // QueuedCommand

namespace host {

// Appends the frames carrying sp's control points, then its knots, each frame as full as
// max_payload allows, marked with step and curve: #K frames when compact (a knot span of
// 2^31 or more goes in a #D frame), else #D frames. Throws PlanError for knots that decrease.
void append_spline_data(const core::Spline& sp, int step, int curve, unsigned max_payload,
                        bool compact, std::vector<QueuedCommand>* out);

// True for the frames that fill the open spline (#D, #K): no queue slot and no job command
// of their own on the controller.
bool is_spline_data(uint8_t letter);
// Adds the values of a #D or #K frame to s, as the controller's store does (s holds the
// #B's degree, rationality and counts, and the values before this frame); false for any
// other frame or one that does not decode.
bool add_spline_data(const QueuedCommand& command, core::Spline* s);

}  // namespace host

#endif  // HOST_LIB_STREAM_SPLINE_FRAMES_H
