// libFuzzer target: the sample batch description reader (common/sample_batch.h) on arbitrary
// bytes, beside a valid pair of batch images. A description is read or refused with InputError;
// any other exception, a crash, a leak, a hang or a sanitizer report is a bug. Run by
// tests/fuzz/run.sh.
#include "batch_inputs.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path folder = rt::fuzzing::fuzz_folder();
  try {
    rt::fuzzing::read_batch_text(folder, std::string_view(reinterpret_cast<const char*>(data), size), "input.json");
  } catch (const rt::InputError&) {
  }
  return 0;
}
