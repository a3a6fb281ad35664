// A .gltf with the external buffer files a multipart upload brings along. The input is the
// glTF JSON, then for each file "\n--papernet-file:<name>\n" and its bytes (fuzz/make_corpus.sh
// writes seeds that way), so names and contents are both fuzzed, as a client controls both.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "fuzz/fuzz_pipeline.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static constexpr std::string_view marker = "\n--papernet-file:";
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  std::size_t end = input.find(marker);
  const std::string_view json = input.substr(0, end);
  std::map<std::string, std::string> files;
  while (end != std::string_view::npos) {
    const std::size_t name_start = end + marker.size();
    const std::size_t name_end = input.find('\n', name_start);
    if (name_end == std::string_view::npos) break;
    end = input.find(marker, name_end + 1);
    const std::string_view content =
        input.substr(name_end + 1, end == std::string_view::npos ? end : end - (name_end + 1));
    files[std::string(input.substr(name_start, name_end - name_start))] = std::string(content);
  }
  papernet::fuzz::load_and_validate(json, papernet::MeshFormat::Gltf, files);
  return 0;
}
