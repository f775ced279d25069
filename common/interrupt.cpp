#include "common/interrupt.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>

namespace rt {
namespace {

std::atomic<int> requested_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");

// The pending temporary file's name, NUL-terminated; empty when none. Written only outside the
// handler, read by it.
char pending_temporary[4096];
std::atomic<bool> has_pending_temporary{false};

void on_signal(int signal_number) {
  int expected = 0;
  if (requested_signal.compare_exchange_strong(expected, signal_number)) {
    constexpr char kMessage[] = "\ninterrupted: finishing the current samples and writing the image "
                                "(press Ctrl-C again to quit at once)\n";
    [[maybe_unused]] const ssize_t ignored = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    return;
  }
  // A second signal: leave now, without a half-written file. unlink, write and _exit are
  // async-signal-safe (POSIX.1-2008, signal-safety(7)).
  if (has_pending_temporary.load()) ::unlink(pending_temporary);
  constexpr char kMessage[] = "\ninterrupted again: quitting without writing the image\n";
  [[maybe_unused]] const ssize_t ignored = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
  ::_exit(128 + signal_number);
}

struct sigaction previous_int, previous_term, previous_hup;

}  // namespace

InterruptHandler::InterruptHandler() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // a write(2) in progress goes on rather than failing with EINTR
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGTERM, &action, &previous_term);
  // A closed terminal (SIGHUP) is a stop request like SIGTERM, not a lost render.
  sigaction(SIGHUP, &action, &previous_hup);
}

InterruptHandler::~InterruptHandler() {
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
  sigaction(SIGHUP, &previous_hup, nullptr);
}

bool interrupt_requested() { return requested_signal.load(std::memory_order_relaxed) != 0; }
int interrupt_signal() { return requested_signal.load(); }
void request_interrupt(int signal_number) { requested_signal = signal_number; }
void clear_interrupt() { requested_signal = 0; }

void set_pending_temporary(const std::filesystem::path& path) {
  const std::string name = path.string();
  has_pending_temporary = false;
  const size_t length = std::min(name.size(), sizeof pending_temporary - 1);
  std::memcpy(pending_temporary, name.data(), length);
  pending_temporary[length] = '\0';
  has_pending_temporary = name.size() < sizeof pending_temporary;
}

void clear_pending_temporary() { has_pending_temporary = false; }

}  // namespace rt
