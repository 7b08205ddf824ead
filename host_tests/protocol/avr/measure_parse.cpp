// AVR (ATmega2560 in simavr) measurement: cycles to parse and decode one full #D frame
// (64-byte payload), one byte at a time, and the CRC share; then a full #K frame and a full
// #Q frame: parse, decode (with its structure check) and unpacking into a spline. Prints
// over UART0.
// Build and run: see docs/performance.md "Path controller and protocol".
#include <avr/interrupt.h>  // cli
#include <avr/io.h>         // TCCR1B, TCNT1, UCSR0A, UDR0
#include <avr/sleep.h>      // sleep_cpu
#include <stdio.h>          // printf

#include "firmware/protocol/codec.h"           // write_frame, decode_frame
#include "firmware/protocol/compact_spline.h"  // put_compact_point, unpack_compact
#include "firmware/protocol/contour_spline.h"  // put_contour_element, unpack_contour
#include "firmware/protocol/crc16.h"           // crc16
#include "firmware/protocol/parser.h"          // Parser

static int uart_putchar(char c, FILE*) {
  while (!(UCSR0A & _BV(UDRE0))) {
  }
  UDR0 = (uint8_t)c;
  return 0;
}

static FILE g_uart;
static uint8_t g_frame[proto::kMaxFrameBytes];
static uint8_t g_size;

// A #D with 4 control points and 5 knots: 4 + 40 + 20 = 64 payload bytes, 70 frame bytes.
static void build_frame() {
  proto::SplineDataCmd d;
  d.control_index = 0;
  d.control_n = 4;
  d.knot_index = 0;
  d.knot_n = 5;
  for (uint8_t i = 0; i < 4; ++i) {
    d.control[i].x_um = 123456L * (i + 1);
    d.control[i].y_um = -98765L * (i + 1);
    d.control[i].weight_q14 = 16384U;
  }
  for (uint8_t i = 0; i < 5; ++i) d.knot[i] = 1000L * i;
  proto::write_frame(d, 7, g_frame, sizeof g_frame, &g_size);
}

// A #K as full as a PCB contour makes it: rational points 0.1-2 mm apart with weight changes,
// then knots (spans 1 and repeats), up to 64 payload bytes.
static uint8_t g_k_frame[proto::kMaxFrameBytes];
static uint8_t g_k_size;
static core::Spline g_spline;

static void build_compact_frame() {
  static const int16_t kStep[4][2] = {{1500, 0}, {120, 180}, {0, 900}, {-40, 300}};
  proto::SplineCompactCmd k;
  k.control_index = 0;
  k.control_n = 0;
  k.knot_index = 0;
  k.knot_n = 0;
  k.data_n = 0;
  core::ControlPoint prev = {0, 0, core::kWeightOneQ14};
  core::ControlPoint p = {123456L, -98765L, 16000U};
  uint8_t value[proto::kMaxCompactPointBytes];
  for (uint8_t i = 0; i < 9; ++i) {
    const uint8_t n = proto::put_compact_point(prev, p, true, value);
    for (uint8_t b = 0; b < n; ++b) k.data[k.data_n++] = value[b];
    ++k.control_n;
    prev = p;
    p.x_um += kStep[i % 4][0];
    p.y_um += kStep[i % 4][1];
    p.weight_q14 = (uint16_t)(i % 2 ? 16000U : 11314U);
  }
  while (k.data_n < 60 - 1) {  // knots 0, then spans of 1 with repeats (double knots)
    const bool first = k.knot_n == 0;
    const uint8_t n =
        proto::put_compact_knot(k.knot_n, k.knot_n + 1, first, !first, k.data + k.data_n);
    k.data_n = (uint8_t)(k.data_n + n);
    k.knot_n = (uint8_t)(k.knot_n + (first ? 1 : 2));
  }
  g_spline.rational = true;
  proto::write_frame(k, 8, g_k_frame, sizeof g_k_frame, &g_k_size);
}

// A #Q as full as a PCB contour makes it: pad outlines, quarter arcs of 0.1-0.3 mm radius
// and lines of 0.2-1.5 mm by turns, up to 64 payload bytes.
static uint8_t g_q_frame[proto::kMaxFrameBytes];
static uint8_t g_q_size;
static core::Spline g_q_spline;

