// Golden-file parsing and writing.
#include "host/spi/golden.h"

#include <cstdlib>  // std::atoi
#include <sstream>  // std::istringstream

namespace host::spi {

bool parse_pattern(const std::string& t, Pattern* out) {
  *out = Pattern();
  if (t == "-" || t == "*") return true;
  if (t.size() < 3 || t[0] != '0' || (t[1] != 'x' && t[1] != 'X')) return false;
  std::string digits = t.substr(2);
  if (digits.size() > 16) return false;
  out->any = false;
  out->bits = static_cast<int>(digits.size()) * 4;
  for (char c : digits) {
    int d = -1;
    if (c >= '0' && c <= '9')
      d = c - '0';
    else if (c >= 'a' && c <= 'f')
      d = c - 'a' + 10;
    else if (c >= 'A' && c <= 'F')
      d = c - 'A' + 10;
    else if (c != 'x' && c != 'X' && c != '?')
      return false;
    out->value <<= 4;
    out->mask <<= 4;
    if (d >= 0) out->value |= static_cast<uint64_t>(d), out->mask |= 0xF;
  }
  return true;
}

std::string pattern_text(const Pattern& p) {
  if (p.any) return "-";
  std::string s = "0x";
  for (int shift = p.bits - 4; shift >= 0; shift -= 4) {
    if (((p.mask >> shift) & 0xF) == 0) {
      s += 'x';
    } else {
      s += "0123456789ABCDEF"[(p.value >> shift) & 0xF];
    }
  }
  return s;
}

bool pattern_matches(const Pattern& p, uint64_t word, int bits) {
  if (p.any) return true;
  return p.bits == bits && ((word ^ p.value) & p.mask) == 0;
}

Pattern exact_pattern(uint64_t word, int bits) {
  Pattern p;
  p.any = false;
  p.bits = bits;
  p.mask = bits >= 64 ? ~0ULL : (1ULL << bits) - 1;
  p.value = word & p.mask;
  return p;
}

// "{n}", "{min,max}", "{min,}" -> counts; false if malformed.
static bool parse_repeat(const std::string& t, int* lo, int* hi) {
  if (t.size() < 3 || t.front() != '{' || t.back() != '}') return false;
  std::string in = t.substr(1, t.size() - 2);
  size_t comma = in.find(',');
  auto num = [](const std::string& s, int* v) {
    if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos)
      return false;
    *v = std::atoi(s.c_str());
    return true;
  };
  if (comma == std::string::npos) {
    if (!num(in, lo)) return false;
    *hi = *lo;
  } else {
    if (!num(in.substr(0, comma), lo)) return false;
    std::string h = in.substr(comma + 1);
    if (h.empty())
      *hi = -1;
    else if (!num(h, hi))
      return false;
  }
  return *hi < 0 || *hi >= *lo;
}

Error parse_golden(const std::string& text, std::vector<Expected>* out) {
  out->clear();
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    Expected e;
    e.line = n;
    size_t hash = line.find('#');
    if (hash != std::string::npos) {
      e.comment = line.substr(hash + 1);
      size_t a = e.comment.find_first_not_of(' ');
      e.comment = a == std::string::npos ? "" : e.comment.substr(a);
      while (!e.comment.empty() && (e.comment.back() == '\r' || e.comment.back() == ' '))
        e.comment.pop_back();
      line = line.substr(0, hash);
    }
    std::istringstream words(line);
    std::vector<std::string> w;
    std::string t;
    while (words >> t) w.push_back(t);
    if (w.empty()) continue;
    std::string where = "golden line " + std::to_string(n) + ": ";
    if (!w.empty() && w.back().front() == '{') {
      if (!parse_repeat(w.back(), &e.min_count, &e.max_count))
        return {"E_GOLDEN", where + "bad repeat '" + w.back() + "' (use {n}, {min,max}, {min,})"};
      w.pop_back();
    }
    if (w.empty() || w.size() > 2)
      return {"E_GOLDEN", where + "expected 'MOSI [MISO] [{min,max}] [# comment]'"};
    if (!parse_pattern(w[0], &e.mosi) || e.mosi.any)
      return {"E_GOLDEN", where + "bad MOSI pattern '" + w[0] + "'"};
    if (w.size() == 2 && !parse_pattern(w[1], &e.miso))
      return {"E_GOLDEN", where + "bad MISO pattern '" + w[1] + "'"};
    if (!e.miso.any && e.miso.bits != e.mosi.bits)
      return {"E_GOLDEN", where + "MISO pattern width differs from MOSI"};
    out->push_back(e);
  }
  return {};
}

std::string format_golden(const std::vector<Expected>& lines, const std::string& header) {
  std::string s = header;
  for (const Expected& e : lines) {
    std::string row = pattern_text(e.mosi);
    std::string miso = pattern_text(e.miso);
    row += std::string(row.size() < 12 ? 12 - row.size() : 1, ' ') + miso;
    if (e.min_count != 1 || e.max_count != 1) {
      row += " {" + std::to_string(e.min_count);
      if (e.max_count != e.min_count)
        row += "," + (e.max_count < 0 ? std::string() : std::to_string(e.max_count));
      row += "}";
    }
    if (!e.comment.empty())
      row += std::string(row.size() < 32 ? 32 - row.size() : 1, ' ') + "# " + e.comment;
    s += row + "\n";
  }
  return s;
}

}  // namespace host::spi
