#include "common/memory_limit.h"

#include "common/error.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <limits>

namespace rt {
namespace {

constexpr std::uint64_t kUnlimited = std::numeric_limits<std::uint64_t>::max();

std::uint64_t soft_limit(int resource) {
  rlimit limit{};
  if (::getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return kUnlimited;
  return std::uint64_t(limit.rlim_cur);
}

// A cgroup file holding one number, or "max" (no limit); absent files are no limit either.
std::uint64_t cgroup_number(const std::string& path) {
  std::ifstream in(path);
  std::string word;
  if (!(in >> word) || word == "max" || word.find_first_not_of("0123456789") != std::string::npos) return kUnlimited;
  try {
    return std::stoull(word);
  } catch (const std::exception&) {
    return kUnlimited;
  }
}

}  // namespace

std::uint64_t cgroup_memory_limit(const std::string& cgroup_file, const std::string& cgroup_root) {
  std::ifstream groups(cgroup_file);
  std::string line;
  std::uint64_t tightest = kUnlimited;
  while (std::getline(groups, line)) {
    // "0::/path" (v2), or "N:memory:/path" among the other controllers' lines (v1).
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    std::string group = line.substr(second + 1), root, file;
    if (controllers.empty()) root = cgroup_root, file = "memory.max";
    else if (controllers == "memory") root = cgroup_root + "/memory", file = "memory.limit_in_bytes";
    else continue;
    while (true) {  // the group's own limit, then every parent's: each applies to all below it
      tightest = std::min(tightest, cgroup_number(root + group + "/" + file));
      if (group.empty() || group == "/") break;
      group = group.substr(0, group.rfind('/'));
    }
  }
  return tightest;
}

std::string binary_size(double bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int unit = 0;
  for (; bytes >= 1024.0 && unit < 6; ++unit) bytes /= 1024.0;
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", bytes, units[unit]);
  return text;
}

std::string MemoryLimit::describe() const {
  const std::string size = binary_size(double(bytes));
  switch (source) {
    case Source::machine: return "this machine has " + size;
    case Source::address_space: return "this process may use " + size + " (ulimit -v)";
    case Source::data_segment: return "this process may use " + size + " (ulimit -d)";
    case Source::cgroup: return "its cgroup allows " + size + " (memory.max)";
  }
  return size;
}

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return kUnlimited;  // unknown: do not refuse
  return std::uint64_t(pages) * std::uint64_t(page_size);
}

MemoryLimit memory_limit() {
  MemoryLimit limit{physical_memory_bytes(), MemoryLimit::Source::machine};
  const std::pair<std::uint64_t, MemoryLimit::Source> others[] = {
      {soft_limit(RLIMIT_AS), MemoryLimit::Source::address_space},
      {soft_limit(RLIMIT_DATA), MemoryLimit::Source::data_segment},
      {cgroup_memory_limit("/proc/self/cgroup", "/sys/fs/cgroup"), MemoryLimit::Source::cgroup}};
  for (const auto& [bytes, source] : others)
    if (bytes < limit.bytes) limit = {bytes, source};
  return limit;
}

void check_image_fits(const std::string& out, int width, int height, const MemoryLimit& limit) {
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (pixels > std::uint64_t(std::numeric_limits<int>::max()))
    throw InputError(out + ": a " + size + " image has more than 2^31 - 1 pixels");
  const std::uint64_t needed = pixels * kBytesPerPixel;
  if (needed > limit.bytes)
    throw InputError(out + ": a " + size + " image needs " + binary_size(double(needed)) +
                     " of memory (its sample sums, the image and the encoded file), and " + limit.describe());
}

void check_scene_fits(const std::string& scene, std::uint64_t triangles, const OtherMemory& other,
                      const MemoryLimit& limit) {
  // In double: 10^5 bunnies are 7e9 triangles, whose bytes overflow no 64-bit integer yet, but a
  // product of two unchecked counts might.
  const double needed = double(triangles) * double(kBytesPerTriangle) + other.bytes;
  if (needed <= double(limit.bytes)) return;
  throw InputError(scene + ": the render needs about " + binary_size(needed) + " of memory (" +
                   std::to_string(triangles) + " triangles at " + std::to_string(kBytesPerTriangle) +
                   " bytes each with the acceleration structure, and " + other.what + "), and " + limit.describe());
}

}  // namespace rt
