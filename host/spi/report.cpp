// Renders decodes and diffs for people (aligned text) and machines (JSON).
#include "host/spi/report.h"

#include <fmt/format.h>  // fmt::format

#include "host/spi/tmc428_names.h"  // decode_tmc428

namespace host::spi {
namespace {

bool is_tmc_word(const Frame& f) {
  return f.bit_count == 32 && f.has_mosi;
}

std::string flags_text(uint32_t flags) {
  std::string s;
  for (const auto& n : flag_names(flags)) s += (s.empty() ? "" : ",") + n;
  return s;
}

// For a ~ step: the fields whose captured value differs from the expected one, when the
// expected word is fully given ("  <> expected clk2_div=6").
std::string changed_fields(const Frame& f, const Expected& e) {
  if (!is_tmc_word(f) || e.mosi.bits != 32 || e.mosi.mask != 0xFFFFFFFFu || f.mosi == e.mosi.value)
    return "";
  Tmc428Datagram got = decode_tmc428(static_cast<uint32_t>(f.mosi), false, 0);
  Tmc428Datagram want = decode_tmc428(static_cast<uint32_t>(e.mosi.value), false, 0);
  std::vector<Field> differ;
  for (const Field& w : want.fields)
    for (const Field& g : got.fields)
      if (g.name == w.name && (g.value != w.value || g.text != w.text)) differ.push_back(w);
  if (differ.empty()) return "  <> expected " + hex_word(e.mosi.value, 32);
  return "  <> expected " + fields_text(differ);
}

}  // namespace

std::string hex_word(uint64_t v, int bits) {
  int digits = bits <= 0 ? 1 : (bits + 3) / 4;
  return fmt::format("0x{:0{}X}", v, digits);
}

std::string time_us(int64_t ps) {
  bool neg = ps < 0;
  uint64_t a = neg ? static_cast<uint64_t>(-ps) : static_cast<uint64_t>(ps);
  uint64_t ns = (a + 500) / 1000;
  return fmt::format("{}{}.{:03}", neg ? "-" : "", ns / 1000, ns % 1000);
}

std::string describe_tmc428(const Frame& f) {
  if (!is_tmc_word(f)) return "";
  Tmc428Datagram d =
      decode_tmc428(static_cast<uint32_t>(f.mosi), f.has_miso, static_cast<uint32_t>(f.miso));
  std::string s = std::string(d.read ? "R " : "W ") + d.reg;
  std::string fields = fields_text(d.fields);
  if (!fields.empty()) s += " " + fields;
  if (f.has_miso) {
    std::string st;
    for (const auto& b : tmc428_status_bits(static_cast<uint8_t>(f.miso >> 24)))
      st += (st.empty() ? "" : " ") + b;
    s += " [" + st + "]";
  }
  return s;
}

std::string decode_text(const DecodeInfo& info, const std::vector<Frame>& frames, bool raw) {
  std::string out =
      fmt::format("# {} ({}): {} datagrams, mode {}, {} bits, CS={} SCK={} MOSI={} MISO={}",
                  info.source, info.format, frames.size(), info.mode,
                  info.bits == 0 ? std::string("any") : std::to_string(info.bits),
                  info.channel_names.size() > 0 ? info.channel_names[0] : "-",
                  info.channel_names.size() > 1 ? info.channel_names[1] : "-",
                  info.channel_names.size() > 2 ? info.channel_names[2] : "-",
                  info.channel_names.size() > 3 ? info.channel_names[3] : "-");
  if (info.min_pulse_ps > 0) out += ", glitch < " + time_us(info.min_pulse_ps) + " us";
  out += "\n";
  out += fmt::format("# {:>4} {:>14} {:>4} {:<10} {:<10} {}\n", "n", "time_us", "bits", "mosi",
                     "miso", raw ? "flags" : "datagram [status] !flags");
  int errors = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const Frame& f = frames[i];
    std::string line = fmt::format("{:>6} {:>14} {:>4} {:<10} {:<10}", i, time_us(f.start_ps),
                                   f.bit_count, f.has_mosi ? hex_word(f.mosi, f.bit_count) : "-",
                                   f.has_miso ? hex_word(f.miso, f.bit_count) : "-");
    if (!raw) {
      std::string d = describe_tmc428(f);
      if (!d.empty()) line += " " + d;
    }
    if (f.flags) {
      line += " !" + flags_text(f.flags);
      if ((f.flags & kFlagGlitch) && f.shortest_pulse_ps > 0)
        line += "(" + time_us(f.shortest_pulse_ps) + "us)";
    }
    if (frame_is_error(f)) ++errors;
    out += line + "\n";
  }
  out += fmt::format("# {} datagrams, {} with errors, {} empty chip-select periods\n",
                     frames.size(), errors, info.empty_periods);
  return out;
}

