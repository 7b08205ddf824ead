// Runs an AVR ELF in simavr (libsimavr): UART0 output goes to stdout; the run ends when the
// firmware sleeps with interrupts off (simavr's "done"), and fails on a crash or when the
// cycle limit is reached, so a hang fails the test instead of blocking it.
// Usage: simavr_run [--mcu atmega2560] [--freq 16000000] [--max-cycles N] firmware.elf
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "avr_uart.h"  // AVR_IOCTL_UART_GETIRQ, UART_IRQ_OUTPUT, AVR_UART_FLAG_STDIO
#include "sim_avr.h"   // avr_t, avr_make_mcu_by_name, avr_run
#include "sim_elf.h"   // elf_read_firmware, avr_load_firmware
#include "sim_irq.h"   // avr_irq_register_notify

namespace {

// Prints a UART0 byte as it is sent.
void uart_output(avr_irq_t*, uint32_t value, void*) {
  std::putchar(static_cast<int>(value & 0xFF));
}

int usage() {
  std::fprintf(stderr,
               "usage: simavr_run [--mcu NAME] [--freq HZ] [--max-cycles N] firmware.elf\n"
               "  e.g. simavr_run --mcu atmega2560 --freq 16000000 --max-cycles 2000000000 "
               "proxy_runner.elf\n"
               "exit status: 0 firmware stopped (slept with interrupts off), 1 crash or cycle "
               "limit, 2 usage or load error\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mcu = "atmega2560";
  unsigned long freq = 16000000UL;
  unsigned long long max_cycles = 2000000000ULL;
  const char* elf = nullptr;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--mcu" && i + 1 < argc) {
      mcu = argv[++i];
    } else if (a == "--freq" && i + 1 < argc) {
      freq = std::strtoul(argv[++i], nullptr, 10);
    } else if (a == "--max-cycles" && i + 1 < argc) {
      max_cycles = std::strtoull(argv[++i], nullptr, 10);
    } else if (a == "--help" || a == "-h") {
      usage();
      return 0;
    } else if (!elf && a[0] != '-') {
      elf = argv[i];
    } else {
      return usage();
    }
  }
  if (!elf || freq == 0) return usage();

  elf_firmware_t firmware;
  std::memset(&firmware, 0, sizeof(firmware));
  if (elf_read_firmware(elf, &firmware) != 0) {
    std::fprintf(stderr, "simavr_run: error: cannot read ELF %s\n", elf);
    return 2;
  }
  std::snprintf(firmware.mmcu, sizeof(firmware.mmcu), "%s", mcu.c_str());
  firmware.frequency = static_cast<uint32_t>(freq);
  avr_t* avr = avr_make_mcu_by_name(firmware.mmcu);
  if (!avr) {
    std::fprintf(stderr, "simavr_run: error: unknown MCU %s\n", firmware.mmcu);
    return 2;
  }
  avr_init(avr);
  avr->log = LOG_ERROR;
  avr_load_firmware(avr, &firmware);

  // Our own byte-by-byte forwarding instead of simavr's line logger.
  uint32_t flags = 0;
  avr_ioctl(avr, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
  flags &= ~static_cast<uint32_t>(AVR_UART_FLAG_STDIO);
  avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT),
                          uart_output, nullptr);

  int state = cpu_Running;
  while (state != cpu_Done && state != cpu_Crashed) {
    state = avr_run(avr);
    if (avr->cycle > max_cycles) {
      std::fflush(stdout);
      std::fprintf(stderr, "simavr_run: error: cycle limit %llu reached (hang?)\n", max_cycles);
      return 1;
    }
  }
  std::fflush(stdout);
  const double seconds = static_cast<double>(avr->cycle) / static_cast<double>(freq);
  if (state == cpu_Crashed) {
    std::fprintf(stderr, "simavr_run: error: firmware crashed after %llu cycles\n",
                 static_cast<unsigned long long>(avr->cycle));
    return 1;
  }
  std::fprintf(stderr, "simavr_run: stopped after %llu cycles (%.3f s at %lu Hz)\n",
               static_cast<unsigned long long>(avr->cycle), seconds, freq);
  return 0;
}
