#include "common/file_io.h"

#include "common/error.h"
#include "common/interrupt.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

namespace rt {
namespace fs = std::filesystem;

namespace {

fs::path directory_of(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

}  // namespace

std::string read_input_file(const fs::path& path, const std::string& what, std::uintmax_t max_bytes) {
  const std::string name = path.string();
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw InputError(name + ": cannot open " + what);
  if (!fs::is_regular_file(status)) throw InputError(name + ": cannot read " + what + ": not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes)
    throw InputError(name + ": " + what + " of " + std::to_string(size) + " bytes, more than the " +
                     std::to_string(max_bytes) + " this program reads");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(name + ": cannot open " + what);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(name + ": cannot read " + what);
  return text.str();
}

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
  set_pending_temporary(temporary);  // an immediate exit (a second Ctrl-C) removes it
  struct Clear {
    ~Clear() { clear_pending_temporary(); }
  } clear;
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
