// libFuzzer target: merge (common/batch_merge.h) on up to 16 batch descriptions, separated by
// lines "---", beside a valid pair of batch images: every description that reads is merged, and
// the merge succeeds or is refused with InputError (or UsageError). Anything else is a bug. Run by
// tests/fuzz/run.sh.
#include "batch_inputs.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path folder = rt::fuzzing::fuzz_folder();
  rt::fuzzing::merge_batch_texts(folder, std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
