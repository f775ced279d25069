// Command lines through CLI11 (docs/design.md): the checks of number flags, the image encoding flags,
// parsing and the exit codes (0 ok, 1 bad input, 2 bad usage; every failure is one line on stderr).
// Only the files that parse a command line include this header, and with it CLI11: the stage
// programs go through common/stage_program.h, the options themselves are plain values
// (common/options.h).
#pragma once

#include "common/options.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace rt {

// A CLI11 check for an integer flag: decimal digits only (CLI11 itself reads "010" as octal 8 and
// "0x10" as 16) with a value in [lo, hi], exact up to 2^64 - 1; the text is rewritten without its
// leading zeros before CLI11 converts it.
CLI::Validator decimal(std::uint64_t lo, std::uint64_t hi);

// A CLI11 check for a floating-point flag: a finite number in [lo, hi] (CLI::Range lets NaN
// through, since every comparison with NaN is false).
CLI::Validator finite_range(double lo, double hi);

// The flags of how an image file encodes (common/image_io.h, common/display_transform.h): --exposure,
// --tone, --white and --gamma for a PNG, --exr-half for an EXR. Every stage program and merge.
void add_image_encoding_flags(CLI::App& app, ImageEncoding& encoding);

// The two halves of a program's shell, for any program of the project (the stage programs' run_stage_program,
// common/stage_program.h, and merge).
// Parses `app`: returns nothing when the run should go on, or the exit code after --help (0, help
// printed) or a usage error (2, one line "PROGRAM: error: ... (see --help)").
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv, const std::string& program);
// Runs `body` and returns the exit code: 0; 2 for UsageError; 1 for InputError, out of memory or
// any other exception, each with one line "PROGRAM: error: ..." (control characters escaped);
// 128 + the signal for Interrupted, with its message if it has one. Out of memory names `subject`
// (the scene, say) and the limit this process runs under.
int run_reporting_errors(const std::string& program, const std::function<void()>& body,
                         const std::string& subject = "");

}  // namespace rt
