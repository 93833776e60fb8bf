#include "interruption.hpp"

#include "commands.hpp"
#include "terminal_progress.hpp"

#include <atomic>
#include <csignal>
#include <unistd.h>

namespace fissure::cli {
namespace {

CancelToken g_token;

// What an unanswered signal may do: nothing while results are written (Busy), end the process
// while only computing (Abandonable). Exiting: the alarm handler won the race and is ending it.
enum State : int { kBusy, kAbandonable, kExiting };
std::atomic<int> g_state{kBusy};
static_assert(std::atomic<int>::is_always_lock_free, "used from signal handlers");

extern "C" void on_interrupt(int signal_number) {
  if (g_token.cancelled()) {
    // Second signal: the default action (terminate) as soon as this handler returns.
    ::signal(signal_number, SIG_DFL);
    ::raise(signal_number);
    return;
  }
  g_token.cancel();
  ::alarm(kGraceSeconds);
}

extern "C" void on_grace_expired(int) {
  int expected = kAbandonable;
  if (!g_state.compare_exchange_strong(expected, kExiting)) return;  // writing: let it finish
  static const char message[] = "fissure: cancelled\n";
  print_line_from_signal_handler(message, sizeof message - 1);
  ::_exit(kExitCancelled);
}

void install(int signal_number, void (*handler)(int), bool keep_ignored) {
  struct sigaction action {};
  if (keep_ignored && ::sigaction(signal_number, nullptr, &action) == 0 && action.sa_handler == SIG_IGN) return;
  action = {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  ::sigaction(signal_number, &action, nullptr);
}

}  // namespace

void install_interrupt_handlers() {
  install(SIGINT, on_interrupt, true);
  install(SIGTERM, on_interrupt, true);
  install(SIGALRM, on_grace_expired, false);
}

const CancelToken& interrupt_token() { return g_token; }

void throw_if_interrupted() { g_token.throw_if_cancelled(); }

AbandonableWork::AbandonableWork() { g_state.store(kAbandonable); }

AbandonableWork::~AbandonableWork() {
  int expected = kAbandonable;
  if (!g_state.compare_exchange_strong(expected, kBusy)) {
    // The alarm handler is ending the process on another thread: wait for it.
    for (;;) ::pause();
  }
}

}  // namespace fissure::cli
