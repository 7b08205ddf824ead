// The probe input: continuity between the clamped tool and the copper blank (a clip on the
// board) closes it. The application debounces it and latches Z in the 1 ms tick.
#ifndef HAL_INTERFACES_PROBE_INPUT_H
#define HAL_INTERFACES_PROBE_INPUT_H

namespace hal {

class ProbeInput {
 public:
  // Raw level: true while the probe circuit is closed (the tool touches the copper), or if
  // it closed at any moment since the last call (a touch shorter than a tick is not lost;
  // the debounce then decides). Called once per 1 ms tick.
  virtual bool closed() = 0;

 protected:
  ~ProbeInput() {}
};

}  // namespace hal

#endif  // HAL_INTERFACES_PROBE_INPUT_H
