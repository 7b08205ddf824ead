// Saleae CSV readers: Logic digital export (transitions) and the SPI analyser export
// (Logic 1.x "Time [s],Packet ID,MOSI,MISO"; Logic 2 "name,type,start_time,duration,mosi,miso").
#include <algorithm>  // std::max
#include <cctype>     // std::tolower
#include <cmath>      // std::llround
#include <cstdlib>    // std::strtold
#include <sstream>    // std::istringstream

#include "host/spi/capture.h"
#include "host/spi/text_values.h"  // trim

namespace host::spi {
namespace {

// A field without spaces and the quotes around it.
std::string trim_field(const std::string& s) {
  return trim(s, " \t\r\n\"");
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Splits one CSV line; quoted fields may contain commas.
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted)
      out.emplace_back();
    else
      out.back() += c;
  }
  for (auto& f : out) f = trim_field(f);
  return out;
}

// Seconds as text -> picoseconds. False if not a number or absurdly large.
bool parse_seconds(const std::string& s, int64_t* ps) {
  if (s.empty()) return false;
  char* end = nullptr;
  long double v = std::strtold(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0' || !(v > -1e6L && v < 1e6L)) return false;
  *ps = std::llround(static_cast<double>(v * 1e12L));
  return true;
}

// "0x1A", "1Ah", "26", "0b1010" -> value and its width in bits (hex digits x 4, else bytes).
bool parse_word(const std::string& s, uint64_t* value, int* bits) {
  if (s.empty()) return false;
  std::string t = lower(s);
  int base = 10;
  size_t digits_at = 0;
  if (t.rfind("0x", 0) == 0)
    base = 16, digits_at = 2;
  else if (t.rfind("0b", 0) == 0)
    base = 2, digits_at = 2;
  std::string digits = t.substr(digits_at);
  if (digits.empty() || digits.size() > 64) return false;
  uint64_t v = 0;
  for (char c : digits) {
    int d = (c >= '0' && c <= '9') ? c - '0' : (c >= 'a' && c <= 'f') ? c - 'a' + 10 : 99;
    if (d >= base) return false;
    v = v * base + d;
  }
  int w = 8;
  if (base == 16)
    w = static_cast<int>(digits.size()) * 4;
  else if (base == 2)
    w = static_cast<int>(digits.size());
  while (w < 64 && (v >> w) != 0) w += 8;
  if (w < 8) w = 8;
  *value = v;
  *bits = w > 64 ? 64 : w;
  return true;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!trim_field(line).empty()) lines.push_back(line);
  }
  return lines;
}

// Appends a word to a frame, MSB first.
void append(Frame* f, uint64_t mosi, bool has_mosi, uint64_t miso, bool has_miso, int bits) {
  if (f->bit_count + bits > 64) f->flags |= kFlagTooLong;
  f->mosi = (bits >= 64 ? 0 : f->mosi << bits) | mosi;
  f->miso = (bits >= 64 ? 0 : f->miso << bits) | miso;
  f->has_mosi = has_mosi;
  f->has_miso = has_miso;
  f->bit_count += bits;
}

}  // namespace

Error parse_saleae_digital_csv(const std::string& text, Trace* out) {
  *out = Trace();
  out->format = "saleae-csv";
  auto lines = lines_of(text);
  if (lines.empty()) return {"E_FORMAT", "CSV: empty file"};
  auto head = split_csv(lines[0]);
  if (head.size() < 2 || lower(head[0]).rfind("time", 0) != 0)
    return {"E_FORMAT", "CSV: first column must be 'Time [s]'"};
  for (size_t i = 1; i < head.size(); ++i) {
    Channel ch;
    ch.name = head[i];
    out->channels.push_back(ch);
  }
  int64_t prev_t = 0;
  for (size_t r = 1; r < lines.size(); ++r) {
    auto f = split_csv(lines[r]);
    int64_t t = 0;
    if (f.size() != head.size() || !parse_seconds(f[0], &t))
      return {"E_FORMAT", "CSV: bad row " + std::to_string(r + 1)};
    if (r > 1 && t < prev_t)
      return {"E_FORMAT", "CSV: time goes backwards at row " + std::to_string(r + 1)};
    for (size_t i = 1; i < f.size(); ++i) {
      if (f[i] != "0" && f[i] != "1")
        return {"E_FORMAT", "CSV: row " + std::to_string(r + 1) + ": level must be 0 or 1"};
      bool high = f[i] == "1";
      if (r == 1)
        out->channels[i - 1].initial_high = high;
      else
        out->channels[i - 1].set_level(t, high);
    }
    if (r == 1) out->start_ps = t;
    prev_t = t;
  }
  if (lines.size() < 2) return {"E_FORMAT", "CSV: no rows"};
  out->end_ps = prev_t;
  return {};
}

