// A clean source: lambdas, auto, decltype, rvalue references, brace init, attributes.
#include "clean.h"  // clean::Sink, clean::Fixed, clean::sum

namespace clean {

namespace {
const char kText[] = "constexpr nullptr std::move [[x]] noexcept";  // text only
const char kRaw[] = R"x(thread_local alignas)x";
}  // namespace

class Recorder : public Sink {
 public:
  Recorder() : last_(0) {}
  void put(uint8_t byte) { last_ = byte; }
  uint8_t last() const { return last_; }

 private:
  uint8_t last_;
};

static void move_into(Pair&& from, Pair* to) { *to = from; }

__attribute__((noinline)) int32_t use_everything() {
  static uint8_t storage[sizeof(Recorder)] __attribute__((aligned(2)));
  Recorder* r = new (storage) Recorder();
  r->put(static_cast<uint8_t>(sizeof(kText) + sizeof(kRaw)));
  auto twice = [](int32_t v) { return 2 * v; };
  decltype(twice(1)) total = twice(sum(1, 2, 3));
  Pair p{1, 2};
  Pair q = {0, 0};
  move_into(static_cast<Pair&&>(p), &q);
  Fixed<int32_t, 4> f;
  f.items[0] = q.a;
  int32_t copy = 0;
  memcpy(&copy, &f.items[0], sizeof(copy));
  Axis axis = Axis::kZ;
  return total + copy + r->last() + static_cast<int32_t>(axis) + (INT_MAX > 0 ? 1 : 0);
}

}  // namespace clean
