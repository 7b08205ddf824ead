// Masking interrupts around the few places that must not be interrupted (not for sharing
// data: that goes through SPSC rings). Implemented by the dsPIC port (CPU priority 7) and
// on the host by hal/fake/dspic_registers (records the nesting).
#ifndef HAL_INTERFACES_IRQ_H
#define HAL_INTERFACES_IRQ_H

#include <stdint.h>  // uint16_t

namespace hal {

// Masks all maskable interrupts; returns the state to hand to irq_restore().
uint16_t irq_save();
// Puts back the state irq_save() returned (so nested sections work).
void irq_restore(uint16_t saved);

// Masks interrupts for the lifetime of a local object.
class IrqGuard {
 public:
  IrqGuard() : saved_(irq_save()) {}
  ~IrqGuard() { irq_restore(saved_); }

 private:
  IrqGuard(const IrqGuard&);
  IrqGuard& operator=(const IrqGuard&);
  uint16_t saved_;
};

}  // namespace hal

#endif  // HAL_INTERFACES_IRQ_H
