// Host-only stand-in for hal::irq_save/irq_restore (hal/interfaces/irq.h) for code tested
// without the dsPIC port: records whether interrupts are masked and how often.
#ifndef HAL_FAKE_DSPIC_REGISTERS_FAKE_IRQ_H
#define HAL_FAKE_DSPIC_REGISTERS_FAKE_IRQ_H

namespace fake {

// True between an irq_save() and its irq_restore().
bool irqs_masked();
// Number of irq_save() calls since the last reset_irq_counts().
int irq_save_count();
void reset_irq_counts();

}  // namespace fake

#endif  // HAL_FAKE_DSPIC_REGISTERS_FAKE_IRQ_H
