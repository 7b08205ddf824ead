// A first-in first-out queue of bytes for the simulated UART: one vector and a read index
// (std::deque cost a visible part of a link-bound simulation, three moves a byte).
#ifndef HOST_LIB_SIM_BYTE_FIFO_H
#define HOST_LIB_SIM_BYTE_FIFO_H

#include <cstddef>  // size_t
#include <cstdint>  // uint8_t
#include <vector>   // std::vector

namespace host::sim {

class ByteFifo {
 public:
  bool empty() const { return head_ == bytes_.size(); }
  size_t size() const { return bytes_.size() - head_; }
  uint8_t front() const { return bytes_[head_]; }
  // The bytes waiting, front first (size() of them).
  const uint8_t* data() const { return bytes_.data() + head_; }
  void push_back(uint8_t b) { bytes_.push_back(b); }
  void append(const uint8_t* data, size_t n) { bytes_.insert(bytes_.end(), data, data + n); }
  void pop_front() { pop_front(1); }
  // Drops the first n bytes (n <= size()): one move for a run of bytes, not one call each.
  void pop_front(size_t n) {
    head_ += n;
    // Read out: start again at the front. Else the read part goes once it is the most.
    if (head_ == bytes_.size()) {
      bytes_.clear();
      head_ = 0;
    } else if (head_ >= 4096 && head_ * 2 >= bytes_.size()) {
      bytes_.erase(bytes_.begin(), bytes_.begin() + static_cast<std::ptrdiff_t>(head_));
      head_ = 0;
    }
  }
  void clear() {
    bytes_.clear();
    head_ = 0;
  }

 private:
  std::vector<uint8_t> bytes_;
  size_t head_ = 0;
};

}  // namespace host::sim

#endif  // HOST_LIB_SIM_BYTE_FIFO_H
