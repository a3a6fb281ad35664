// A glTF's colour: per-corner TEXCOORD_n and COLOR_0, materials (baseColorFactor,
// baseColorTexture with its sampler and KHR_texture_transform) and their images. What cannot be
// used (an image missing, not PNG/JPEG, malformed) becomes a note, never a refusal: the net is
// still made, without that texture.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/errors.h"
#include "core/io/image.h"
#include "core/io/internal/gltf_colour.h"
#include "core/io/internal/load_formats.h"

namespace papernet::detail {

double gltf_component(const unsigned char* p, int type, bool normalized) {
  auto get = [p](auto v) {
    std::memcpy(&v, p, sizeof v);
    return v;
  };
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return get(float{});
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return normalized ? std::max(get(std::int8_t{}) / 127.0, -1.0) : get(std::int8_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? get(std::uint8_t{}) / 255.0 : get(std::uint8_t{});
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return normalized ? std::max(get(std::int16_t{}) / 32767.0, -1.0) : get(std::int16_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return normalized ? get(std::uint16_t{}) / 65535.0 : get(std::uint16_t{});
  }
  return std::nan("");
}

namespace {

/// An accessor of 2 to 4 float / unsigned normalized components, checked against its buffer,
/// as `count` rows of `width` doubles (the missing fourth colour component is 1). Empty when the
/// accessor is unusable: colour data are never a reason to refuse a mesh.
std::vector<double> read_floats(const tinygltf::Model& model, int index, std::size_t count,
                                int width) {
  if (index < 0 || std::size_t(index) >= model.accessors.size()) return {};
  const tinygltf::Accessor& a = model.accessors[index];
  const int n = a.type == TINYGLTF_TYPE_VEC2   ? 2
                : a.type == TINYGLTF_TYPE_VEC3 ? 3
                : a.type == TINYGLTF_TYPE_VEC4 ? 4
                                               : 0;
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  if (n == 0 || n > width || size <= 0 || size > 4 || a.sparse.isSparse || a.count < count)
    return {};
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized) return {};
  if (a.bufferView < 0 || std::size_t(a.bufferView) >= model.bufferViews.size()) return {};
  const tinygltf::BufferView& bv = model.bufferViews[a.bufferView];
  if (bv.buffer < 0 || std::size_t(bv.buffer) >= model.buffers.size()) return {};
  const auto& buffer = model.buffers[bv.buffer].data;
  const std::size_t element = std::size_t(n) * std::size_t(size);
  const std::size_t stride = bv.byteStride ? bv.byteStride : element;
  if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset ||
      stride < element || count == 0)
    return {};
  const std::uint64_t need =
      std::uint64_t{a.byteOffset} + element + std::uint64_t{stride} * (std::uint64_t{count} - 1);
  if (need > bv.byteLength) return {};
  const unsigned char* data = buffer.data() + bv.byteOffset + a.byteOffset;
  std::vector<double> out(count * std::size_t(width), 1.0);
  for (std::size_t i = 0; i < count; ++i)
    for (int k = 0; k < n; ++k)
      out[i * std::size_t(width) + std::size_t(k)] =
          gltf_component(data + i * stride + std::size_t(k * size), a.componentType, a.normalized);
  return out;
}

double number(const tinygltf::Value& v, double fallback) {
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

/// KHR_texture_transform of a texture reference: offset, rotation, scale as an affine map of
/// (u, v), and the texture coordinate set it overrides (or -1).
struct UvTransform {
  double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;  // u' = a u + c v + e, v' = b u + d v + f
  int tex_coord = -1;
};

UvTransform uv_transform(const tinygltf::TextureInfo& info) {
  UvTransform t;
  const auto it = info.extensions.find("KHR_texture_transform");
  if (it == info.extensions.end() || !it->second.IsObject()) return t;
  const tinygltf::Value& x = it->second;
  double ox = 0, oy = 0, sx = 1, sy = 1, r = 0;
  if (x.Has("offset") && x.Get("offset").ArrayLen() == 2) {
    ox = number(x.Get("offset").Get(0), 0);
    oy = number(x.Get("offset").Get(1), 0);
  }
  if (x.Has("scale") && x.Get("scale").ArrayLen() == 2) {
    sx = number(x.Get("scale").Get(0), 1);
    sy = number(x.Get("scale").Get(1), 1);
  }
  if (x.Has("rotation")) r = number(x.Get("rotation"), 0);
  if (x.Has("texCoord")) t.tex_coord = int(number(x.Get("texCoord"), -1));
  // The extension's matrix: translation * rotation * scale, rotation [cos sin; -sin cos].
  const double cs = std::cos(r), sn = std::sin(r);
  t.a = cs * sx;
  t.b = -sn * sx;
  t.c = sn * sy;
  t.d = cs * sy;
  t.e = ox;
  t.f = oy;
  return t;
}

const tinygltf::Material* material_of(const tinygltf::Model& model,
                                      const tinygltf::Primitive& prim) {
  if (prim.material < 0 || std::size_t(prim.material) >= model.materials.size()) return nullptr;
  return &model.materials[prim.material];
}

}  // namespace

void read_gltf_materials(const tinygltf::Model& model, const GltfImageBytes& images,
                         const LoadOptions& options, MeshColour& colour,
                         std::vector<std::string>& notes) {
  // (image, sampler) -> our texture (-1 when unusable): glTF textures that repeat an image with
  // the same sampler are one texture.
  std::map<std::pair<int, int>, int> texture_of;
  const auto texture = [&](int index) -> int {
    if (index < 0 || std::size_t(index) >= model.textures.size()) return -1;
    const tinygltf::Texture& t = model.textures[index];
    const auto known = texture_of.find({t.source, t.sampler});
    if (known != texture_of.end()) return known->second;
    int& ours = texture_of[{t.source, t.sampler}] = -1;
    const std::string which = std::string("texture ") + std::to_string(index);
    if (t.source < 0 || std::size_t(t.source) >= model.images.size()) {
      notes.push_back(which + " names no image; its material is printed without it");
      return -1;
    }
    const tinygltf::Image& image = model.images[t.source];
    std::string bytes;
    const auto found = images.find(t.source);
    if (image.bufferView >= 0) {
      const auto view = std::size_t(image.bufferView);
      const tinygltf::BufferView* bv =
          view < model.bufferViews.size() ? &model.bufferViews[view] : nullptr;
      const std::vector<unsigned char>* buffer =
          bv && bv->buffer >= 0 && std::size_t(bv->buffer) < model.buffers.size()
              ? &model.buffers[std::size_t(bv->buffer)].data
              : nullptr;
      if (!buffer || bv->byteOffset > buffer->size() ||
          bv->byteLength > buffer->size() - bv->byteOffset) {
        notes.push_back(which + "'s image lies in buffer view " + std::to_string(image.bufferView) +
                        ", which lies outside its buffer; its material is printed without it");
        return -1;
      }
      if (bv->byteLength > 0)
        bytes.assign(reinterpret_cast<const char*>(buffer->data()) + bv->byteOffset,
                     bv->byteLength);
    } else if (found != images.end()) {
      bytes = found->second;
    } else if (image.uri.starts_with("data:")) {
      // A data URI of a type tinygltf does not decode itself (image/ktx2, image/webp, ...).
      const std::size_t comma = image.uri.find(";base64,");
      if (comma != std::string::npos) bytes = decode_base64(image.uri.substr(comma + 8));
    } else if (!image.uri.empty()) {
      const std::string uri = url_decode(image.uri);
      auto file = options.external_files.find(uri);
      if (file == options.external_files.end() && uri.starts_with("./"))
        file = options.external_files.find(uri.substr(2));
      if (file == options.external_files.end()) {
        notes.push_back("texture image '" + uri +
                        "' was not supplied with the model; its material is printed without it");
        return -1;
      }
      bytes = file->second;
    }
    Texture out;
    std::string name = image.name.empty() ? image.uri : image.name;
    if (name.empty() || name.starts_with("data:"))
      name = std::string("image ") + std::to_string(t.source);
    if (!make_texture(std::move(name), std::move(bytes), options, "its material", out, notes))
      return -1;
    if (t.sampler >= 0 && std::size_t(t.sampler) < model.samplers.size()) {
      const tinygltf::Sampler& s = model.samplers[t.sampler];
      out.sampler = {s.wrapS, s.wrapT, std::max(s.magFilter, 0), std::max(s.minFilter, 0)};
    }
    ours = int(colour.textures.size());
    colour.textures.push_back(std::move(out));
    return ours;
  };
  for (const tinygltf::Material& m : model.materials) {
    Material out;
    out.name = m.name;
    const auto& factor = m.pbrMetallicRoughness.baseColorFactor;
    for (std::size_t k = 0; k < 4 && k < factor.size(); ++k) out.base_color[k] = factor[k];
    out.texture = texture(m.pbrMetallicRoughness.baseColorTexture.index);
    if (m.alphaMode == "MASK") out.alpha_mode = AlphaMode::Mask;
    if (m.alphaMode == "BLEND") out.alpha_mode = AlphaMode::Blend;
    if (std::isfinite(m.alphaCutoff)) out.alpha_cutoff = m.alphaCutoff;
    colour.materials.push_back(std::move(out));
  }
}

MeshColour read_gltf_primitive_colour(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                      const std::vector<std::array<std::uint32_t, 3>>& faces,
                                      std::size_t vertex_count) {
  MeshColour out;
  const tinygltf::Material* material = material_of(model, prim);
  if (material) out.face_materials.assign(faces.size(), prim.material);
  // The set the base colour texture samples (texCoord, or the transform's override).
  int set = 0;
  UvTransform transform;
  if (material) {
    const tinygltf::TextureInfo& info = material->pbrMetallicRoughness.baseColorTexture;
    transform = uv_transform(info);
    set = transform.tex_coord >= 0 ? transform.tex_coord : info.texCoord;
  }
  const auto uv = prim.attributes.find(std::string("TEXCOORD_") + std::to_string(set));
  if (uv != prim.attributes.end()) {
    const std::vector<double> v = read_floats(model, uv->second, vertex_count, 2);
    if (!v.empty()) {
      out.uvs.resize(faces.size());
      for (std::size_t f = 0; f < faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
          const double u = v[2 * faces[f][k]], w = v[2 * faces[f][k] + 1];
          const UvTransform& t = transform;
          out.uvs[f][k] = {t.a * u + t.c * w + t.e, t.b * u + t.d * w + t.f};
        }
    }
  }
  const auto colour = prim.attributes.find("COLOR_0");
  if (colour != prim.attributes.end()) {
    const std::vector<double> v = read_floats(model, colour->second, vertex_count, 4);
    if (!v.empty()) {
      out.colours.resize(faces.size());
      for (std::size_t f = 0; f < faces.size(); ++f)
        for (int k = 0; k < 3; ++k)
          for (int i = 0; i < 4; ++i) out.colours[f][k][i] = v[4 * faces[f][k] + i];
    }
  }
  return out;
}

}  // namespace papernet::detail
