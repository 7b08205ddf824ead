// The simulated UART's byte queue: first in, first out, across the compaction of what was
// read and after a clear.
#include "host/lib/sim/byte_fifo.h"

#include <gtest/gtest.h>

#include <algorithm>  // std::min
#include <deque>      // std::deque: the reference

namespace host::sim {
namespace {

TEST(ByteFifo, KeepsTheOrderOfAStdDequeAcrossCompactions) {
  ByteFifo fifo;
  std::deque<uint8_t> reference;
  uint32_t seed = 7;
  for (int round = 0; round < 20000; ++round) {
    seed = seed * 1103515245u + 12345u;
    const int pushes = (seed >> 16) % 24;  // a frame or so in, some bytes out, as the UART
    for (int i = 0; i < pushes; ++i) {
      const uint8_t b = static_cast<uint8_t>(round * 31 + i);
      if (i % 2) {
        fifo.push_back(b);
      } else {
        fifo.append(&b, 1);
      }
      reference.push_back(b);
    }
    const int pops = (seed >> 8) % 23;
    for (int i = 0; i < pops && !reference.empty(); ++i) {
      ASSERT_FALSE(fifo.empty());
      ASSERT_EQ(fifo.front(), reference.front()) << "round " << round;
      fifo.pop_front();
      reference.pop_front();
    }
    ASSERT_EQ(fifo.size(), reference.size());
  }
  EXPECT_GT(reference.size(), 4096u);  // compactions happened with bytes still queued
  fifo.clear();
  EXPECT_TRUE(fifo.empty());
  fifo.push_back(5);
  EXPECT_EQ(fifo.front(), 5);
}

// The UART model moves the bytes one credit allows as a run (data(), pop_front(n)): the same
// order as a byte at a time, across compactions too.
TEST(ByteFifo, RunsTakenFromTheFrontKeepTheOrder) {
  ByteFifo fifo;
  std::deque<uint8_t> reference;
  uint32_t seed = 11;
  for (int round = 0; round < 20000; ++round) {
    seed = seed * 1103515245u + 12345u;
    const int pushes = (seed >> 16) % 24;
    for (int i = 0; i < pushes; ++i) {
      const uint8_t b = static_cast<uint8_t>(round * 37 + i);
      fifo.push_back(b);
      reference.push_back(b);
    }
    const size_t run = std::min<size_t>((seed >> 8) % 23, reference.size());
    ASSERT_EQ(fifo.size(), reference.size());
    for (size_t i = 0; i < run; ++i) ASSERT_EQ(fifo.data()[i], reference[i]) << "round " << round;
    fifo.pop_front(run);
    reference.erase(reference.begin(), reference.begin() + static_cast<std::ptrdiff_t>(run));
  }
  EXPECT_GT(reference.size(), 4096u);  // compactions happened with bytes still queued
  fifo.pop_front(fifo.size());
  EXPECT_TRUE(fifo.empty());
}

}  // namespace
}  // namespace host::sim
