// Reading inputs and writing outputs so that no input can hang a program and no run, failed,
// interrupted or killed, leaves a half-written file or writes through a planted link.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rt {

// Writes bytes to a new temporary file beside `path`, then renames it over `path`; rename within a
// directory is atomic on POSIX, so readers see the old file or the whole new one. The temporary is
// created with O_CREAT | O_EXCL | O_NOFOLLOW under a name with random digits, so a link planted
// under any name it could take is never followed (the creation fails and another name is drawn).
// Throws InputError naming the path on any failure.
void write_file_atomically(const std::filesystem::path& path, const std::vector<char>& bytes);

// Reads a whole input file (a scene, a mesh, an image). Throws InputError "PATH: problem" when it
// cannot be opened or read, is not a regular file (a directory, a FIFO, a device such as /dev/zero,
// which would never end), is a kernel interface under /proc or /sys (which claim to be regular files
// of size 0 and may block for ever, /proc/kmsg), or is larger than `max_bytes`; `what` names the
// kind of file in the message. The file is opened without blocking and read between checks for a
// stop request, so Ctrl-C or SIGTERM ends even a read that would block (it throws Interrupted).
// With `head`, only the file's first `head` bytes are read (a header, to check before the rest).
std::string read_input_file(const std::filesystem::path& path, const std::string& what, std::uintmax_t max_bytes,
                            std::size_t head = SIZE_MAX);

// Checks before any work is done that `path` could be written: its directory exists and is
// writable, it is not a directory itself, and its name fits the file system (NAME_MAX). Throws
// InputError naming the path.
void check_output_writable(const std::filesystem::path& path);

// Whether two paths name the same file: the same inode once both exist, else the same absolute
// path once "." and ".." are resolved.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace rt
