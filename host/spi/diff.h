// Aligns captured datagrams with expected ones (Needleman-Wunsch with wildcard matching
// and repeatable lines) and classifies each step: = same, ~ changed (same address byte),
// - expected but not captured, + captured but not expected.
#ifndef HOST_SPI_DIFF_H
#define HOST_SPI_DIFF_H

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/spi/capture.h"  // Error
#include "host/spi/frame.h"    // Frame
#include "host/spi/golden.h"   // Expected

namespace host::spi {

enum class Mark : char { kEqual = '=', kChanged = '~', kMissing = '-', kExtra = '+' };

struct DiffStep {
  Mark mark;
  int frame;     // index into the frames given, -1 for kMissing
  int expected;  // index into the expected lines, -1 for kExtra
};

struct DiffResult {
  std::vector<DiffStep> steps;
  int equal = 0, changed = 0, missing = 0, extra = 0;
  std::vector<std::string> notes;  // e.g. repeat counts out of range
  bool miso_checked = true;        // false when the capture has no MISO but lines give one
  int ignored_before = 0, ignored_after = 0;  // with `within`: datagrams outside the match
  bool same() const { return changed == 0 && missing == 0 && extra == 0 && notes.empty(); }
};

// Largest frames x expected product aligned (the traceback matrix is one byte per cell).
const long long kMaxDiffCells = 64LL * 1024 * 1024;

// True when the frame fits the line (both patterns, MISO only where captured).
bool frame_matches(const Frame& f, const Expected& e);

// Aligns. within: the expected lines may lie anywhere in the capture; datagrams before the
// first and after the last aligned line are not marked (counted in ignored_before/after).
// E_TOO_BIG when frames x expected exceeds kMaxDiffCells.
Error diff_datagrams(const std::vector<Frame>& frames, const std::vector<Expected>& expected,
                     DiffResult* out, bool within = false);

// The same frames with MOSI and MISO exchanged (to test the "probes swapped" hypothesis).
std::vector<Frame> swap_mosi_miso(const std::vector<Frame>& frames);

}  // namespace host::spi

#endif  // HOST_SPI_DIFF_H
