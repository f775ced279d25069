// Stopping a long render on Ctrl-C (SIGINT), SIGTERM or SIGHUP (a closed terminal) without losing
// it. The first signal only raises a flag: the pixel loop sees it within one sample, stops, and the
// program writes what it has (each pixel normalized by the samples it finished) and says so; a
// read of an input sees it too (common/file_io.h). A second signal exits at once (after removing a
// half-written temporary file), for when even that is too slow.
#pragma once

#include <filesystem>

namespace rt {

// Installs the handlers for the lifetime of the object (the stage programs hold one while they
// render); the previous handlers come back on destruction.
class InterruptHandler {
 public:
  InterruptHandler();
  ~InterruptHandler();
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;
};

// Whether a stop was asked for, and by which signal (0 when none). A lock-free atomic load:
// cheap enough to ask once per sample.
bool interrupt_requested();
int interrupt_signal();
// For tests: asks for a stop as the first SIGINT would, or forgets a request.
void request_interrupt(int signal_number);
void clear_interrupt();

// The temporary file being written (write_file_atomically), which an immediate exit removes.
// Kept in a fixed buffer: the signal handler may only call async-signal-safe functions.
void set_pending_temporary(const std::filesystem::path& path);
void clear_pending_temporary();

}  // namespace rt
