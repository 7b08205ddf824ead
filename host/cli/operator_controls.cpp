// Signals and keys for the machine commands (see operator_controls.h).
#include "host/cli/operator_controls.h"

#include <signal.h>  // sigaction
#include <unistd.h>  // isatty, read

#include <algorithm>  // std::max, std::min

#include "host/lib/heightmap/controller_map.h"  // raise_tool_after_abort

namespace host::cli {

namespace {

Sender* g_sender = nullptr;           // for the signal handlers (request_* set atomics)
std::atomic<bool>* g_stop = nullptr;  // for `sim`
volatile sig_atomic_t g_abort_signalled = 0;

// Who stopped the job, as its message says it: Ctrl-C at the terminal is the operator (the
// terminal sends that SIGINT itself: SI_KERNEL); a signal from a process (kill, timeout, a
// service manager) is not, and is named.
const char* abort_cause(int sig, const siginfo_t* info) {
  if (sig == SIGINT && info != nullptr && info->si_code == SI_KERNEL)
    return "aborted by the operator (Ctrl-C)";
  return sig == SIGINT ? "stopped by SIGINT" : "stopped by SIGTERM";
}

extern "C" void on_signal(int sig, siginfo_t* info, void*) {
  if (g_sender == nullptr) return;
  if (sig == SIGUSR1)
    g_sender->request_hold();
  else if (sig == SIGUSR2)
    g_sender->request_resume();
  else {
    g_sender->request_abort(abort_cause(sig, info));
    g_abort_signalled = 1;
  }
}

extern "C" void on_stop(int) {
  if (g_stop != nullptr) *g_stop = true;
}

}  // namespace

void signals_to(Sender* sender) {
  g_sender = sender;
  struct sigaction sa {};
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGUSR1, SIGUSR2}) {
    // Without a sender: INT and TERM end the process, a hold or resume has nothing to act on.
    const bool stops = sig == SIGINT || sig == SIGTERM;
    sa.sa_flags = sender != nullptr ? SA_SIGINFO : 0;  // on_signal tells Ctrl-C from kill
    if (sender != nullptr)
      sa.sa_sigaction = on_signal;
    else
      sa.sa_handler = stops ? SIG_DFL : SIG_IGN;
    sigaction(sig, &sa, nullptr);
  }
}

bool abort_signalled() {
  return g_abort_signalled != 0;
}

std::string raise_tool_if_abort_signalled(Link& link, const SenderOptions& options, double z_mm) {
  if (!abort_signalled()) return "";
  return heightmap::raise_tool_after_abort(link, options, z_mm);
}

void signals_stop(std::atomic<bool>* stop) {
  g_stop = stop;
  struct sigaction sa {};
  sa.sa_handler = on_stop;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

Keyboard::Keyboard(Sender& sender) : sender_(sender) {
  if (!isatty(STDIN_FILENO)) return;
  tcgetattr(STDIN_FILENO, &saved_);
  termios raw = saved_;
  raw.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO);
  raw.c_cc[VMIN] = 0;
  raw.c_cc[VTIME] = 1;  // read() returns every 100 ms so the thread can stop
  tcsetattr(STDIN_FILENO, TCSANOW, &raw);
  active_ = true;
  thread_ = std::thread([this] { loop(); });
}

Keyboard::~Keyboard() {
  if (!active_) return;
  stop_ = true;
  thread_.join();
  tcsetattr(STDIN_FILENO, TCSANOW, &saved_);
}

void Keyboard::loop() {
  int override_pct = 100;
  while (!stop_) {
    char c;
    if (read(STDIN_FILENO, &c, 1) != 1) continue;
    if (c == 'h' || c == ' ') sender_.request_hold();
    if (c == 'r') sender_.request_resume();
    if (c == 'x' || c == 'q') sender_.request_abort();
    if (c == '+' || c == '-') {
      override_pct = std::max(10, std::min(200, override_pct + (c == '+' ? 10 : -10)));
      sender_.request_override(override_pct);
    }
  }
}

}  // namespace host::cli
