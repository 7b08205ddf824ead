// Global alignment of captured and expected datagrams.
#include "host/spi/diff.h"

#include <cstdint>  // int32_t

namespace host::spi {
namespace {

const int kMatch = 2;
const int kSubstitute = 0;
const int kGap = -1;
const int32_t kNone = -1000000000;

// Traceback codes.
enum : uint8_t { kDiag = 1, kUp = 2 /* frame extra */, kLeft = 3 /* missing */, kRepeat = 4 };

// Top byte of a word (the TMC428 address byte for 32-bit datagrams).
uint64_t top_byte(uint64_t word, int bits) {
  return bits >= 8 ? (word >> (bits - 8)) & 0xFF : word;
}

// A substitution is shown only between words to the same address (fully given top byte).
bool same_address(const Frame& f, const Expected& e) {
  const Pattern& p = e.mosi;
  if (!f.has_mosi || p.bits < 16 || f.bit_count < 8) return false;
  if (top_byte(p.mask, p.bits) != 0xFF) return false;
  return top_byte(f.mosi, f.bit_count) == top_byte(p.value, p.bits);
}

}  // namespace

bool frame_matches(const Frame& f, const Expected& e) {
  if (frame_is_error(f)) return false;
  if (!f.has_mosi || !pattern_matches(e.mosi, f.mosi, f.bit_count)) return false;
  if (!e.miso.any && f.has_miso && !pattern_matches(e.miso, f.miso, f.bit_count)) return false;
  return true;
}

std::vector<Frame> swap_mosi_miso(const std::vector<Frame>& frames) {
  std::vector<Frame> out = frames;
  for (Frame& f : out) {
    std::swap(f.mosi, f.miso);
    std::swap(f.has_mosi, f.has_miso);
  }
  return out;
}

namespace {

// The alignment's score table, filled row by row (captured datagrams) and column by column
// (expected lines): where each cell came from, and each row's score at the last column.
struct Alignment {
  size_t m = 0;  // expected lines
  std::vector<uint8_t> back;
  std::vector<int32_t> last_column;
  size_t at(size_t i, size_t j) const { return i * (m + 1) + j; }
};

Alignment align(const std::vector<Frame>& frames, const std::vector<Expected>& expected,
                bool within) {
  const size_t n = frames.size(), m = expected.size();
  Alignment al;
  al.m = m;
  std::vector<uint8_t>& back = al.back;
  back.assign((n + 1) * (m + 1), 0);
  std::vector<int32_t> prev(m + 1), cur(m + 1);
  std::vector<int32_t>& last_column = al.last_column;
  last_column.assign(n + 1, 0);
  auto at = [&al](size_t i, size_t j) { return al.at(i, j); };
  // Row 0: only expected lines skipped.
  prev[0] = 0;
  for (size_t j = 1; j <= m; ++j) {
    prev[j] = prev[j - 1] + (expected[j - 1].min_count == 0 ? 0 : kGap);
    back[at(0, j)] = kLeft;
  }
  last_column[0] = prev[m];
  for (size_t i = 1; i <= n; ++i) {
    const Frame& f = frames[i - 1];
    cur[0] = within ? 0 : prev[0] + kGap;
    back[at(i, 0)] = kUp;
    for (size_t j = 1; j <= m; ++j) {
      const Expected& e = expected[j - 1];
      bool match = frame_matches(f, e);
      int32_t best = prev[j] + kGap;
      uint8_t how = kUp;
      if (match && e.max_count != 1 && prev[j] + kMatch > best) {
        best = prev[j] + kMatch;
        how = kRepeat;
      }
      int32_t diag = match                ? prev[j - 1] + kMatch
                     : same_address(f, e) ? prev[j - 1] + kSubstitute
                                          : kNone;
      if (diag > best) best = diag, how = kDiag;
      int32_t left = cur[j - 1] + (e.min_count == 0 ? 0 : kGap);
      if (left > best) best = left, how = kLeft;
      cur[j] = best;
      back[at(i, j)] = how;
    }
    last_column[i] = cur[m];
    std::swap(prev, cur);
  }
  return al;
}

// The steps from the table's end back to its start (with --within, from where the whole
// expected sequence scores best, and to where it begins).
void trace_back(const Alignment& al, const std::vector<Frame>& frames,
                const std::vector<Expected>& expected, bool within, DiffResult* out) {
  const size_t n = frames.size(), m = expected.size();
  const std::vector<int32_t>& last_column = al.last_column;
  auto at = [&al](size_t i, size_t j) { return al.at(i, j); };
  const std::vector<uint8_t>& back = al.back;
  std::vector<DiffStep> rev;
  size_t i = n, j = m;
  if (within) {
    // End where the whole expected sequence scores best; later datagrams are outside.
    size_t best = n;
    for (size_t k = 0; k <= n; ++k)
      if (last_column[k] > last_column[best] || (last_column[k] == last_column[best] && k < best))
        best = k;
    out->ignored_after = static_cast<int>(n - best);
    i = best;
  }
  while (i > 0 || j > 0) {
    if (within && j == 0) {
      out->ignored_before = static_cast<int>(i);
      break;
    }
    uint8_t how = back[at(i, j)];
    if (how == kDiag) {
      bool match = frame_matches(frames[i - 1], expected[j - 1]);
      rev.push_back({match ? Mark::kEqual : Mark::kChanged, int(i - 1), int(j - 1)});
      --i, --j;
    } else if (how == kRepeat) {
      rev.push_back({Mark::kEqual, int(i - 1), int(j - 1)});
      --i;
    } else if (how == kUp) {
      rev.push_back({Mark::kExtra, int(i - 1), -1});
      --i;
    } else {
      if (expected[j - 1].min_count > 0) rev.push_back({Mark::kMissing, -1, int(j - 1)});
      --j;
    }
  }
  out->steps.assign(rev.rbegin(), rev.rend());
}

// Repeatable lines: present when reached through a skip, extra beyond their count, a note
// below it; then the counts of each mark.
void settle_repeats(const std::vector<Expected>& expected, DiffResult* out) {
  const size_t m = expected.size();
  // A repeatable line reached through a skip and then repeats is present, not missing.
  std::vector<bool> seen(m, false);
  for (const DiffStep& s : out->steps)
    if (s.mark == Mark::kEqual) seen[s.expected] = true;
  std::vector<DiffStep> kept;
  for (const DiffStep& s : out->steps)
    if (!(s.mark == Mark::kMissing && seen[s.expected])) kept.push_back(s);
  out->steps.swap(kept);
  // Repeat counts: beyond max become extra; below min is a note.
  std::vector<int> count(m, 0);
  for (DiffStep& s : out->steps) {
    if (s.mark != Mark::kEqual) continue;
    const Expected& e = expected[s.expected];
    if (++count[s.expected] > e.max_count && e.max_count >= 0) s = {Mark::kExtra, s.frame, -1};
  }
  for (size_t k = 0; k < m; ++k)
    if (count[k] > 0 && count[k] < expected[k].min_count)
      out->notes.push_back("line " + std::to_string(expected[k].line) + " matched " +
                           std::to_string(count[k]) + " times, expected at least " +
                           std::to_string(expected[k].min_count));
  for (const DiffStep& s : out->steps) {
    if (s.mark == Mark::kEqual) ++out->equal;
    if (s.mark == Mark::kChanged) ++out->changed;
    if (s.mark == Mark::kMissing) ++out->missing;
    if (s.mark == Mark::kExtra) ++out->extra;
  }
}

}  // namespace

Error diff_datagrams(const std::vector<Frame>& frames, const std::vector<Expected>& expected,
                     DiffResult* out, bool within) {
  *out = DiffResult();
  const size_t n = frames.size(), m = expected.size();
  if (static_cast<long long>(n + 1) * static_cast<long long>(m + 1) > kMaxDiffCells)
    return {"E_TOO_BIG", "too many datagrams to align (" + std::to_string(n) + " captured x " +
                             std::to_string(m) + " expected); cut the capture shorter"};
  for (const Expected& e : expected)
    if (!e.miso.any)
      for (const Frame& f : frames)
        if (!f.has_miso) out->miso_checked = false;
  trace_back(align(frames, expected, within), frames, expected, within, out);
  settle_repeats(expected, out);
  return {};
}

}  // namespace host::spi
