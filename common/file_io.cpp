#include "common/file_io.h"

#include "common/error.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace rt {
namespace fs = std::filesystem;

namespace {

fs::path directory_of(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

}  // namespace

void check_output_writable(const fs::path& path) {
  const fs::path dir = directory_of(path);
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError("cannot write '" + path.string() + "': directory '" + dir.string() +
                     "' does not exist");
  if (fs::is_directory(path, ec))
    throw InputError("cannot write '" + path.string() + "': it is a directory");
  if (::access(dir.c_str(), W_OK) != 0)
    throw InputError("cannot write '" + path.string() + "': directory '" + dir.string() +
                     "' is not writable");
}

void write_file_atomically(const fs::path& path, const std::vector<char>& bytes) {
  check_output_writable(path);
  // The temporary name carries the process id, so parallel runs writing the same output do not
  // write into each other's temporary file.
  fs::path temporary = path;
  temporary += ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (out) out.write(bytes.data(), std::streamsize(bytes.size()));
    out.flush();
    if (!out) {
      const std::string reason = std::strerror(errno);
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw InputError("cannot write '" + path.string() + "': " + reason);
    }
  }
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw InputError("cannot write '" + path.string() + "': " + ec.message());
  }
}

}  // namespace rt
