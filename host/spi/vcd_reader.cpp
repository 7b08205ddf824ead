// Value Change Dump reader: 1-bit wires only, times scaled to picoseconds.
#include <cstdlib>        // std::strtoll
#include <limits>         // std::numeric_limits
#include <sstream>        // std::istringstream
#include <unordered_map>  // std::unordered_map

#include "host/spi/capture.h"

namespace host::spi {
namespace {

// Picoseconds per unit ("s", "ms", "us", "ns", "ps"); 0 for femtoseconds (handled apart).
int64_t unit_ps(const std::string& unit, bool* ok) {
  *ok = true;
  if (unit == "s") return 1000000000000LL;
  if (unit == "ms") return 1000000000LL;
  if (unit == "us") return 1000000LL;
  if (unit == "ns") return 1000LL;
  if (unit == "ps") return 1LL;
  *ok = false;
  return 0;
}

// Parses "10ns" or "10" "ns" into picoseconds per VCD tick.
Error parse_timescale(const std::vector<std::string>& words, int64_t* ps) {
  std::string all;
  for (const auto& w : words) all += w;
  size_t i = 0;
  while (i < all.size() && isdigit(static_cast<unsigned char>(all[i]))) ++i;
  if (i == 0) return {"E_FORMAT", "VCD: bad $timescale '" + all + "'"};
  int64_t n = std::strtoll(all.substr(0, i).c_str(), nullptr, 10);
  bool ok = false;
  int64_t u = unit_ps(all.substr(i), &ok);
  if (!ok || n <= 0 || n > 1000)
    return {"E_FORMAT", "VCD: unsupported $timescale '" + all + "' (use 1ps..100s)"};
  *ps = n * u;
  return {};
}

// Where a VCD reader stands.
struct VcdState {
  int64_t scale_ps = 1000;                   // VCD default is 1 ns when $timescale is missing
  std::unordered_map<std::string, int> ids;  // identifier code -> channel (-1: not 1-bit)
  bool in_defs = true;
  bool have_time = false;
  int64_t now_ps = 0;
  size_t changes = 0;
};

// One token of the header ($timescale, $var, what to skip, $enddefinitions).
Error read_header_token(std::istream& in, std::string tok, VcdState* st, Trace* out) {
  if (tok == "$enddefinitions") {
    in >> tok;  // $end
    st->in_defs = false;
    return {};
  }
  if (tok == "$timescale") {
    std::vector<std::string> words;
    while (in >> tok && tok != "$end") words.push_back(tok);
    return parse_timescale(words, &st->scale_ps);
  }
  if (tok == "$var") {
    std::vector<std::string> words;
    while (in >> tok && tok != "$end") words.push_back(tok);
    if (words.size() < 4) return {"E_FORMAT", "VCD: short $var declaration"};
    const std::string& id = words[2];
    if (words[1] == "1" && !st->ids.count(id)) {
      Channel ch;
      ch.name = words[3];
      out->channels.push_back(ch);
      st->ids[id] = static_cast<int>(out->channels.size()) - 1;
    } else if (!st->ids.count(id)) {
      st->ids[id] = -1;
    }
    return {};
  }
  if (tok[0] == '$' && tok != "$end") {
    // $date, $version, $comment, $scope, $upscope...: skip to $end.
    while (in >> tok && tok != "$end") {
    }
    return {};
  }
  if (tok[0] == '#' || tok[0] == '0' || tok[0] == '1')
    return {"E_FORMAT", "VCD: value changes before $enddefinitions"};
  return {"E_FORMAT", "VCD: unexpected '" + tok.substr(0, 20) + "' in the header"};
}

// A timestamp "#N"; *stop when it is the file's last token, cut off while being written.
Error read_timestamp(const std::string& tok, bool last_token, VcdState* st, Trace* out,
                     bool* stop) {
  char* endp = nullptr;
  long long t = std::strtoll(tok.c_str() + 1, &endp, 10);
  if (tok.size() < 2 || *endp != '\0' || t < 0) {
    if (last_token) {
      *stop = true;
      return {};
    }
    return {"E_FORMAT", "VCD: bad timestamp '" + tok.substr(0, 20) + "'"};
  }
  if (t > std::numeric_limits<int64_t>::max() / st->scale_ps)
    return {"E_FORMAT", "VCD: timestamp out of range"};
  int64_t t_ps = static_cast<int64_t>(t) * st->scale_ps;
  if (st->have_time && t_ps < st->now_ps) return {"E_FORMAT", "VCD: time goes backwards at " + tok};
  if (!st->have_time) out->start_ps = t_ps;
  st->have_time = true;
  st->now_ps = t_ps;
  return {};
}

}  // namespace

Error parse_vcd(const std::string& text, Trace* out) {
  *out = Trace();
  out->format = "vcd";
  std::istringstream in(text);
  std::string tok;
  VcdState st;
  while (in >> tok) {
    if (st.in_defs) {
      const Error e = read_header_token(in, tok, &st, out);
      if (!e.ok()) return e;
      continue;
    }
    // A file cut off while being written ends in a partial token: stop there.
    std::streampos after = in.tellg();
    std::string probe;
    bool last_token = !(in >> probe);
    in.clear();
    in.seekg(after);
    char c = tok[0];
    if (tok == "$comment") {
      while (in >> tok && tok != "$end") {
      }
      continue;
    }
    if (c == '$') continue;  // $dumpvars, $end, $dumpall...
    if (c == '#') {
      bool stop = false;
      const Error e = read_timestamp(tok, last_token, &st, out, &stop);
      if (!e.ok()) return e;
      if (stop) break;
      continue;
    }
    std::string id;
    char value = 0;
    if (c == '0' || c == '1' || c == 'x' || c == 'X' || c == 'z' || c == 'Z') {
      value = c;
      id = tok.substr(1);
    } else if (c == 'b' || c == 'B' || c == 'r' || c == 'R') {
      value = tok.size() > 1 ? tok.back() : '0';  // 1-bit vector "b1 !": its only bit
      if (!(in >> id)) break;                     // cut off after the value
    } else {
      if (last_token) break;
      return {"E_FORMAT", "VCD: unexpected '" + tok.substr(0, 20) + "'"};
    }
    auto it = st.ids.find(id);
    if (it == st.ids.end() && last_token) break;
    if (it == st.ids.end())
      return {"E_FORMAT", "VCD: change for undeclared identifier '" + id + "'"};
    if (it->second < 0) continue;
    bool high = (value == '1');
    Channel& ch = out->channels[it->second];
    if (!st.have_time || st.now_ps == out->start_ps) {
      ch.initial_high = high;  // $dumpvars/first timestamp: the starting level
      ch.toggles_ps.clear();
    } else {
      ch.set_level(st.now_ps, high);
    }
    ++st.changes;
  }
  if (st.in_defs) return {"E_FORMAT", "VCD: no $enddefinitions (not a VCD or truncated header)"};
  if (out->channels.empty()) return {"E_FORMAT", "VCD: no 1-bit wires declared"};
  if (!st.have_time && st.changes == 0) return {"E_FORMAT", "VCD: no value changes"};
  out->end_ps = st.now_ps;
  return {};
}

}  // namespace host::spi
