// libFuzzer target: the scene loader on arbitrary bytes. A scene either loads or is refused with
// InputError (one line naming the file and the problem); any other exception, a crash, a leak or a
// sanitizer report is a bug. Built by the preset "fuzz" (clang); run by tests/fuzz/run.sh.
#include "common/error.h"
#include "common/scene.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    rt::parse_scene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
  } catch (const rt::InputError&) {
  }
  return 0;
}
