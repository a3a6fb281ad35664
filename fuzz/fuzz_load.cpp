// One loader (PAPERNET_FUZZ_FORMAT, a MeshFormat enumerator) fed arbitrary bytes, then
// validation: built once per format (fuzz/CMakeLists.txt).
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_pipeline.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  papernet::fuzz::load_and_validate(std::string_view(reinterpret_cast<const char*>(data), size),
                                    papernet::MeshFormat::PAPERNET_FUZZ_FORMAT);
  return 0;
}
