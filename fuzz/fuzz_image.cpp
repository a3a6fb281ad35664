// Texture image decoding (core/io/image.h: PNG through libpng, JPEG through libjpeg-turbo) fed
// arbitrary bytes, under a pixel limit like the loader's (smaller, so that the fuzzer's memory
// limit is never the one that stops a large declared size).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/errors.h"
#include "core/io/image.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    papernet::image_size(bytes, std::uint64_t{16} << 20);
    papernet::decode_image(bytes, std::uint64_t{16} << 20);
  } catch (const papernet::IOException&) {
  }
  return 0;
}
