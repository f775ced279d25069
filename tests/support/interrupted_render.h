// A render stopped by Ctrl-C as a user stops it: the program started, SIGINT a second later, and
// what came of it two seconds after that. Shared by the stage programs' Ctrl-C tests, which take it
// through subject() and judge it outside.
#pragma once

#include "common/image_io.h"
#include "reliability/child_process.h"
#include "support/test_support.h"

#include <csignal>
#include <filesystem>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

namespace rt::testing {

struct InterruptedRender {
  bool started = false, ended = false;  // ended within two seconds of the signal
  int exit_code = -1;                   // -1 when a signal ended it
  std::string said;                     // its stdout
  Image image;                          // what it wrote to `out`, if anything
};
inline auto record_fields(InterruptedRender& r) {  // support/record.h
  return std::tie(r.started, r.ended, r.exit_code, r.said, r.image);
}

// Runs `argv` (which writes `out`) with stdout and stderr in `folder`, and interrupts it.
inline InterruptedRender interrupt_render(const std::vector<std::string>& argv, const std::filesystem::path& folder,
                                          const std::filesystem::path& out) {
  using namespace std::chrono_literals;
  InterruptedRender r;
  ChildProcess child(argv, folder / "stdout.txt", folder / "stderr.txt");
  r.started = child.started();
  if (!r.started) return r;
  std::this_thread::sleep_for(1000ms);
  child.signal(SIGINT);
  const std::optional<int> status = child.wait_for(2000ms);
  r.ended = status.has_value();
  if (!r.ended) return r;
  r.exit_code = WIFEXITED(*status) ? WEXITSTATUS(*status) : -1;
  r.said = read_text(folder / "stdout.txt");
  if (std::filesystem::exists(out)) r.image = read_pfm(out);
  return r;
}

}  // namespace rt::testing
