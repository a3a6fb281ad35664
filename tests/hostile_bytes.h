#pragma once
// Byte-level builders for hand-made hostile mesh files, shared by the loader and HTTP tests.

#include <cstdint>
#include <string>

namespace papernet::test {

/// The 11-byte header of a Draco 2.2 file: "DRACO", version, encoder type (0 point cloud,
/// 1 triangle mesh), method (0 sequential, 1 edgebreaker) and empty flags.
inline std::string draco_header(int type, int method) {
  return std::string("DRACO") + char(2) + char(2) + char(type) + char(method) + '\0' + '\0';
}

/// `v` as Draco's little-endian base-128 varint.
inline std::string varint(std::uint32_t v) {
  std::string s;
  do {
    s += char((v & 0x7f) | (v >= 0x80 ? 0x80 : 0));
    v >>= 7;
  } while (v);
  return s;
}

}  // namespace papernet::test
