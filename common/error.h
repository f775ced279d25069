// The two ways a run can fail on purpose, each with its exit code (docs/design.md, "Command line").
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace rt {

std::string printable(std::string_view text);

// Bad input: a malformed scene or image file, an unwritable output. Exit code 1.
// The message is one line that names the file and the problem. It is made printable (below) when
// the error is made: what() is a C string, so a NUL byte quoted from a file would cut it there.
struct InputError : std::runtime_error {
  explicit InputError(const std::string& message) : std::runtime_error(printable(message)) {}
};

// Bad usage: unknown flags, impossible parameters. Exit code 2. Printable as InputError is.
struct UsageError : std::runtime_error {
  explicit UsageError(const std::string& message) : std::runtime_error(printable(message)) {}
};

// A run stopped by SIGINT, SIGTERM or SIGHUP (common/interrupt.h): after its partial image was
// written, or before anything was (then `message` says so). Exit code 128 + the signal's number, as
// a shell reports a process the signal ended.
struct Interrupted {
  int signal_number;
  std::string message;  // printed as "PROGRAM: MESSAGE" when not empty
};

// `text` with every control character (a newline in a file name, say) written as an escape: \n,
// \r, \t or \xHH. Every message a program prints goes through it, so an error is always one line.
std::string printable(std::string_view text);

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;
inline constexpr int kExitBadUsage = 2;

}  // namespace rt
