// A link wrapper for tests: corrupts, drops or cuts the bytes the sender writes, with a
// fixed seed so every run is the same.
#ifndef HOST_TESTS_HOST_SIM_FAULTY_LINK_H
#define HOST_TESTS_HOST_SIM_FAULTY_LINK_H

#include <memory>  // std::unique_ptr
#include <random>  // std::mt19937

#include "host/lib/stream/link.h"

namespace host::test {

struct Faults {
  double flip_bit = 0.0;    // per byte written: flip one bit
  double drop_byte = 0.0;   // per byte written: leave it out
  double garbage = 0.0;     // per write: add 1..8 random bytes first
  double drop_frame = 0.0;  // per write: send nothing
  size_t cut_after = 0;     // bytes written before the link "breaks" (0 = never)
  uint32_t seed = 1;
};

class FaultyLink : public Link {
 public:
  FaultyLink(std::unique_ptr<Link> inner, const Faults& f)
      : inner_(std::move(inner)), f_(f), rng_(f.seed) {}

  void write(const uint8_t* data, size_t size) override {
    if (f_.cut_after && written_ + size > f_.cut_after) throw LinkError("test: link cut");
    written_ += size;
    if (chance(f_.drop_frame)) return;
    std::vector<uint8_t> out;
    if (chance(f_.garbage)) {
      const int n = 1 + static_cast<int>(rng_() % 8);
      for (int i = 0; i < n; ++i) out.push_back(static_cast<uint8_t>(rng_()));
    }
    for (size_t i = 0; i < size; ++i) {
      if (chance(f_.drop_byte)) continue;
      uint8_t b = data[i];
      if (chance(f_.flip_bit)) b ^= static_cast<uint8_t>(1u << (rng_() % 8));
      out.push_back(b);
    }
    if (!out.empty()) inner_->write(out.data(), out.size());
  }
  size_t read(uint8_t* buffer, size_t capacity, std::chrono::milliseconds timeout) override {
    return inner_->read(buffer, capacity, timeout);
  }
  std::string name() const override { return "faulty " + inner_->name(); }

 private:
  bool chance(double p) { return p > 0 && std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
  std::unique_ptr<Link> inner_;
  Faults f_;
  std::mt19937 rng_;
  size_t written_ = 0;
};

}  // namespace host::test

#endif  // HOST_TESTS_HOST_SIM_FAULTY_LINK_H
