// One protocol message as a queued command, through the shared codec (the controller's
// own field checks), for the job encoder, the spline frames and the resume prefix; and
// back (the resume reads the commands it continues from).
#ifndef HOST_LIB_STREAM_ENCODE_COMMAND_H
#define HOST_LIB_STREAM_ENCODE_COMMAND_H

#include <fmt/format.h>  // fmt::format

#include "firmware/protocol/codec.h"      // proto::encode, proto::decode
#include "host/lib/plan/job_plan.h"       // PlanError
#include "host/lib/stream/job_encoder.h"  // QueuedCommand

namespace host {

// msg as a queued command marked with step and curve (-1: a set-up frame, no curve), or
// PlanError with the codec's verdict.
template <typename Msg>
QueuedCommand encode_command(const Msg& msg, int step = -1, int curve = -1) {
  proto::Payload payload;
  const proto::ErrorCode error = proto::encode(msg, &payload);
  if (error != proto::ErrorCode::kOk) {
    const std::string where = step >= 0 ? fmt::format("step {}", step) : "set-up";
    throw PlanError(fmt::format("{}: command '{}' has a field out of range (code {})", where,
                                static_cast<char>(Msg::kLetter), static_cast<int>(error)));
  }
  QueuedCommand c;
  c.letter = static_cast<uint8_t>(Msg::kLetter);
  c.payload.assign(payload.bytes, payload.bytes + payload.length);
  c.step = step;
  c.curve = curve;
  return c;
}

// The message a queued command carries (its letter already checked by the caller).
template <typename Msg>
Msg decoded(const QueuedCommand& c) {
  Msg m{};
  proto::decode(c.payload.data(), static_cast<uint8_t>(c.payload.size()), &m);
  return m;
}

}  // namespace host

#endif  // HOST_LIB_STREAM_ENCODE_COMMAND_H
