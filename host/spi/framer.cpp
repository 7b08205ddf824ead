// SPI framing of a capture, with the diagnostics a bench test needs.
#include "host/spi/framer.h"

#include <algorithm>  // std::lower_bound, std::nth_element
#include <cctype>     // std::isdigit
#include <cmath>      // std::llround

#include "host/lib/plan/plain_decimal.h"  // is_plain_decimal
#include "host/spi/text_values.h"         // split_number_unit, unit_scale

namespace host::spi {
namespace {

const char* const kCsNames[] = {"CS",  "CS#", "nCS",  "/CS", "CSN", "NCS",    "SS",
                                "SS#", "nSS", "NSS",  "SSN", "CSB", "nSCS_C", "SCS",
                                "LE",  "EN",  "SYNC", "CS0", "CE",  nullptr};
const char* const kSckNames[] = {"SCK", "CLK", "SCLK", "SPC", "SCK_C", "SCK1", "CLOCK", nullptr};
const char* const kMosiNames[] = {"MOSI", "SDI_C", "SDO1", "COPI", "SIMO", "DIN", "DI", nullptr};
const char* const kMisoNames[] = {"MISO", "SDO_C", "SDI1", "CIPO", "SOMI", "DOUT", "DO", nullptr};

// The channel called one of `names`, or -1.
int find_any(const Trace& t, const char* const* names) {
  for (; *names; ++names) {
    int i = t.find(*names);
    if (i >= 0) return i;
  }
  return -1;
}

// Channel numbered n ("2", "Channel 2", "D2", "CH2") or -1.
int find_numbered(const Trace& t, int n) {
  std::string s = std::to_string(n);
  for (const std::string& name : {s, "Channel " + s, "D" + s, "CH" + s, "Ch" + s}) {
    int i = t.find(name);
    if (i >= 0) return i;
  }
  return -1;
}

// A user's choice: a name, or "#N" for the N-th channel (0-based). -2: not found.
int find_user(const Trace& t, const std::string& spec) {
  if (spec.size() > 1 && spec[0] == '#') {
    int n = std::atoi(spec.c_str() + 1);
    return n >= 0 && n < static_cast<int>(t.channels.size()) ? n : -2;
  }
  int i = t.find(spec);
  return i >= 0 ? i : -2;
}

std::string channel_list(const Trace& t) {
  std::string s;
  for (const auto& c : t.channels) s += (s.empty() ? "" : ", ") + c.name;
  return s;
}

// Widths between consecutive toggles that lie inside [a, b].
void pulses_within(const Channel& ch, int64_t a, int64_t b, std::vector<int64_t>* out) {
  auto it = std::lower_bound(ch.toggles_ps.begin(), ch.toggles_ps.end(), a);
  for (; it != ch.toggles_ps.end() && it + 1 != ch.toggles_ps.end() && *(it + 1) <= b; ++it)
    out->push_back(*(it + 1) - *it);
}

struct Period {
  int64_t a, b;
  bool cut_start, cut_end;
};

// Chip-select active (low) periods.
std::vector<Period> cs_periods(const Trace& t, int cs) {
  std::vector<Period> out;
  if (cs < 0) {
    out.push_back({t.start_ps, t.end_ps, false, false});
    return out;
  }
  const Channel& ch = t.channels[cs];
  bool active = !ch.initial_high;
  int64_t a = t.start_ps;
  bool cut = active;
  for (int64_t when : ch.toggles_ps) {
    if (active) out.push_back({a, when, cut, false});
    active = !active;
    a = when;
    cut = false;
  }
  if (active) out.push_back({a, t.end_ps, cut, true});
  return out;
}

}  // namespace

bool parse_duration_ps(const std::string& text, int64_t* ps) {
  static const UnitScale kPsPer[] = {{"s", 1e12}, {"ms", 1e9}, {"us", 1e6}, {"ns", 1e3}, {"ps", 1}};
  double v = 0;
  std::string unit;
  if (!split_number_unit(text, &v, &unit) || !(v >= 0) || v > 1e6) return false;
  // As the documentation writes numbers: no hex ("0x10ns"), no leading blank.
  std::string number = text.substr(0, text.size() - unit.size());
  number.erase(number.find_last_not_of(' ') + 1);
  if (!is_plain_decimal(number)) return false;
  const double mul = unit.empty() && v == 0 ? 1 : unit_scale(unit, kPsPer);
  if (mul == 0) return false;
  *ps = std::llround(v * mul);
  // A duration written non-zero that comes to 0 ps ("1e-400s", "0.1ps") would turn glitch
  // detection off: only a written 0 does.
  const size_t mantissa_end = number.find_first_of("eE");
  return *ps != 0 || number.find_first_of("123456789") >= mantissa_end;
}

Error resolve_channels(const Trace& t, const ChannelMap& names, FramerResult* out) {
  struct Role {
    const std::string* user;
    const char* const* defaults;
    int index_fallback;
    int* slot;
    const char* what;
    bool required;
  } roles[] = {{&names.cs, kCsNames, 0, &out->cs, "chip-select", true},
               {&names.sck, kSckNames, 2, &out->sck, "clock", true},
               {&names.mosi, kMosiNames, 1, &out->mosi, "MOSI", false},
               {&names.miso, kMisoNames, -1, &out->miso, "MISO", false}};
  for (auto& r : roles) {
    *r.slot = -1;
    if (*r.user == "none") {
      if (r.slot == &out->sck) return {"E_CHANNEL", "the clock channel cannot be 'none'"};
      continue;
    }
    if (!r.user->empty()) {
      int i = find_user(t, *r.user);
      if (i == -2)
        return {"E_CHANNEL", std::string("no ") + r.what + " channel '" + *r.user +
                                 "' (channels: " + channel_list(t) + ")"};
      *r.slot = i;
      continue;
    }
    *r.slot = find_any(t, r.defaults);
    if (*r.slot < 0 && r.index_fallback >= 0) *r.slot = find_numbered(t, r.index_fallback);
    if (*r.slot < 0 && r.required)
      return {"E_CHANNEL", std::string("cannot tell which channel is the ") + r.what +
                               " (channels: " + channel_list(t) + "); name it with --" +
                               (r.slot == &out->cs ? "cs" : "sck")};
  }
  if (out->mosi < 0 && out->miso < 0 && names.mosi != "none" && names.miso != "none")
    return {"E_CHANNEL", "no MOSI or MISO channel (channels: " + channel_list(t) +
                             "); name one with --mosi/--miso"};
  int ids[] = {out->cs, out->sck, out->mosi, out->miso};
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (ids[i] >= 0 && ids[i] == ids[j])
        return {"E_CHANNEL", "one channel ('" + t.channels[ids[i]].name + "') given two roles"};
  return {};
}

Error frame_capture(const Trace& t, const FramerOptions& o, FramerResult* out) {
  *out = FramerResult();
  if (o.mode < 0 || o.mode > 3) return {"E_OPTION", "SPI mode must be 0..3"};
  if (o.bits < 0 || o.bits > 64) return {"E_OPTION", "--bits must be 1..64 (or 0 = any)"};
  Error e = resolve_channels(t, o.names, out);
  if (!e.ok()) return e;
  if (out->cs < 0 && o.bits == 0)
    return {"E_OPTION", "without a chip-select channel --bits must give the word size"};
  const bool cpol = (o.mode >> 1) & 1;
  const bool cpha = o.mode & 1;
  const bool sample_rising = (cpol == cpha);
  const Channel& sck = t.channels[out->sck];
  const std::vector<Period> periods = cs_periods(t, out->cs);

  // Glitch threshold: given, or 40 % of the median clock pulse inside chip-select periods.
  out->min_pulse_ps = o.min_pulse_ps;
  if (o.min_pulse_ps < 0) {
    std::vector<int64_t> widths;
    for (const Period& p : periods) pulses_within(sck, p.a, p.b, &widths);
    out->min_pulse_ps = 0;
    if (!widths.empty()) {
      std::nth_element(widths.begin(), widths.begin() + widths.size() / 2, widths.end());
      out->min_pulse_ps = widths[widths.size() / 2] * 2 / 5;
    }
  }

  for (size_t k = 0; k < periods.size(); ++k) {
    const Period& p = periods[k];
    // Sampling edges in (a, b]: an edge in the same sample as chip-select rising still counts.
    std::vector<int64_t> edges;
    auto it = std::upper_bound(sck.toggles_ps.begin(), sck.toggles_ps.end(), p.a);
    for (; it != sck.toggles_ps.end() && *it <= p.b; ++it)
      if (sck.level_at(*it) == sample_rising) edges.push_back(*it);
    if (edges.empty()) {
      ++out->empty_periods;
      continue;
    }
    std::vector<int64_t> widths;
    pulses_within(sck, p.a, p.b, &widths);
    int64_t shortest = widths.empty() ? 0 : *std::min_element(widths.begin(), widths.end());
    bool cs_glitch = false;  // chip-select high for less than the threshold either side
    if (out->cs >= 0) {
      if (k > 0 && !p.cut_start && p.a - periods[k - 1].b < out->min_pulse_ps) cs_glitch = true;
      if (k + 1 < periods.size() && periods[k + 1].a - p.b < out->min_pulse_ps) cs_glitch = true;
    }
    // Without chip-select the stream is cut into words of `bits` bits.
    size_t word = out->cs < 0 ? static_cast<size_t>(o.bits) : edges.size();
    for (size_t first = 0; first < edges.size(); first += word) {
      size_t last = std::min(edges.size(), first + word);
      Frame f;
      f.start_ps = out->cs < 0 ? (first == 0 ? p.a : edges[first - 1]) : p.a;
      f.end_ps = out->cs < 0 ? edges[last - 1] : p.b;
      f.bit_count = static_cast<int>(last - first);
      f.has_mosi = out->mosi >= 0;
      f.has_miso = out->miso >= 0;
      for (size_t i = first; i < last; ++i) {
        if (f.has_mosi) f.mosi = (f.mosi << 1) | t.channels[out->mosi].level_before(edges[i]);
        if (f.has_miso) f.miso = (f.miso << 1) | t.channels[out->miso].level_before(edges[i]);
      }
      if (f.bit_count > 64) f.flags |= kFlagTooLong;
      if (o.bits > 0 && f.bit_count != o.bits) f.flags |= kFlagWrongBitCount;
      if (p.cut_start && first == 0) f.flags |= kFlagCutAtStart;
      if (p.cut_end && last == edges.size()) f.flags |= kFlagCutAtEnd;
      if (out->cs >= 0 && !p.cut_start && sck.level_before(p.a) != cpol)
        f.flags |= kFlagClockNotIdle;
      if ((shortest > 0 && shortest < out->min_pulse_ps) || cs_glitch) {
        f.flags |= kFlagGlitch;
        f.shortest_pulse_ps = cs_glitch ? 0 : shortest;
      }
      out->frames.push_back(f);
    }
  }
  return {};
}

}  // namespace host::spi