nlohmann::json decode_json(const DecodeInfo& info, const std::vector<Frame>& frames, bool raw) {
  nlohmann::json j;
  j["source"] = info.source;
  j["format"] = info.format;
  j["mode"] = info.mode;
  j["bits"] = info.bits;
  const char* roles[] = {"cs", "sck", "mosi", "miso"};
  for (size_t k = 0; k < 4; ++k)
    j["channels"][roles[k]] = k < info.channel_names.size() ? info.channel_names[k] : "-";
  j["min_pulse_ns"] = info.min_pulse_ps / 1000.0;
  j["frames"] = nlohmann::json::array();
  int errors = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const Frame& f = frames[i];
    nlohmann::json fr;
    fr["index"] = i;
    fr["start_us"] = f.start_ps / 1e6;
    fr["end_us"] = f.end_ps / 1e6;
    fr["bits"] = f.bit_count;
    fr["mosi"] = f.has_mosi ? nlohmann::json(hex_word(f.mosi, f.bit_count)) : nlohmann::json();
    fr["miso"] = f.has_miso ? nlohmann::json(hex_word(f.miso, f.bit_count)) : nlohmann::json();
    fr["flags"] = flag_names(f.flags);
    fr["error"] = frame_is_error(f);
    if (frame_is_error(f)) ++errors;
    if (!raw && is_tmc_word(f)) {
      Tmc428Datagram d =
          decode_tmc428(static_cast<uint32_t>(f.mosi), f.has_miso, static_cast<uint32_t>(f.miso));
      fr["register"] = d.reg;
      fr["rw"] = d.read ? "R" : "W";
      nlohmann::json fields = nlohmann::json::object();
      for (const Field& x : d.fields) {
        if (!x.text.empty())
          fields[x.name] = x.text;
        else
          fields[x.name] = x.value;
      }
      fr["fields"] = fields;
      if (f.has_miso) {
        fr["status"]["byte"] = hex_word(f.miso >> 24, 8);
        fr["status"]["bits"] = tmc428_status_bits(static_cast<uint8_t>(f.miso >> 24));
      }
    }
    j["frames"].push_back(fr);
  }
  j["summary"] = {
      {"frames", frames.size()}, {"errors", errors}, {"empty_periods", info.empty_periods}};
  return j;
}

std::string diff_text(const std::vector<Frame>& frames, const std::vector<Expected>& expected,
                      const DiffResult& d, bool names) {
  std::string out = fmt::format("# {:<1} {:>14} {:<22} {:<22} {}\n", "m", "time_us",
                                "captured mosi/miso", "expected mosi/miso", "line: datagram");
  for (const DiffStep& s : d.steps) {
    const Frame* f = s.frame >= 0 ? &frames[s.frame] : nullptr;
    const Expected* e = s.expected >= 0 ? &expected[s.expected] : nullptr;
    std::string cap, exp;
    if (f) {
      cap = f->has_mosi ? hex_word(f->mosi, f->bit_count) : "-";
      if (f->has_miso) cap += " " + hex_word(f->miso, f->bit_count);
    }
    if (e) {
      exp = pattern_text(e->mosi);
      if (!e->miso.any) exp += " " + pattern_text(e->miso);
    }
    std::string what;
    if (e) what += fmt::format("{}: ", e->line);
    if (names && f && is_tmc_word(*f)) {
      what += describe_tmc428(*f);
    } else if (names && e && e->mosi.bits == 32) {
      // Missing line: name the register from the pattern's address byte when given.
      if (((e->mosi.mask >> 24) & 0xFF) == 0xFF) {
        Frame g;
        g.bit_count = 32;
        g.mosi = e->mosi.value;
        what += describe_tmc428(g);
      }
    } else if (e && !e->comment.empty()) {
      what += e->comment;
    }
    if (names && s.mark == Mark::kChanged && f && e) what += changed_fields(*f, *e);
    if (f && f->flags) what += " !" + flags_text(f->flags);
    out += fmt::format("{} {:>14} {:<22} {:<22} {}\n", static_cast<char>(s.mark),
                       f ? time_us(f->start_ps) : "", cap, exp, what);
  }
  for (const auto& n : d.notes) out += "# note: " + n + "\n";
  if (!d.miso_checked) out += "# note: the capture has no MISO; MISO patterns were not checked\n";
  return out;
}

std::string diff_verdict(const DiffResult& d, size_t frames, size_t expected) {
  if (d.same())
    return fmt::format("MATCH: {} captured datagrams fit all {} expected lines", frames, expected);
  return fmt::format(
      "DIFFER: {} equal, {} changed (~), {} missing (-), {} extra (+); {} captured, {} expected"
      "{}",
      d.equal, d.changed, d.missing, d.extra, frames, expected,
      d.notes.empty() ? "" : fmt::format(", {} notes", d.notes.size()));
}

nlohmann::json diff_json(const std::vector<Frame>& frames, const std::vector<Expected>& expected,
                         const DiffResult& d) {
  nlohmann::json j;
  j["steps"] = nlohmann::json::array();
  for (const DiffStep& s : d.steps) {
    nlohmann::json x;
    x["mark"] = std::string(1, static_cast<char>(s.mark));
    if (s.frame >= 0) {
      const Frame& f = frames[s.frame];
      x["frame"] = s.frame;
      x["start_us"] = f.start_ps / 1e6;
      x["mosi"] = f.has_mosi ? nlohmann::json(hex_word(f.mosi, f.bit_count)) : nlohmann::json();
      x["miso"] = f.has_miso ? nlohmann::json(hex_word(f.miso, f.bit_count)) : nlohmann::json();
      x["flags"] = flag_names(f.flags);
    }
    if (s.expected >= 0) {
      x["line"] = expected[s.expected].line;
      x["expected_mosi"] = pattern_text(expected[s.expected].mosi);
      x["expected_miso"] = pattern_text(expected[s.expected].miso);
    }
    j["steps"].push_back(x);
  }
  j["counts"] = {
      {"equal", d.equal}, {"changed", d.changed}, {"missing", d.missing}, {"extra", d.extra}};
  j["notes"] = d.notes;
  j["match"] = d.same();
  j["verdict"] = diff_verdict(d, frames.size(), expected.size());
  return j;
}

}  // namespace host::spi
