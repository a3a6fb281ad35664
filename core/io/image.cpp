// PNG and JPEG decoding through the Debian libraries every image tool uses: libpng (its
// simplified png_image API) and libjpeg-turbo. Sizes are read from the header and checked
// against the pixel limit before any pixel buffer is allocated.
#include "core/io/image.h"

#include <jpeglib.h>
#include <png.h>

#include <csetjmp>
#include <cstring>

#include "core/errors.h"

namespace papernet {
namespace {

void check_pixels(std::uint64_t width, std::uint64_t height, std::uint64_t max_pixels) {
  if (width == 0 || height == 0) throw IOException("image: zero width or height");
  if (width * height > max_pixels)
    throw LimitExceededException(LimitExceededException::Limit::Pixels,
                                 std::string("a texture image of ") + std::to_string(width) +
                                     " x " + std::to_string(height) +
                                     " pixels is larger than the limit of " +
                                     std::to_string(max_pixels) + " pixels");
}

Image png(std::string_view bytes, std::uint64_t max_pixels, bool pixels) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) {
    std::string message = "png: ";
    message += image.message;
    png_image_free(&image);
    throw IOException(message);
  }
  Image out;
  out.width = int(image.width);
  out.height = int(image.height);
  try {
    check_pixels(image.width, image.height, max_pixels);
  } catch (...) {
    png_image_free(&image);
    throw;
  }
  if (!pixels) {
    png_image_free(&image);
    return out;
  }
  image.format = PNG_FORMAT_RGBA;
  out.rgba.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgba.data(), 0, nullptr)) {
    std::string message = "png: ";
    message += image.message;
    png_image_free(&image);
    throw IOException(message);
  }
  return out;
}

// libjpeg reports errors through a callback that must not return: it jumps back here.
struct JpegError {
  jpeg_error_mgr mgr;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void jpeg_fail(j_common_ptr info) {
  JpegError* e = reinterpret_cast<JpegError*>(info->err);
  (*info->err->format_message)(info, e->message);
  std::longjmp(e->jump, 1);
}

// Warnings (corrupt but decodable data) are counted, not printed.
void jpeg_quiet(j_common_ptr info, int level) {
  if (level < 0) ++info->err->num_warnings;
}

// Decodes into `out` (its size already set when `pixels`); returns an error message or "".
// No C++ object with a destructor lives between setjmp and longjmp.
std::string jpeg(std::string_view bytes, std::uint64_t max_pixels, bool pixels, Image& out,
                 std::uint64_t& declared) {
  jpeg_decompress_struct info;
  JpegError error;
  info.err = jpeg_std_error(&error.mgr);
  error.mgr.error_exit = jpeg_fail;
  error.mgr.emit_message = jpeg_quiet;
  error.message[0] = 0;
  if (setjmp(error.jump)) {
    jpeg_destroy_decompress(&info);
    return error.message[0] ? error.message : "malformed data";
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, reinterpret_cast<const unsigned char*>(bytes.data()),
               static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  out.width = int(info.image_width);
  out.height = int(info.image_height);
  declared = std::uint64_t{info.image_width} * info.image_height;
  if (!pixels || declared == 0 || declared > max_pixels) {
    jpeg_destroy_decompress(&info);
    return "";
  }
  info.out_color_space = JCS_EXT_RGBA;
  jpeg_start_decompress(&info);
  unsigned char* data = out.rgba.data();
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = data + std::size_t{info.output_scanline} * info.output_width * 4;
    jpeg_read_scanlines(&info, &row, 1);
  }
  // A stream cut short decodes with libjpeg's warning (grey rows); that counts as truncated.
  const bool truncated = info.err->num_warnings > 0;
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return truncated ? "the data is truncated or corrupt" : "";
}

Image decode(std::string_view bytes, std::uint64_t max_pixels, bool pixels) {
  switch (sniff_image(bytes)) {
    case ImageFormat::Png:
      return png(bytes, max_pixels, pixels);
    case ImageFormat::Jpeg: {
      Image out;
      std::uint64_t declared = 0;
      std::string error = jpeg(bytes, max_pixels, false, out, declared);
      if (!error.empty()) throw IOException("jpeg: " + error);
      check_pixels(std::uint64_t(out.width), std::uint64_t(out.height), max_pixels);
      if (!pixels) return out;
      out.rgba.resize(std::size_t(declared) * 4);
      error = jpeg(bytes, max_pixels, true, out, declared);
      if (!error.empty()) throw IOException("jpeg: " + error);
      return out;
    }
    case ImageFormat::Unknown:
      throw IOException("image: not a PNG or JPEG");
    default:
      throw IOException(std::string("image: ") + image_mime_type(sniff_image(bytes)) +
                        " is not decoded (PNG and JPEG are)");
  }
}

}  // namespace

ImageFormat sniff_image(std::string_view b) {
  if (b.starts_with("\x89PNG\r\n\x1a\n")) return ImageFormat::Png;
  if (b.starts_with("\xff\xd8\xff")) return ImageFormat::Jpeg;
  if (b.starts_with("\xabKTX 20\xbb\r\n\x1a\n")) return ImageFormat::Ktx2;
  if (b.size() >= 12 && b.starts_with("RIFF") && b.substr(8, 4) == "WEBP") return ImageFormat::Webp;
  if (b.starts_with("GIF8")) return ImageFormat::Gif;
  if (b.starts_with("BM")) return ImageFormat::Bmp;
  return ImageFormat::Unknown;
}

std::string image_mime_type(ImageFormat format) {
  switch (format) {
    case ImageFormat::Png:
      return "image/png";
    case ImageFormat::Jpeg:
      return "image/jpeg";
    case ImageFormat::Ktx2:
      return "image/ktx2";
    case ImageFormat::Webp:
      return "image/webp";
    case ImageFormat::Gif:
      return "image/gif";
    case ImageFormat::Bmp:
      return "image/bmp";
    case ImageFormat::Unknown:
      break;
  }
  return "";
}

Image image_size(std::string_view bytes, std::uint64_t max_pixels) {
  return decode(bytes, max_pixels, false);
}

Image decode_image(std::string_view bytes, std::uint64_t max_pixels) {
  return decode(bytes, max_pixels, true);
}

}  // namespace papernet
