#include "common/file_io.h"

#include "common/error.h"
#include "common/interrupt.h"

#include <fcntl.h>
#include <linux/magic.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/statfs.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <random>

namespace rt {
namespace fs = std::filesystem;

namespace {

fs::path directory_of(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

// Closes a file descriptor when it goes out of scope.
struct FileDescriptor {
  int fd;
  explicit FileDescriptor(int f) : fd(f) {}
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
};

// File systems whose "files" are kernel interfaces: stat calls them regular files of size 0, and
// reading one may block for ever (/proc/kmsg) or never end.
bool is_kernel_interface(int fd) {
  struct statfs info {};
  if (::fstatfs(fd, &info) != 0) return false;
  switch (static_cast<unsigned long>(info.f_type)) {
    case PROC_SUPER_MAGIC:
    case SYSFS_MAGIC:
    case DEBUGFS_MAGIC:
    case TRACEFS_MAGIC:
    case SECURITYFS_MAGIC:
    case CGROUP_SUPER_MAGIC:
    case CGROUP2_SUPER_MAGIC:
      return true;
    default:
      return false;
  }
}

// Waits until `fd` has data (at once for a regular file) or a stop request comes; returns false on
// a stop request. poll(2) is never restarted after a signal, whatever SA_RESTART says, and it wakes
// every `milliseconds` besides, so a stop is seen within that time even by a read that would block.
bool wait_readable(int fd, int milliseconds) {
  pollfd p{fd, POLLIN, 0};
  while (true) {
    const int ready = ::poll(&p, 1, milliseconds);
    if (ready > 0) return true;
    if (ready < 0 && errno != EINTR) return true;  // let read(2) report the error
    if (interrupt_requested()) return false;
  }
}

}  // namespace

std::string read_input_file(const fs::path& path, const std::string& what, std::uintmax_t max_bytes, std::size_t head) {
  const std::string name = path.string();
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer.
  const FileDescriptor file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
  if (file.fd < 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw InputError(name + ": cannot open " + what);
    throw InputError(name + ": cannot open " + what + ": " + std::strerror(errno));
  }
  struct stat status {};
  if (::fstat(file.fd, &status) != 0) throw InputError(name + ": cannot read " + what + ": " + std::strerror(errno));
  if (!S_ISREG(status.st_mode)) throw InputError(name + ": cannot read " + what + ": not a regular file");
  if (is_kernel_interface(file.fd))
    throw InputError(name + ": cannot read " + what + ": a kernel interface under /proc or /sys, not a file");
  const std::uintmax_t size = std::uintmax_t(status.st_size);
  if (size > max_bytes)
    throw InputError(name + ": " + what + " of " + std::to_string(size) + " bytes, more than the " +
                     std::to_string(max_bytes) + " this program reads");
  std::string bytes;
  bytes.reserve(std::min(size_t(size), head));
  char buffer[1 << 16];
  while (bytes.size() < head) {
    if (!wait_readable(file.fd, 100))
      throw Interrupted{interrupt_signal(), "interrupted while reading " + name + ": nothing written"};
    const ssize_t got = ::read(file.fd, buffer, std::min(sizeof buffer, head - bytes.size()));
    if (got == 0) break;
    if (got < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      throw InputError(name + ": cannot read " + what + ": " + std::strerror(errno));
    }
    if (bytes.size() + size_t(got) > max_bytes)  // the file grew while it was read
      throw InputError(name + ": " + what + " of more than the " + std::to_string(max_bytes) +
                       " bytes this program reads");
    bytes.append(buffer, size_t(got));
  }
  return bytes;
}

namespace {

// A new, empty file ".NAME.RANDOM.tmp" beside `path`, NAME cut so that the whole name stays within
// NAME_MAX whatever the output's length. O_EXCL makes the creation fail on any existing name, a
// link included, and another name is drawn: a planted link is never followed. Returns its
// descriptor and name; throws InputError naming `path`.
std::pair<int, fs::path> create_temporary_beside(const fs::path& path) {
  const std::string stem = path.filename().string().substr(0, 128);
  std::random_device entropy;
  for (int attempt = 0; attempt < 64; ++attempt) {
    const fs::path temporary = directory_of(path) / ("." + stem + "." + std::to_string(entropy()) + ".tmp");
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) return {fd, temporary};
    if (errno != EEXIST) throw InputError("cannot write '" + path.string() + "': " + std::strerror(errno));
  }
  throw InputError("cannot write '" + path.string() + "': no free temporary name beside it");
}

}  // namespace

void check_output_writable(const fs::path& path) {
  const fs::path dir = directory_of(path);
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError("cannot write '" + path.string() + "': directory '" + dir.string() + "' does not exist");
  if (fs::is_directory(path, ec)) throw InputError("cannot write '" + path.string() + "': it is a directory");
  if (::access(dir.c_str(), W_OK) != 0)
    throw InputError("cannot write '" + path.string() + "': directory '" + dir.string() + "' is not writable");
  const long name_max = ::pathconf(dir.c_str(), _PC_NAME_MAX);
  const size_t length = path.filename().string().size();
  if (name_max > 0 && length > size_t(name_max))
    throw InputError("cannot write '" + path.string() + "': its name is " + std::to_string(length) +
                     " bytes long, and this file system allows " + std::to_string(name_max));
  // What access(2) cannot tell (it says yes to root, and knows nothing of a read-only mount): make
  // the temporary file the write would make, and remove it again.
  const auto [fd, probe] = create_temporary_beside(path);
  ::close(fd);
  ::unlink(probe.c_str());
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::equivalent(a, b, ec)) return true;
  // Absolute first: of a relative path whose first part does not exist, weakly_canonical returns
  // the path unchanged, so "o.png" and "./o.png" would differ.
  const fs::path x = fs::weakly_canonical(fs::absolute(a, ec), ec);
  if (ec) return false;
  const fs::path y = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return !ec && x == y;
}

void write_file_atomically(const fs::path& path, const std::vector<char>& bytes) {
  check_output_writable(path);
  const auto [fd, temporary] = create_temporary_beside(path);
  const FileDescriptor file(fd);
  set_pending_temporary(temporary);  // an immediate exit (a second Ctrl-C) removes it
  struct Clear {
    ~Clear() { clear_pending_temporary(); }
  } clear;
  auto fail = [&, &temporary = temporary](const std::string& reason) {
    ::unlink(temporary.c_str());
    throw InputError("cannot write '" + path.string() + "': " + reason);
  };
  for (size_t written = 0; written < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(std::strerror(errno));
    written += size_t(n);
  }
  // On disk before the rename, so that even a crash of the machine leaves the old file or the new.
  if (::fsync(fd) != 0) fail(std::strerror(errno));
  if (::rename(temporary.c_str(), path.c_str()) != 0) fail(std::strerror(errno));
}

}  // namespace rt
