// libFuzzer target: the OBJ reader on arbitrary bytes. A mesh either loads or is refused with
// InputError; anything else (another exception, a crash, a leak, a sanitizer report) is a bug.
#include "common/error.h"
#include "common/obj_loader.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    rt::parse_obj(std::string(reinterpret_cast<const char*>(data), size), "fuzz.obj");
  } catch (const rt::InputError&) {
  }
  return 0;
}
