// Host-only hal::irq_save/irq_restore: a flag instead of the CPU priority.
#include "hal/fake/dspic_registers/fake_irq.h"

#include "hal/interfaces/irq.h"

namespace {
bool g_masked = false;
int g_saves = 0;
}  // namespace

namespace fake {
bool irqs_masked() {
  return g_masked;
}
int irq_save_count() {
  return g_saves;
}
void reset_irq_counts() {
  g_masked = false;
  g_saves = 0;
}
}  // namespace fake

namespace hal {
uint16_t irq_save() {
  const uint16_t was = g_masked ? 1 : 0;
  g_masked = true;
  ++g_saves;
  return was;
}
void irq_restore(uint16_t saved) {
  g_masked = saved != 0;
}
}  // namespace hal
