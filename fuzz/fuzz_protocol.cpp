// libFuzzer target: the frame parser and every payload decoder. The input is a byte stream;
// its first byte steers the harness (which parser direction, when to simulate a time-out or
// a UART error). Extend here (e.g. feed frames to the dispatcher) by linking more libraries.
#include <stddef.h>  // size_t
#include <stdint.h>  // uint8_t
#include <stdlib.h>  // abort

#include "firmware/protocol/codec.h"                // decode_frame
#include "firmware/protocol/contour_spline.h"       // unpack_contour
#include "firmware/protocol/parser.h"               // Parser
#include "firmware/protocol/sequence_window.h"      // SequenceWindow
#include "host_tests/protocol/message_roundtrip.h"  // round_trip_any

namespace {

// Stops the run: a property the protocol guarantees was broken.
void check(bool ok) {
  if (!ok) abort();
}

// A #Q that decodes, unpacked into a contour spline as the store would: every point it
// writes is in range, every middle weight a cosine (0, 1].
void unpack_contour_frame(const proto::Frame& f) {
  proto::SplineContourCmd q;
  if (f.start != proto::kCommandStart || f.letter != proto::kCmdSplineContour ||
      proto::decode_frame(f, &q) != proto::ErrorCode::kOk)
    return;
  core::Spline s;
  s.degree = 2;
  s.rational = true;
  s.control_count = (uint16_t)((q.control_index + q.control_n) | 1U);
  if (s.control_count > core::kMaxControlPoints) return;
  s.knot_count = (uint16_t)(s.control_count + 3U);
  // The previous corner at the edge of the range: the sums that could overflow are reached.
  const core::ControlPoint corner = {-core::kMaxCoordinateUm, core::kMaxCoordinateUm,
                                     core::kWeightOneQ14};
  if (q.control_index > 0) s.control[q.control_index - 1] = corner;
  const proto::ErrorCode e = proto::unpack_contour(q, &s);
  check(proto::is_known_error((uint8_t)e));
  if (e != proto::ErrorCode::kOk) return;
  for (uint16_t i = q.control_index; i < q.control_index + q.control_n; ++i) {
    check(s.control[i].x_um >= -core::kMaxCoordinateUm &&
          s.control[i].x_um <= core::kMaxCoordinateUm);
    check(s.control[i].y_um >= -core::kMaxCoordinateUm &&
          s.control[i].y_um <= core::kMaxCoordinateUm);
    check(s.control[i].weight_q14 >= 1 && s.control[i].weight_q14 <= core::kWeightOneQ14);
  }
}

// Decodes one frame with every codec, and checks the frame fields and codec agreement.
void on_frame(const proto::Frame& f, proto::SequenceWindow* window) {
  check(f.length <= proto::kMaxPayload);
  check(proto::is_frame_letter(f.letter));
  const test_proto::RoundTrip r =
      test_proto::round_trip_any(f.start, f.letter, f.payload, f.length);
  // A payload that decodes must re-encode to exactly the same bytes.
  if (r.decode == proto::ErrorCode::kOk) check(r.same_bytes);
  check(proto::is_known_error((uint8_t)r.decode));
  unpack_contour_frame(f);
  // Sequence bookkeeping: classification is total and accept() only moves on kNew.
  const uint8_t before = window->next_expected();
  const proto::SeqClass c = window->classify(f.seq);
  window->accept(f.seq);
  check(c == proto::SeqClass::kNew ? window->next_expected() == (uint8_t)(before + 1)
                                   : window->next_expected() == before);
}

void run(proto::Parser& parser, proto::SequenceWindow* window, proto::ParseEvent ev) {
  // Bounded: each poll() consumes at least one buffered byte or returns kNone.
  for (int guard = 0; ev != proto::ParseEvent::kNone; ++guard) {
    check(guard <= proto::kMaxFrameBytes + 1);
    if (ev == proto::ParseEvent::kFrame)
      on_frame(parser.frame(), window);
    else
      check((uint8_t)parser.last_error() < proto::kParserErrorCount);
    ev = parser.poll();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t control = data[0];
  proto::Parser parser((control & 1) ? proto::kReplyStart : proto::kCommandStart);
  proto::SequenceWindow window;
  window.reset(data[0]);
  for (size_t i = 1; i < size; ++i) {
    const uint8_t b = data[i];
    // Now and then, as steered by the control byte, a silence or a UART error.
    if ((control & 0x02) && b == 0xFE) {
      run(parser, &window, parser.expire());
      continue;
    }
    if ((control & 0x04) && b == 0xFD) parser.note_rx_error();
    run(parser, &window, parser.feed(b));
  }
  run(parser, &window, parser.expire());
  check(!parser.in_frame());
  return 0;
}
