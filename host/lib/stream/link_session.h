// The sender's session with the controller outside the ordered stream: the #I handshake
// (its seq, the version asked for, the *I answer) and the counters and answers of the
// un-ordered frames (real-time frames and their acks, #? / #T queries).
#ifndef HOST_LIB_STREAM_LINK_SESSION_H
#define HOST_LIB_STREAM_LINK_SESSION_H

#include <chrono>   // std::chrono
#include <cstdint>  // uint8_t

#include "firmware/protocol/messages.h"  // proto::SessionReply

namespace host {

struct LinkSession {
  proto::SessionReply reply{};  // the controller's *I
  bool open = false;
  uint8_t seq = 0;  // of the last #I
  // The version #I asks for: ours, or an older controller's own that it named when it
  // refused ours (then version_lowered until #I is sent again).
  uint8_t version = proto::kProtocolVersion;
  bool version_lowered = false;
  uint8_t realtime_seq = 0;
  uint8_t status_seq = 0;  // #? and #T
  bool realtime_acked = false;
  bool status_outstanding = false;
  std::chrono::steady_clock::time_point status_sent;
};

}  // namespace host

#endif  // HOST_LIB_STREAM_LINK_SESSION_H
