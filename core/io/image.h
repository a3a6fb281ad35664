#pragma once
// Decoding the images a model's materials use (PNG through libpng, JPEG through libjpeg-turbo).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace papernet {

/// Decoded-pixel limit of a texture by default: 64 megapixels (256 MB as RGBA).
constexpr std::uint64_t kDefaultMaxImagePixels = std::uint64_t{64} << 20;

/// The image formats a texture can have: what we decode, and what we name but do not.
enum class ImageFormat { Unknown, Png, Jpeg, Ktx2, Webp, Gif, Bmp };

/// Format from the first bytes (the signature), Unknown when none fits.
ImageFormat sniff_image(std::string_view bytes);

/// "image/png", "image/jpeg", "image/ktx2", "image/webp", ... ("" for Unknown).
std::string image_mime_type(ImageFormat format);

/// An image as 8-bit RGBA rows, top row first.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  ///< width * height * 4 bytes
};

/// Width and height of a PNG or JPEG from its header, checked against `max_pixels` before
/// anything is decoded. \throw IOException (unsupported format, malformed header),
/// LimitExceededException (more pixels than `max_pixels`).
Image image_size(std::string_view bytes, std::uint64_t max_pixels = kDefaultMaxImagePixels);

/// Decodes a PNG or JPEG, refusing more than `max_pixels` pixels before allocating them.
/// \throw IOException naming the fault (unsupported format, truncated or malformed data),
///        LimitExceededException over the limit.
Image decode_image(std::string_view bytes, std::uint64_t max_pixels = kDefaultMaxImagePixels);

/// `bytes` in base64 (RFC 4648), for data URIs: tinygltf's encoder.
std::string encode_base64(std::string_view bytes);

}  // namespace papernet
