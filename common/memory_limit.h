// How much memory this process may use, and the checks that refuse, before anything is allocated,
// an image or a scene that would not fit, with the figures (so a run fails in a second with a
// reason, not after minutes with "out of memory" or the kernel's OOM killer).
#pragma once

#include <cstdint>
#include <string>

namespace rt {

struct MemoryLimit {
  // What sets the limit: the machine's memory, the address-space or data limit (ulimit -v, -d), or
  // the memory controller of the process's cgroup (a container's or a batch job's limit).
  enum class Source { machine, address_space, data_segment, cgroup };
  std::uint64_t bytes;
  Source source;

  // "this machine has 23.4 GiB", "this process may use 4.0 GiB (ulimit -v)", ...
  std::string describe() const;
};

// The smallest of: physical memory, RLIMIT_AS, RLIMIT_DATA, and the cgroup's memory.max (v2) or
// memory.limit_in_bytes (v1) of every cgroup from the process's own up to the root.
MemoryLimit memory_limit();
// The tightest memory limit of the cgroups that `cgroup_file` (in the format of /proc/self/cgroup,
// v1 or v2) names under `cgroup_root` (/sys/fs/cgroup): each group's own and its parents'. No limit
// is UINT64_MAX.
std::uint64_t cgroup_memory_limit(const std::string& cgroup_file, const std::string& cgroup_root);
// The machine's physical memory in bytes (sysconf).
std::uint64_t physical_memory_bytes();

// "44.7 GiB", "512 bytes".
std::string binary_size(double bytes);

// Refuses an image of more than 2^31 - 1 pixels or one whose memory (kBytesPerPixel) exceeds
// `limit`. Throws InputError "OUT: a WxH image needs ..., and this machine has ...".
// kBytesPerPixel is what a render of any stage holds per pixel at its peak: the sample sums and
// counts (16 bytes), their copy with the non-finite pixels blackened (16), the mean image (12) and
// the encoded file. Measured as peak resident memory (/usr/bin/time, the Cornell box at 1024^2
// less at 256^2, stages 1-5 alike): 56 bytes a pixel for a PNG or PFM, 78 for an EXR.
inline constexpr std::uint64_t kBytesPerPixel = 80;
void check_image_fits(const std::string& out, int width, int height, const MemoryLimit& limit);

// What a placed triangle costs at most in any stage: the world copy of its mesh, its corners and
// ids in the flat primitive list, the BVH builder's record and the tree. Measured with
// /usr/bin/time on assets/scenes/bunnies.json (1.1 M triangles): peak resident memory 180 bytes
// per triangle for stage 3's binary SAH tree, 200 for its 4-wide tree, 27 for stage 2.
inline constexpr std::uint64_t kBytesPerTriangle = 256;
// What a render holds besides its triangles, for check_scene_fits: its bytes, and what they are in
// words ("the image", "the image with sppm's state, 272 bytes a pixel, and ...").
struct OtherMemory {
  double bytes;
  std::string what;
};
// Refuses a scene whose `triangles` (common/scene.h, triangle_count) at kBytesPerTriangle, plus
// `other`, exceed `limit`. Throws InputError "SCENE: the render needs about ... (N triangles at 256
// bytes each ..., and WHAT), and this machine has ...".
void check_scene_fits(const std::string& scene, std::uint64_t triangles, const OtherMemory& other,
                      const MemoryLimit& limit);

}  // namespace rt