static void build_contour_frame() {
  static const int16_t kArc[4][3] = {
      {212, 212, -88}, {-283, 283, -117}, {-141, -141, -59}, {300, -300, -124}};
  static const int16_t kLine[4][2] = {{1500, 0}, {0, 900}, {-400, 0}, {0, -1200}};
  proto::SplineContourCmd q;
  q.control_index = 0;
  q.control_n = 1;
  q.data_n = proto::put_contour_start(123456L, -98765L, q.data);
  uint8_t value[proto::kMaxContourElementBytes];
  for (uint8_t i = 0;; ++i) {
    proto::ContourElement e;
    e.arc = (i % 2) != 0;
    e.dx_um = e.arc ? kArc[(i / 2) % 4][0] : kLine[(i / 2) % 4][0];
    e.dy_um = e.arc ? kArc[(i / 2) % 4][1] : kLine[(i / 2) % 4][1];
    e.height_um = e.arc ? kArc[(i / 2) % 4][2] : 0;
    const uint8_t n = proto::put_contour_element(e, value);
    if (q.data_n + n > proto::kMaxContourData) break;
    for (uint8_t b = 0; b < n; ++b) q.data[q.data_n++] = value[b];
    q.control_n = (uint8_t)(q.control_n + 2U);
  }
  g_q_spline.degree = 2;
  g_q_spline.rational = true;
  g_q_spline.control_count = q.control_n;
  g_q_spline.knot_count = (uint16_t)(q.control_n + 3U);
  proto::write_frame(q, 9, g_q_frame, sizeof g_q_frame, &g_q_size);
}

// Cycles to parse a spline data frame byte by byte, decode it into *cmd and unpack it into s.
struct FrameCycles {
  uint16_t parse, decode, unpack;
  proto::ErrorCode decoded, unpacked;
};

template <typename Cmd>
static FrameCycles time_spline_frame(const uint8_t* frame, uint8_t size, Cmd* cmd,
                                     proto::ErrorCode (*unpack)(const Cmd&, core::Spline*),
                                     core::Spline* s) {
  static proto::Parser parser(proto::kCommandStart);
  parser.reset();
  FrameCycles c;
  uint16_t t0 = TCNT1;
  for (uint8_t i = 0; i < size; ++i) parser.feed(frame[i]);
  c.parse = (uint16_t)(TCNT1 - t0);
  t0 = TCNT1;
  c.decoded = proto::decode_frame(parser.frame(), cmd);
  c.decode = (uint16_t)(TCNT1 - t0);
  t0 = TCNT1;
  c.unpacked = unpack(*cmd, s);
  c.unpack = (uint16_t)(TCNT1 - t0);
  return c;
}

int main() {
  UCSR0A = _BV(U2X0);
  UBRR0 = 1;
  UCSR0B = _BV(TXEN0);
  UCSR0C = _BV(UCSZ01) | _BV(UCSZ00);
  fdev_setup_stream(&g_uart, uart_putchar, 0, _FDEV_SETUP_WRITE);
  stdout = &g_uart;
  TCCR1A = 0;
  TCCR1B = _BV(CS10);  // clk/1: TCNT1 counts CPU cycles (all runs below fit 16 bits)
  build_frame();

  static proto::Parser parser(proto::kCommandStart);
  proto::SplineDataCmd decoded;
  uint16_t ok = 0;

  uint16_t t0 = TCNT1;
  for (uint8_t i = 0; i < g_size; ++i) {
    if (parser.feed(g_frame[i]) == proto::ParseEvent::kFrame) ++ok;
  }
  uint16_t parse_cycles = (uint16_t)(TCNT1 - t0);

  t0 = TCNT1;
  const proto::ErrorCode e = proto::decode_frame(parser.frame(), &decoded);
  uint16_t decode_cycles = (uint16_t)(TCNT1 - t0);

  t0 = TCNT1;
  volatile uint16_t crc = proto::crc16(g_frame, (size_t)(g_size - 2));
  uint16_t crc_cycles = (uint16_t)(TCNT1 - t0);
  (void)crc;

  t0 = TCNT1;
  uint16_t empty = (uint16_t)(TCNT1 - t0);

  printf("frame_bytes=%u frames=%u decode=%u\n", g_size, ok, (unsigned)e);
  printf("parse_cycles=%u decode_cycles=%u crc_cycles=%u timer_overhead=%u\n", parse_cycles,
         decode_cycles, crc_cycles, empty);
  printf("parser_ram_bytes=%u\n", (unsigned)sizeof(proto::Parser));

  build_compact_frame();
  proto::SplineCompactCmd compact;
  const FrameCycles k =
      time_spline_frame(g_k_frame, g_k_size, &compact, proto::unpack_compact, &g_spline);
  printf("k_frame_bytes=%u k_points=%u k_knots=%u decode=%u unpack=%u\n", g_k_size,
         compact.control_n, compact.knot_n, (unsigned)k.decoded, (unsigned)k.unpacked);
  printf("k_parse_cycles=%u k_decode_cycles=%u k_unpack_cycles=%u\n", k.parse, k.decode, k.unpack);

  build_contour_frame();
  proto::SplineContourCmd contour;
  const FrameCycles q =
      time_spline_frame(g_q_frame, g_q_size, &contour, proto::unpack_contour, &g_q_spline);
  printf("q_frame_bytes=%u q_points=%u decode=%u unpack=%u\n", g_q_size, contour.control_n,
         (unsigned)q.decoded, (unsigned)q.unpacked);
  printf("q_parse_cycles=%u q_decode_cycles=%u q_unpack_cycles=%u\n", q.parse, q.decode, q.unpack);
  while (!(UCSR0A & _BV(TXC0))) {
  }
  cli();
  sleep_enable();
  sleep_cpu();
  return 0;
}
