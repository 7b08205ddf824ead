// The operator's controls while `send`, `probe` or `run` talk to a machine, and while `sim`
// serves one: signals (INT/TERM abort, USR1 hold, USR2 resume) and keys on a terminal.
#ifndef HOST_CLI_OPERATOR_CONTROLS_H
#define HOST_CLI_OPERATOR_CONTROLS_H

#include <termios.h>  // termios

#include <atomic>  // std::atomic
#include <string>  // std::string
#include <thread>  // std::thread

#include "host/lib/stream/sender.h"

namespace host::cli {

// Signals go to this sender from now on (the handlers only set atomics); nullptr: INT and
// TERM end the process again (a command's later stages stay interruptible).
void signals_to(Sender* sender);
// Whether SIGINT or SIGTERM (Ctrl-C) asked signals_to's sender to abort since the start.
bool abort_signalled();
// After Ctrl-C stopped the machine where it was (#X: mid-touch, or cutting): a new session on
// the link and the tool up to z_mm; what happened, for the operator ("" without a Ctrl-C).
// probe, send and run all end this way.
std::string raise_tool_if_abort_signalled(Link& link, const SenderOptions& options, double z_mm);

// INT and TERM set `stop` (for `sim`, which has no sender); it must outlive the process's
// handling of them.
void signals_stop(std::atomic<bool>* stop);

// Keys while a job runs (stdin a terminal): h or space hold, r resume, x or q abort, + / -
// feed override in steps of 10 % (10..200 %). The terminal is raw while this object lives.
class Keyboard {
 public:
  explicit Keyboard(Sender& sender);
  ~Keyboard();
  Keyboard(const Keyboard&) = delete;
  Keyboard& operator=(const Keyboard&) = delete;

 private:
  void loop();
  Sender& sender_;
  termios saved_{};
  bool active_ = false;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace host::cli

#endif  // HOST_CLI_OPERATOR_CONTROLS_H