Error parse_saleae_spi_csv(const std::string& text, std::vector<Frame>* out) {
  out->clear();
  auto lines = lines_of(text);
  if (lines.empty()) return {"E_FORMAT", "SPI CSV: empty file"};
  auto head = split_csv(lines[0]);
  int c_time = -1, c_packet = -1, c_mosi = -1, c_miso = -1, c_type = -1;
  for (size_t i = 0; i < head.size(); ++i) {
    std::string h = lower(head[i]);
    if (h.rfind("time", 0) == 0 || h == "start_time")
      c_time = static_cast<int>(i);
    else if (h == "packet id")
      c_packet = static_cast<int>(i);
    else if (h == "mosi")
      c_mosi = static_cast<int>(i);
    else if (h == "miso")
      c_miso = static_cast<int>(i);
    else if (h == "type")
      c_type = static_cast<int>(i);
  }
  if (c_time < 0 || (c_mosi < 0 && c_miso < 0))
    return {"E_FORMAT", "SPI CSV: need a time column and a MOSI and/or MISO column"};
  bool open = false;  // Logic 2: inside an enable..disable pair
  std::string packet;
  for (size_t r = 1; r < lines.size(); ++r) {
    auto f = split_csv(lines[r]);
    std::string where = "SPI CSV row " + std::to_string(r + 1);
    if (static_cast<int>(f.size()) <= std::max({c_time, c_mosi, c_miso, c_type, c_packet}))
      return {"E_FORMAT", where + ": too few columns"};
    int64_t t = 0;
    if (!parse_seconds(f[c_time], &t)) return {"E_FORMAT", where + ": bad time"};
    std::string type = c_type >= 0 ? lower(f[c_type]) : "result";
    if (type == "enable") {
      out->push_back(Frame());
      out->back().start_ps = out->back().end_ps = t;
      open = true;
      continue;
    }
    if (type == "disable") {
      if (open) out->back().end_ps = t;
      open = false;
      continue;
    }
    if (type != "result") continue;  // "error" rows and others carry no data
    uint64_t mo = 0, mi = 0;
    int wb = 0, wb2 = 0;
    bool has_mo = c_mosi >= 0 && !f[c_mosi].empty();
    bool has_mi = c_miso >= 0 && !f[c_miso].empty();
    if (has_mo && !parse_word(f[c_mosi], &mo, &wb)) return {"E_FORMAT", where + ": bad MOSI"};
    if (has_mi && !parse_word(f[c_miso], &mi, &wb2)) return {"E_FORMAT", where + ": bad MISO"};
    int bits = std::max(wb, wb2);
    if (bits == 0) continue;
    // A new frame: Logic 2 outside enable/disable, Logic 1 when Packet ID changes or is empty.
    bool new_frame = out->empty();
    if (c_type >= 0)
      new_frame = new_frame || !open;
    else if (c_packet >= 0)
      new_frame = new_frame || f[c_packet].empty() || f[c_packet] != packet;
    else
      new_frame = true;
    if (c_packet >= 0) packet = f[c_packet];
    if (new_frame) {
      out->push_back(Frame());
      out->back().start_ps = t;
    }
    Frame& fr = out->back();
    append(&fr, mo, has_mo, mi, has_mi, bits);
    fr.end_ps = t;
  }
  // Logic 2 "enable" rows with no result: nothing was clocked, drop them.
  std::vector<Frame> kept;
  for (const auto& fr : *out)
    if (fr.bit_count > 0) kept.push_back(fr);
  *out = kept;
  if (out->empty()) return {"E_NO_FRAMES", "SPI CSV: no data rows"};
  return {};
}

}  // namespace host::spi
