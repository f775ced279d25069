// Writing output files so that a failed or interrupted run never leaves a half-written file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rt {

// Writes bytes to a temporary file beside `path`, then renames it over `path`; rename within a
// directory is atomic on POSIX, so readers see the old file or the whole new one.
// Throws InputError naming the path on any failure.
void write_file_atomically(const std::filesystem::path& path, const std::vector<char>& bytes);

// Checks before any work is done that `path` could be written: its directory exists and is
// writable, and it is not a directory itself. Throws InputError naming the path.
void check_output_writable(const std::filesystem::path& path);

}  // namespace rt
