// Writing output files so that a failed or interrupted run never leaves a half-written file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rt {

// Writes bytes to a temporary file beside `path`, then renames it over `path`; rename within a
// directory is atomic on POSIX, so readers see the old file or the whole new one.
// Throws InputError naming the path on any failure.
void write_file_atomically(const std::filesystem::path& path, const std::vector<char>& bytes);

// Reads a whole input file (a scene, a mesh). Throws InputError "PATH: problem" when it cannot be
// opened or read, is not a regular file (a directory, or a device such as /dev/zero, which would
// never end), or is larger than `max_bytes`; `what` names the kind of file in the message.
std::string read_input_file(const std::filesystem::path& path, const std::string& what, std::uintmax_t max_bytes);

// Checks before any work is done that `path` could be written: its directory exists and is
// writable, and it is not a directory itself. Throws InputError naming the path.
void check_output_writable(const std::filesystem::path& path);

}  // namespace rt
