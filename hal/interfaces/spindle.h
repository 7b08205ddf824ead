// The spindle (or any tool motor switched by one output), as the application sees it.
#ifndef HAL_INTERFACES_SPINDLE_H
#define HAL_INTERFACES_SPINDLE_H

namespace hal {

class Spindle {
 public:
  // Switches the spindle on or off. Called from the background loop only.
  virtual void set_on(bool on) = 0;

 protected:
  ~Spindle() {}
};

}  // namespace hal

#endif  // HAL_INTERFACES_SPINDLE_H
