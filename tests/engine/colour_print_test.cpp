// The printed colour, checked as a person would see it (issue "Colour kits"): each PDF page is
// rendered by poppler (pdftoppm) at the print's dpi, and every face placed on it (by the net
// JSON's `print` placements, not by the print's own drawing) whose inscribed circle is at least
// 3 px is sampled at interior points and compared with the model's own colour at the same
// barycentric point: its texture (decoded here, sampled bilinearly), times the material's
// factor and the vertex colours (linear, so turned into sRGB as the page is).
#include <cairo.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "api/net_json.h"
#include "core/io/image.h"
#include "core/io/internal/load_formats.h"
#include "core/io/load.h"
#include "core/unfold/net_check.h"
#include "engine/pipeline.h"
#include "print/colour.h"
#include "tests/support/job_input.h"
#include "tests/support/paths.h"
#include "tests/support/sanitized.h"
#include "tests/support/svg.h"

namespace papernet::test {
namespace {

constexpr double kDpi = 100;
// A face matches when the median over its sample points of the largest channel difference is
// at most this (0..1): 0.1 is 26 of 255 levels, room for filtering, antialiasing and JPEG.
constexpr double kTolerance = 0.1;

struct Raster {
  int width = 0, height = 0;
  std::string rgb;
  std::array<double, 3> at(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    return {static_cast<unsigned char>(rgb[i]) / 255.0,
            static_cast<unsigned char>(rgb[i + 1]) / 255.0,
            static_cast<unsigned char>(rgb[i + 2]) / 255.0};
  }
};

bool has_pdftoppm() { return std::system("command -v pdftoppm >/dev/null 2>&1") == 0; }

// Page `page` (1-based) of the PDF at `path`, rendered by pdftoppm as PPM (P6).
Raster render(const std::string& path, int page) {
  const std::string command = "pdftoppm -r " + std::to_string(static_cast<int>(kDpi)) + " -f " +
                              std::to_string(page) + " -l " + std::to_string(page) + " " + path;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string out;
  char buf[65536];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe.get())) out.append(buf, n);
  Raster r;
  int maxval = 0, consumed = 0;
  if (std::sscanf(out.c_str(), "P6 %d %d %d%n", &r.width, &r.height, &maxval, &consumed) != 3)
    return r;
  r.rgb = out.substr(static_cast<std::size_t>(consumed) + 1);
  if (r.rgb.size() < static_cast<std::size_t>(r.width) * r.height * 3) r.width = r.height = 0;
  return r;
}

double srgb(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

// Bilinear sample at (u, v), texel centres at half-integers: red, green, blue, alpha. Repeating,
// or with `clamp` clamped to [0, 1] (texel indices clamped at the edges).
std::array<double, 4> sample_rgba(const Image& image, double u, double v, bool clamp = false) {
  if (clamp) u = std::clamp(u, 0.0, 1.0), v = std::clamp(v, 0.0, 1.0);
  const double x = u * image.width - 0.5, y = v * image.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  auto index = [&](double t, int n) {
    return clamp ? std::clamp(static_cast<int>(t), 0, n - 1) : ((static_cast<int>(t) % n) + n) % n;
  };
  auto texel = [&](double tx, double ty, int c) {
    const int ix = index(tx, image.width), iy = index(ty, image.height);
    return image.rgba[(static_cast<std::size_t>(iy) * image.width + ix) * 4 + c] / 255.0;
  };
  std::array<double, 4> out{};
  for (int c = 0; c < 4; ++c)
    out[c] = (1 - (x - fx)) * (1 - (y - fy)) * texel(fx, fy, c) +
             (x - fx) * (1 - (y - fy)) * texel(fx + 1, fy, c) +
             (1 - (x - fx)) * (y - fy) * texel(fx, fy + 1, c) +
             (x - fx) * (y - fy) * texel(fx + 1, fy + 1, c);
  return out;
}

std::array<double, 3> sample(const Image& image, double u, double v) {
  const auto s = sample_rgba(image, u, v);
  return {s[0], s[1], s[2]};
}

// The model's colour of face f at barycentric w: texture x factor x vertex colour (sRGB), on
// white paper by the material's alpha (glTF alphaMode: opaque ignores it, mask cuts it at the
// cutoff, blend mixes).
std::array<double, 3> model_colour(const NetDocument& doc, const std::vector<Image>& textures,
                                   std::size_t f, const std::array<double, 3>& w) {
  const int material = f < doc.colour.face_materials.size() ? doc.colour.face_materials[f] : -1;
  std::array<double, 3> c{1, 1, 1};
  double alpha = 1;
  if (material >= 0) {
    const Material& m = doc.colour.materials[material];
    for (int i = 0; i < 3; ++i) c[i] = srgb(m.base_color[i]);
    alpha = m.base_color[3];
    if (m.texture >= 0 && f < doc.colour.uvs.size()) {
      const auto& uv = doc.colour.uvs[f];
      const auto s =
          sample_rgba(textures[m.texture], w[0] * uv[0][0] + w[1] * uv[1][0] + w[2] * uv[2][0],
                      w[0] * uv[0][1] + w[1] * uv[1][1] + w[2] * uv[2][1]);
      for (int i = 0; i < 3; ++i) c[i] *= s[i];
      alpha *= s[3];
    }
    if (m.alpha_mode == AlphaMode::Opaque) alpha = 1;
    if (m.alpha_mode == AlphaMode::Mask) alpha = alpha >= m.alpha_cutoff ? 1 : 0;
  }
  if (f < doc.colour.colours.size()) {  // NaN: the face has none
    const auto& vc = doc.colour.colours[f];
    for (int i = 0; i < 3; ++i)
      if (std::isfinite(vc[0][i]) && std::isfinite(vc[1][i]) && std::isfinite(vc[2][i]))
        c[i] *= srgb(w[0] * vc[0][i] + w[1] * vc[1][i] + w[2] * vc[2][i]);
  }
  for (double& x : c) x = x * alpha + (1 - alpha);
  return c;
}

// The colour face f of the printed net should show at barycentric point w.
using Expected = std::function<std::array<double, 3>(const NetDocument& doc, std::size_t f,
                                                     const std::array<double, 3>& w)>;

// Face f's corners on its page in pixels at kDpi, by its piece's placement (net JSON `print`).
std::array<Vec2, 3> page_pixels(const NetDocument& doc, std::size_t f) {
  const auto& t = doc.print->placements.at(doc.piece[f]).transform;
  std::array<Vec2, 3> p;
  for (int k = 0; k < 3; ++k) {
    const Vec2 q = doc.net.points[f][k];
    p[k] = (kDpi / 25.4) * Vec2{t[0] * q.x + t[2] * q.y + t[4], t[1] * q.x + t[3] * q.y + t[5]};
  }
  return p;
}

double inradius(const std::array<Vec2, 3>& p) {
  const double perimeter = norm(p[1] - p[0]) + norm(p[2] - p[1]) + norm(p[0] - p[2]);
  return std::abs(cross(p[1] - p[0], p[2] - p[0])) / perimeter;
}

double difference(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

// Interior sample points of a face (barycentric), and the median of their errors: a piece's
// number (line art over the colour, several millimetres tall) may cover a few of them.
constexpr std::array<std::array<double, 3>, 7> kSamples{{{1.0 / 3, 1.0 / 3, 1.0 / 3},
                                                         {0.5, 0.25, 0.25},
                                                         {0.25, 0.5, 0.25},
                                                         {0.25, 0.25, 0.5},
                                                         {0.2, 0.4, 0.4},
                                                         {0.4, 0.2, 0.4},
                                                         {0.4, 0.4, 0.2}}};

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

struct Check {
  std::size_t faces = 0;    ///< faces large enough to sample
  std::size_t matched = 0;  ///< of those, within kTolerance
  double worst = 0;
  /// Cut edges of 4 mm or more, both faces on the page, with paper printed on at least one side
  /// (a tab; an edge with a glue strip instead has none, unless another face lies there).
  std::size_t cut_edges = 0;
  std::size_t tabbed = 0;           ///< of those, one side shows the other face's colour (its tab)
  std::size_t strips = 0;           ///< glue strips printed
  std::vector<NetRepair> warnings;  ///< the result's
};

// Glue tabs: for each cut edge of 4 mm or more, the point 0.8 mm outside each of its two faces'
// sides at the edge's middle lies on the tab when that side has it (tabs are at least 2 mm
// tall). A tab shows the face it glues under as if folded out about the edge: that face's colour
// at the same point of its own plane (0.8 mm from the edge, at its middle). Counts the edges
// where one side shows it, of those where one side is printed at all.
void check_tabs(const NetDocument& doc, const Expected& model, const Raster& raster, int page,
                Check& check) {
  const double px = kDpi / 25.4, mm = doc.print->mm_per_unit;
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> sides;  // edge -> (face, k)
  for (std::size_t f = 0; f < doc.mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = doc.mesh.faces[f][k], b = doc.mesh.faces[f][(k + 1) % 3];
      sides[{std::min(a, b), std::max(a, b)}].push_back({static_cast<int>(f), k});
    }
  auto page_point = [&](int f, int k) { return page_pixels(doc, f)[k]; };
  for (const auto& [edge, faces] : sides) {
    if (faces.size() != 2) continue;
    const auto [f, kf] = faces[0];
    const auto [g, kg] = faces[1];
    if (doc.print->placements.at(doc.piece[f]).page != page ||
        doc.print->placements.at(doc.piece[g]).page != page)
      continue;
    const Vec2 fa = page_point(f, kf), fb = page_point(f, (kf + 1) % 3);
    const Vec2 ga = page_point(g, (kg + 1) % 3), gb = page_point(g, kg);   // the same vertices
    if (norm(fa - ga) < 0.05 * px && norm(fb - gb) < 0.05 * px) continue;  // a fold
    if (norm(fb - fa) < 4 * px) continue;
    bool shown = false, present = false;
    // Side of face `own` (placed at own_a, own_b, apex `own_c`); `under` glues there.
    auto side = [&](int own, int k_own, int under, int k_under) {
      const Vec2 a = page_point(own, k_own), b = page_point(own, (k_own + 1) % 3);
      const Vec2 apex = page_point(own, (k_own + 2) % 3);
      const Vec2 along = (1 / norm(b - a)) * (b - a);
      Vec2 out{-along.y, along.x};
      if (dot(out, apex - a) > 0) out = -1 * out;
      const auto& tri = doc.mesh.faces[under];
      const Vec3 u0 = doc.mesh.vertices[tri[k_under]],
                 u1 = doc.mesh.vertices[tri[(k_under + 1) % 3]];
      const Vec3 u2 = doc.mesh.vertices[tri[(k_under + 2) % 3]];
      const Vec3 e = u1 - u0;
      Vec3 inward = (u2 - u0) - (dot(u2 - u0, e) / dot(e, e)) * e;
      inward = (1 / norm(inward)) * inward;
      const Vec3 v0 = doc.mesh.vertices[tri[0]], v1 = doc.mesh.vertices[tri[1]];
      const Vec3 v2 = doc.mesh.vertices[tri[2]];
      const Vec3 n = cross(v1 - v0, v2 - v0);
      // Three points along the edge (a line of the drawing may cross one), each 0.8 mm out on
      // the page and 0.8 mm into the under face's plane in 3D; own's a is under's u1.
      for (double t : {0.5, 0.35, 0.65}) {
        const Vec2 at = a + t * (b - a) + (0.8 * px) * out;
        const Vec3 q = u1 + t * (u0 - u1) + (0.8 / mm) * inward;
        const double w1 = dot(cross(q - v0, v2 - v0), n) / dot(n, n);
        const double w2 = dot(cross(v1 - v0, q - v0), n) / dot(n, n);
        const auto want = model(doc, under, {1 - w1 - w2, w1, w2});
        const int x = static_cast<int>(at.x), y = static_cast<int>(at.y);
        if (x < 0 || y < 0 || x >= raster.width || y >= raster.height) continue;
        const auto printed = raster.at(x, y);
        // Paper, or a glue strip's pale yellow (strips lie beside their edges, uncoloured).
        const bool strip = difference(printed, {0xfb / 255.0, 0xf1 / 255.0, 0xd3 / 255.0}) < 0.03;
        if (t == 0.5)
          present = present || (std::min({printed[0], printed[1], printed[2]}) < 0.95 && !strip);
        shown = shown || difference(printed, want) <= kTolerance;
      }
    };
    side(f, kf, g, kg);
    side(g, kg, f, kf);
    check.cut_edges += present;
    check.tabbed += shown;
  }
}

// Prints `input` to PDF at `size_mm` with colour at `dpi` (kDpi unless given; rendered at kDpi)
// and compares every page with `expected` (by default the net JSON's own colour data:
// model_colour).
Check check_colour(const std::string& file, double size_mm, const JobInput& input,
                   Expected expected = nullptr,
                   std::function<bool(const NetDocument&, std::size_t)> sampled = nullptr,
                   double dpi = kDpi) {
  JobOptions options;
  options.strategy = Strategy::TU;
  options.detail = {DetailMode::Full, 0};
  options.size_mm = size_mm;
  options.dpi = dpi;
  options.layout = PageLayoutMode::Fit;
  options.labels = false;  // line art over the colour: numbers cover small faces' centres
  options.tab_room_budget = 2000;
  PipelineProgress quiet;
  const UnfoldOutcome out =
      run_pipeline(input, options, {}, {.svg_pages = true, .pdf = true}, quiet);
  const NetDocument& doc = out.net;
  EXPECT_TRUE(check_pieces(doc.mesh, doc.net, doc.piece).ok());
  Check check;
  if (!doc.print) {
    ADD_FAILURE() << file << ": no print placements";
    return check;
  }
  std::vector<Image> textures;
  for (const Texture& t : doc.colour.textures) textures.push_back(decode_image(t.bytes));
  if (!expected)
    expected = [&](const NetDocument& d, std::size_t f, const std::array<double, 3>& w) {
      return model_colour(d, textures, f, w);
    };
  const std::string path =
      (std::filesystem::temp_directory_path() /
       ("papernet_colour_" + std::filesystem::path(file).filename().string() + ".pdf"))
          .string();
  {
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), std::fclose);
    std::fwrite(out.documents.pdf.data(), 1, out.documents.pdf.size(), f.get());
  }
  for (int page = 0; page < doc.print->pages; ++page) {
    const Raster raster = render(path, page + 1);
    if (raster.width == 0) {
      ADD_FAILURE() << "pdftoppm could not render page " << page + 1 << " of " << path;
      continue;
    }
    // The pieces' numbers ("P3") as the page's SVG draws them, each within its box's
    // half-diagonal (a box of 0.6 em per character, 1 em high) of its centre, in pixels: samples
    // there are not compared; they may be under the number.
    std::vector<std::pair<Vec2, double>> numbers;
    if (static_cast<std::size_t>(page) < out.documents.svg_pages.size()) {
      const std::string& svg = out.documents.svg_pages[page];
      static const std::regex number(
          "<text x=\"([-0-9.]+)\" y=\"([-0-9.]+)\" font-size=\"([0-9.]+)\"[^>]*>(P[0-9]+)</text>");
      for (auto it = std::sregex_iterator(svg.begin(), svg.end(), number);
           it != std::sregex_iterator(); ++it) {
        const double size = std::stod((*it)[3]), chars = static_cast<double>((*it)[4].length());
        const Vec2 centre{std::stod((*it)[1]), std::stod((*it)[2]) - 0.35 * size};
        numbers.push_back({(kDpi / 25.4) * centre,
                           1.05 * (kDpi / 25.4) * size * std::sqrt(0.09 * chars * chars + 0.25)});
      }
    }
    const auto under_a_number = [&](Vec2 at) {
      return std::any_of(numbers.begin(), numbers.end(),
                         [&](const auto& n) { return norm(at - n.first) < n.second; });
    };
    for (std::size_t f = 0; f < doc.mesh.faces.size(); ++f) {
      const PiecePlacement& placed = doc.print->placements.at(doc.piece[f]);
      if (placed.page != page) continue;
      const std::array<Vec2, 3> p = page_pixels(doc, f);
      if (!(inradius(p) >= 3) || (sampled && !sampled(doc, f))) continue;
      std::vector<double> errors;
      for (const auto& w : kSamples) {
        const Vec2 at = w[0] * p[0] + w[1] * p[1] + w[2] * p[2];
        if (under_a_number(at)) continue;
        const int x = static_cast<int>(at.x), y = static_cast<int>(at.y);
        if (x < 0 || y < 0 || x >= raster.width || y >= raster.height) {
          errors.push_back(1);
          continue;
        }
        // The pixel at the sample or one beside it: a sample a fraction of a pixel from a
        // sharp edge in the texture (the letters of VertexColorTest's captions) falls on either
        // side of it depending on how the piece is turned on the page.
        const auto want = expected(doc, f, w);
        double error = 1;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            if (x + dx >= 0 && y + dy >= 0 && x + dx < raster.width && y + dy < raster.height)
              error = std::min(error, difference(raster.at(x + dx, y + dy), want));
        errors.push_back(error);
      }
      if (errors.empty()) continue;  // every sample under the piece's number
      const double error = median(errors);
      ++check.faces;
      check.matched += error <= kTolerance;
      check.worst = std::max(check.worst, error);
    }
    check_tabs(doc, expected, raster, page, check);
  }
  check.strips = out.print->strips;
  check.warnings = doc.warnings;
  std::filesystem::remove(path);
  return check;
}

class ColourPrint : public ::testing::TestWithParam<std::pair<const char*, double>> {};

INSTANTIATE_TEST_SUITE_P(
    Models, ColourPrint,
    ::testing::Values(std::pair{"Duck.glb", 150.0}, std::pair{"BoxTextured.glb", 80.0},
                      std::pair{"cubevc.glb", 80.0}, std::pair{"rgb_cube.gltf", 80.0},
                      std::pair{"VertexColorTest/VertexColorTest.gltf", 150.0}),
    [](const auto& info) {
      std::string name = info.param.first;
      name = name.substr(name.find('/') + 1);
      return name.substr(0, name.find('.'));
    });

// At least 98 % of the faces large enough to sample print the model's colour.
TEST_P(ColourPrint, PagesShowTheModelsColourOnEveryFace) {
  if (!has_pdftoppm()) GTEST_SKIP() << "pdftoppm missing: install poppler-utils";
  const auto [file, size] = GetParam();
  const Check check = check_colour(file, size, data_file(file));
  ASSERT_GT(check.faces, 0u) << file;
  EXPECT_GE(static_cast<double>(check.matched), 0.98 * check.faces)
      << file << ": " << check.matched << " of " << check.faces
      << " faces print their colour; worst mean difference " << check.worst;
  std::printf("%s: %zu of %zu faces within %.2f (worst %.3f)\n", file, check.matched, check.faces,
              kTolerance, check.worst);
  // Every cut edge has a tab or a glue strip; the tabs show the colour of the face they glue
  // under.
  // The Duck at 150 mm is dense: beside many short edges the point 0.8 mm out meets a tab's
  // outline, a partial tab (one over a stretch of its edge) or a neighbour face; 89.6 % of its
  // edges show the tab's colour there. The cubes' tabs are whole trapezoids on long edges.
  const double share = std::string(file) == "Duck.glb" ? 0.85 : 0.98;
  EXPECT_GE(static_cast<double>(check.tabbed), share * check.cut_edges)
      << file << ": " << check.tabbed << " of " << check.cut_edges
      << " cut edges show a coloured tab, " << check.strips << " glue strips";
  std::printf(
      "%s: %zu of %zu cut edges (4 mm or more) show a tab in the colour of the face it "
      "glues under; %zu glue strips\n",
      file, check.tabbed, check.cut_edges, check.strips);
}

// BoxTextured written again by the test in another form (issue "Colour kits": an OBJ with MTL,
// and a glTF with KHR_texture_transform): each face's corners with their positions and texture
// coordinates as the test wrote them, so that the colour a printed face should show is looked
// up by its corners' positions, whatever the loader made of the file.
struct SourceModel {
  std::vector<std::array<Vec3, 3>> corners;
  std::vector<std::array<UV, 3>> uvs;  // glTF's convention (v down), before any transform
  Texture texture;
  RGBA factor{1, 1, 1, 1};  // linear
};

SourceModel box_textured() {
  const LoadedMesh box = load_mesh_file(papernet::test::test_data_dir() + "/BoxTextured.glb");
  SourceModel m;
  for (std::size_t f = 0; f < box.mesh.faces.size(); ++f) {
    std::array<Vec3, 3> corners;
    for (int k = 0; k < 3; ++k) corners[k] = box.mesh.vertices[box.mesh.faces[f][k]];
    m.corners.push_back(corners);
    m.uvs.push_back(box.colour.uvs.at(f));
  }
  const Material& material = box.colour.materials.at(box.colour.face_materials.at(0));
  m.texture = box.colour.textures.at(material.texture);
  m.factor = material.base_color;
  return m;
}

// The source's colour at barycentric w of the printed face f: the source face with the same
// corner positions, its texture sampled at w of its corners' texture coordinates.
Expected source_colour(const SourceModel& m, const Image& texture) {
  return [&m, &texture](const NetDocument& doc, std::size_t f, const std::array<double, 3>& w) {
    const auto& tri = doc.mesh.faces[f];
    for (std::size_t i = 0; i < m.corners.size(); ++i) {
      std::array<int, 3> corner{-1, -1, -1};
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
          if (norm(m.corners[i][j] - doc.mesh.vertices[tri[k]]) < 1e-6) corner[k] = j;
      if (std::count(corner.begin(), corner.end(), -1) > 0) continue;
      double u = 0, v = 0;
      for (int k = 0; k < 3; ++k)
        u += w[k] * m.uvs[i][corner[k]][0], v += w[k] * m.uvs[i][corner[k]][1];
      std::array<double, 3> c = sample(texture, u, v);
      for (int k = 0; k < 3; ++k) c[k] *= srgb(m.factor[k]);
      return c;
    }
    return std::array<double, 3>{-1, -1, -1};  // no such face in the source: never matches
  };
}

// The source as an OBJ (vt's v up, as OBJ has it) with an MTL naming the texture (map_Kd).
JobInput as_obj_with_mtl(const SourceModel& m) {
  std::ostringstream obj, faces, mtl;
  obj.precision(9);
  mtl.precision(9);
  obj << "mtllib box.mtl\nusemtl logo\n";
  int corner = 0;
  for (std::size_t f = 0; f < m.corners.size(); ++f) {
    faces << "f";
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = m.corners[f][k];
      obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
      obj << "vt " << m.uvs[f][k][0] << ' ' << 1 - m.uvs[f][k][1] << '\n';
      ++corner;
      faces << ' ' << corner << '/' << corner;
    }
    faces << '\n';
  }
  mtl << "newmtl logo\nKd " << m.factor[0] << ' ' << m.factor[1] << ' ' << m.factor[2]
      << "\nmap_Kd box.png\n";
  JobInput input;
  input.mesh = obj.str() + faces.str();
  input.format = MeshFormat::Obj;
  input.external_files["box.mtl"] = mtl.str();
  input.external_files["box.png"] = m.texture.bytes;
  return input;
}

// The source as a glTF, its corners with texture coordinates `uvs` (glTF's convention), the
// material's texture reference with `extensions` (null: none), the texture with `sampler` (null:
// none, so repeat). With `colours` (linear RGB per corner), those as COLOR_0 and no texture.
JobInput as_gltf(const SourceModel& m, const std::vector<std::array<UV, 3>>& uvs,
                 const nlohmann::json& extensions, const nlohmann::json& sampler,
                 const std::vector<std::array<std::array<float, 3>, 3>>& colours = {}) {
  std::vector<float> positions, coordinates, rgb;
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (std::size_t f = 0; f < m.corners.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = m.corners[f][k];
      const std::array<double, 3> xyz{p.x, p.y, p.z};
      for (int i = 0; i < 3; ++i) {
        positions.push_back(static_cast<float>(xyz[i]));
        lo[i] = std::min(lo[i], static_cast<double>(positions.back()));
        hi[i] = std::max(hi[i], static_cast<double>(positions.back()));
      }
      coordinates.push_back(static_cast<float>(uvs[f][k][0]));
      coordinates.push_back(static_cast<float>(uvs[f][k][1]));
      if (!colours.empty()) rgb.insert(rgb.end(), colours[f][k].begin(), colours[f][k].end());
    }
  std::string buffer(reinterpret_cast<const char*>(positions.data()),
                     positions.size() * sizeof(float));
  const std::size_t uv_offset = buffer.size();
  buffer.append(reinterpret_cast<const char*>(coordinates.data()),
                coordinates.size() * sizeof(float));
  const std::size_t rgb_offset = buffer.size();
  buffer.append(reinterpret_cast<const char*>(rgb.data()), rgb.size() * sizeof(float));
  const std::size_t count = m.corners.size() * 3;
  nlohmann::json reference = nlohmann::json::object({{"index", 0}});
  if (!extensions.is_null()) reference["extensions"] = extensions;
  nlohmann::json texture = nlohmann::json::object({{"source", 0}});
  nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"material", 0}}}}}}},
      {"materials",
       {{{"pbrMetallicRoughness",
          {{"baseColorFactor", {m.factor[0], m.factor[1], m.factor[2], 1.0}},
           {"baseColorTexture", reference}}}}}},
      {"images", {{{"uri", "box.png"}}}},
      {"buffers",
       {{{"byteLength", buffer.size()},
         {"uri", "data:application/octet-stream;base64," + encode_base64(buffer)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", uv_offset}},
        {{"buffer", 0}, {"byteOffset", uv_offset}, {"byteLength", rgb_offset - uv_offset}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", count},
         {"type", "VEC3"},
         {"min", lo},
         {"max", hi}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", count}, {"type", "VEC2"}}}}};
  if (!extensions.is_null()) gltf["extensionsUsed"] = {"KHR_texture_transform"};
  if (!colours.empty()) {
    gltf["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", rgb_offset}, {"byteLength", buffer.size() - rgb_offset}});
    gltf["accessors"].push_back(
        {{"bufferView", 2}, {"componentType", 5126}, {"count", count}, {"type", "VEC3"}});
    gltf["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 2;
    gltf["materials"][0]["pbrMetallicRoughness"].erase("baseColorTexture");
    gltf.erase("textures");
    gltf.erase("images");
    gltf.erase("samplers");
    JobInput input;
    input.mesh = gltf.dump();
    input.format = MeshFormat::Gltf;
    return input;
  }
  if (!sampler.is_null()) {
    gltf["samplers"] = nlohmann::json::array({sampler});
    texture["sampler"] = 0;
  }
  gltf["textures"] = nlohmann::json::array({texture});
  JobInput input;
  input.mesh = gltf.dump();
  input.format = MeshFormat::Gltf;
  input.external_files["box.png"] = m.texture.bytes;
  return input;
}

// The source as a glTF whose material's texture reference has a KHR_texture_transform (offset,
// rotation, scale): the file's texture coordinates are the source's under the inverse of that
// transform, so printed through it they show the source's colours. The transform as the
// extension's specification defines it: uv' = T R S uv, R = [cos r, sin r; -sin r, cos r].
JobInput as_gltf_with_texture_transform(const SourceModel& m) {
  const double ox = 0.25, oy = -0.125, r = 0.5, sx = 2, sy = 0.5;
  const double a = std::cos(r) * sx, c = std::sin(r) * sy;   // u' = a u + c v + ox
  const double b = -std::sin(r) * sx, d = std::cos(r) * sy;  // v' = b u + d v + oy
  const double det = a * d - b * c;
  std::vector<std::array<UV, 3>> uvs = m.uvs;
  for (auto& face : uvs)
    for (UV& uv : face) {
      const double u = uv[0] - ox, v = uv[1] - oy;
      uv = {(d * u - c * v) / det, (-b * u + a * v) / det};
    }
  const nlohmann::json transform = {{"offset", {ox, oy}}, {"rotation", r}, {"scale", {sx, sy}}};
  return as_gltf(m, uvs, {{"KHR_texture_transform", transform}}, nullptr);
}

// The source as a glTF whose primitive is Draco-compressed (KHR_draco_mesh_compression):
// positions and texture coordinates encoded by libdraco, losslessly (no quantization).
JobInput as_draco_gltf(const SourceModel& m) {
  const int faces = static_cast<int>(m.corners.size());
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(faces);
  const int position =
      builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int texcoord =
      builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (int f = 0; f < faces; ++f) {
    std::array<std::array<float, 3>, 3> p;
    std::array<std::array<float, 2>, 3> t;
    for (int k = 0; k < 3; ++k) {
      const Vec3 q = m.corners[f][k];
      p[k] = {static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)};
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(lo[i], static_cast<double>(p[k][i]));
        hi[i] = std::max(hi[i], static_cast<double>(p[k][i]));
      }
      t[k] = {static_cast<float>(m.uvs[f][k][0]), static_cast<float>(m.uvs[f][k][1])};
    }
    builder.SetAttributeValuesForFace(position, draco::FaceIndex(f), p[0].data(), p[1].data(),
                                      p[2].data());
    builder.SetAttributeValuesForFace(texcoord, draco::FaceIndex(f), t[0].data(), t[1].data(),
                                      t[2].data());
  }
  const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  draco::Encoder encoder;
  draco::EncoderBuffer buffer;
  EXPECT_TRUE(mesh && encoder.EncodeMeshToBuffer(*mesh, &buffer).ok());
  const std::string drc(buffer.data(), buffer.size());
  const std::size_t count = m.corners.size() * 3;
  const nlohmann::json draco = {{"bufferView", 0},
                                {"attributes",
                                 {{"POSITION", mesh->attribute(position)->unique_id()},
                                  {"TEXCOORD_0", mesh->attribute(texcoord)->unique_id()}}}};
  const nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_draco_mesh_compression"}},
      {"extensionsRequired", {"KHR_draco_mesh_compression"}},
      {"scene", 0},
      {"scenes", nlohmann::json::array({nlohmann::json::object({{"nodes", {0}}})})},
      {"nodes", nlohmann::json::array({nlohmann::json::object({{"mesh", 0}})})},
      {"meshes", nlohmann::json::array({nlohmann::json::object(
                     {{"primitives",
                       nlohmann::json::array({nlohmann::json::object(
                           {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}},
                            {"indices", 2},
                            {"material", 0},
                            {"extensions", nlohmann::json::object(
                                               {{"KHR_draco_mesh_compression", draco}})}})})}})})},
      {"materials", nlohmann::json::array({nlohmann::json::object(
                        {{"pbrMetallicRoughness",
                          {{"baseColorFactor", {m.factor[0], m.factor[1], m.factor[2], 1.0}},
                           {"baseColorTexture", nlohmann::json::object({{"index", 0}})}}}})})},
      {"textures", nlohmann::json::array({nlohmann::json::object({{"source", 0}})})},
      {"images", nlohmann::json::array({nlohmann::json::object({{"uri", "box.png"}})})},
      {"buffers", nlohmann::json::array({nlohmann::json::object(
                      {{"byteLength", drc.size()},
                       {"uri", "data:application/octet-stream;base64," + encode_base64(drc)}})})},
      {"bufferViews", nlohmann::json::array({nlohmann::json::object(
                          {{"buffer", 0}, {"byteOffset", 0}, {"byteLength", drc.size()}})})},
      {"accessors",
       {{{"componentType", 5126}, {"count", count}, {"type", "VEC3"}, {"min", lo}, {"max", hi}},
        {{"componentType", 5126}, {"count", count}, {"type", "VEC2"}},
        {{"componentType", 5125}, {"count", count}, {"type", "SCALAR"}}}}};
  JobInput input;
  input.mesh = gltf.dump();
  input.format = MeshFormat::Gltf;
  input.external_files["box.png"] = m.texture.bytes;
  return input;
}

// The textured box as an OBJ with MTL, as a glTF with KHR_texture_transform and as a
// Draco-compressed glTF prints the colours of the box it was written from, face by face (found
// by position), tabs included.
TEST(ColourPrintForms, ObjWithMtlTextureTransformAndDracoPrintTheSourcesColours) {
  if (!has_pdftoppm()) GTEST_SKIP() << "pdftoppm missing: install poppler-utils";
  const SourceModel box = box_textured();
  ASSERT_EQ(box.corners.size(), 12u);
  const Image texture = decode_image(box.texture.bytes);
  for (const auto& [name, input] :
       {std::pair{std::string("box.obj"), as_obj_with_mtl(box)},
        std::pair{std::string("box_texture_transform.gltf"), as_gltf_with_texture_transform(box)},
        std::pair{std::string("box_draco.gltf"), as_draco_gltf(box)}}) {
    const Check check = check_colour(name, 80, input, source_colour(box, texture));
    EXPECT_EQ(check.faces, 12u) << name;
    EXPECT_GE(static_cast<double>(check.matched), 0.98 * check.faces)
        << name << ": " << check.matched << " of " << check.faces
        << " faces print the source's colour; worst mean difference " << check.worst;
    EXPECT_GE(static_cast<double>(check.tabbed), 0.98 * check.cut_edges)
        << name << ": " << check.tabbed << " of " << check.cut_edges;
    std::printf(
        "%s: %zu of %zu faces within %.2f (worst %.3f); %zu of %zu cut edges show a "
        "coloured tab\n",
        name.c_str(), check.matched, check.faces, kTolerance, check.worst, check.tabbed,
        check.cut_edges);
  }
}

// A 64 x 64 texture whose texels all differ: red grows along u, green along v.
Texture gradient_texture() {
  std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> s(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, 64, 64), cairo_surface_destroy);
  cairo_surface_flush(s.get());
  unsigned char* data = cairo_image_surface_get_data(s.get());
  for (int y = 0; y < 64; ++y) {
    auto* row =
        reinterpret_cast<std::uint32_t*>(data + y * cairo_image_surface_get_stride(s.get()));
    for (int x = 0; x < 64; ++x)
      row[x] = 0xff000000u | std::uint32_t(x * 4) << 16 | std::uint32_t(y * 4) << 8 | 0x80;
  }
  cairo_surface_mark_dirty(s.get());
  Texture t;
  t.bytes = encode_png(s.get());
  t.mime_type = "image/png";
  t.width = t.height = 64;
  return t;
}

// Texture coordinates far outside [0, 1] under clamp sampling (issue "Colour kits", bad
// input): the box with a gradient texture, its faces' coordinates moved 1,000 widths out in u
// (a face shows the last column's gradient along v), 10^6 out in both (the corner texel) or
// stretched 2,000-fold about the middle (each side shows an edge column, the texture itself a
// sliver between); one face's coordinates NaN (it prints the material's white). The print shows
// what clamping says at every sampled point, and the result warns of both.
TEST(ColourPrintForms, FarOutUvsUnderClampSamplingPrintTheClampedTexture) {
  if (!has_pdftoppm()) GTEST_SKIP() << "pdftoppm missing: install poppler-utils";
  SourceModel box = box_textured();
  ASSERT_EQ(box.corners.size(), 12u);
  box.texture = gradient_texture();
  box.factor = {1, 1, 1, 1};
  std::vector<std::array<UV, 3>> far = box.uvs;
  for (std::size_t f = 0; f < far.size(); ++f)
    for (UV& uv : far[f]) {
      if (f % 3 == 0) uv[0] += 1000;
      if (f % 3 == 1) uv = {uv[0] - 1e6, uv[1] - 1e6};
      if (f % 3 == 2) uv[0] = (uv[0] - 0.5) * 2000 + 0.5;
    }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  far[3][1] = {nan, nan};
  SourceModel printed = box;
  printed.uvs = far;
  const Image texture = decode_image(box.texture.bytes);
  const Expected expected = [&](const NetDocument& doc, std::size_t f,
                                const std::array<double, 3>& w) {
    const auto& tri = doc.mesh.faces[f];
    for (std::size_t i = 0; i < far.size(); ++i) {
      std::array<int, 3> corner{-1, -1, -1};
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
          if (norm(box.corners[i][j] - doc.mesh.vertices[tri[k]]) < 1e-6) corner[k] = j;
      if (std::count(corner.begin(), corner.end(), -1) > 0) continue;
      if (i == 3) return std::array<double, 3>{1, 1, 1};
      double u = 0, v = 0;
      for (int k = 0; k < 3; ++k)
        u += w[k] * far[i][corner[k]][0], v += w[k] * far[i][corner[k]][1];
      const auto c = sample_rgba(texture, u, v, true);
      return std::array<double, 3>{c[0], c[1], c[2]};
    }
    return std::array<double, 3>{-1, -1, -1};
  };
  const nlohmann::json clamp = {{"wrapS", 33071}, {"wrapT", 33071}};
  const Check check =
      check_colour("box_far_uvs.gltf", 80, as_gltf(printed, far, nullptr, clamp), expected);
  EXPECT_EQ(check.faces, 12u);
  EXPECT_GE(static_cast<double>(check.matched), 0.98 * check.faces)
      << check.matched << " of " << check.faces
      << " faces print the clamped texture; worst mean difference " << check.worst;
  std::printf("far-out clamped coordinates: %zu of %zu faces within %.2f (worst %.3f)\n",
              check.matched, check.faces, kTolerance, check.worst);
  auto warning = [&](const std::string& code) {
    for (const NetRepair& w : check.warnings)
      if (w.code == code) return w.count;
    return std::size_t{0};
  };
  EXPECT_EQ(warning("texture_coordinates_out_of_range"), 11u);
  EXPECT_EQ(warning("texture_coordinates_missing"), 1u);
}

// The box with each face black at one corner and white at the others, printed with colour at
// `dpi`: every face prints the linear blend of its corners (the test's expected colour: srgb of
// the interpolated linear colour).
void expect_linear_blend(const std::string& file, double dpi) {
  const SourceModel box = box_textured();
  std::vector<std::array<std::array<float, 3>, 3>> colours(box.corners.size());
  for (auto& face : colours) face = {{{0, 0, 0}, {1, 1, 1}, {1, 1, 1}}};
  const Check check = check_colour(file, 80, as_gltf(box, box.uvs, nullptr, nullptr, colours),
                                   nullptr, nullptr, dpi);
  EXPECT_EQ(check.faces, 12u);
  EXPECT_GE(static_cast<double>(check.matched), 0.98 * check.faces)
      << check.matched << " of " << check.faces
      << " faces print the linear blend of their corners; worst mean difference " << check.worst;
  std::printf("vertex colour gradients at %g dpi: %zu of %zu faces within %.2f (worst %.3f)\n", dpi,
              check.matched, check.faces, kTolerance, check.worst);
}

// Vertex colours are linear (glTF) and so is their interpolation across a face; cairo's
// gradients interpolate in sRGB, which from black to white is 0.235 off at the middle.
TEST(ColourPrintForms, VertexColourGradientsBlendLinearly) {
  if (!has_pdftoppm()) GTEST_SKIP() << "pdftoppm missing: install poppler-utils";
  expect_linear_blend("box_gradient.gltf", kDpi);
}

// The same at the print's default resolution, 300 dpi, where vertex colours are not drawn by
// cairo's gradients but computed pixel by pixel (print/colour.cpp, write_gradient).
TEST(ColourPrintForms, VertexColourGradientsBlendLinearlyAtTheDefaultResolution) {
  if (!has_pdftoppm()) GTEST_SKIP() << "pdftoppm missing: install poppler-utils";
  expect_linear_blend("box_gradient_300.gltf", kDefaultColourDpi);
}

// Alpha (glTF alphaMode; docs/colour.md, "Alpha"): the Khronos AlphaBlendModeTest, whose
// panels are textured with an alpha gradient under MASK (cutoffs 0.25, 0.75 and the default
// 0.5) and BLEND. On paper, what the model does not show is the paper: its faces under those
// materials print the texture over white by the alpha (the test's expected colour: cut at the
// cutoff, or mixed). Its OPAQUE faces (small labels and check marks whose texels are finer than
// the print) are not sampled here.
TEST(ColourPrintForms, MaskAndBlendMaterialsShowThePaperWhereTheyAreSeeThrough) {
  if (!has_pdftoppm()) GTEST_SKIP() << "pdftoppm missing: install poppler-utils";
  const Check check = check_colour(
      "AlphaBlendModeTest.glb", 200, data_file("AlphaBlendModeTest/AlphaBlendModeTest.glb"),
      nullptr, [](const NetDocument& doc, std::size_t f) {
        const int m = doc.colour.face_materials.at(f);
        return m >= 0 && doc.colour.materials.at(m).alpha_mode != AlphaMode::Opaque;
      });
  EXPECT_GE(check.faces, 8u);
  EXPECT_GE(static_cast<double>(check.matched), 0.98 * check.faces)
      << check.matched << " of " << check.faces
      << " faces print the paper through their alpha; worst mean difference " << check.worst;
  std::printf("alpha modes: %zu of %zu mask and blend faces within %.2f (worst %.3f)\n",
              check.matched, check.faces, kTolerance, check.worst);
}

// Closest point of triangle abc to p, as barycentric coordinates (Ericson, Real-Time Collision
// Detection, 5.1.5), and its squared distance: the test's own, brute force over every face.
std::pair<double, std::array<double, 3>> closest_on_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  auto result = [&](double u, double v, double w) {
    const Vec3 q = u * a + v * b + w * c;
    return std::pair{dot(p - q, p - q), std::array<double, 3>{u, v, w}};
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return result(1, 0, 0);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return result(0, 1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return result(1 - v, v, 0);
  }
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return result(0, 0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return result(1 - w, 0, w);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return result(0, 1 - w, w);
  }
  const double denom = va + vb + vc;
  if (!(denom > 0)) return result(1, 0, 0);
  return result(1 - (vb + vc) / denom, vb / denom, vc / denom);
}

// The Duck at detail auto folds into a coarser mesh, whose faces have no texture coordinates of
// their own: the print colours them from the input surface nearest to them. Checked against
// the input itself: each sample point of a coarse face (its 3D position), the nearest point of
// the input Duck found by brute force, the input's texture at that point's texture coordinates.
TEST(ColourPrintApproximate, CoarserFacesPrintTheColourOfTheNearestInputSurface) {
  if (!has_pdftoppm()) GTEST_SKIP() << "pdftoppm missing: install poppler-utils";
  JobOptions options;
  options.dpi = kDpi;
  options.labels = false;
  options.tab_room_budget = 2000;
  PipelineProgress quiet;
  const JobInput input = data_file("Duck.glb");
  const UnfoldOutcome out = run_pipeline(input, options, {}, {.pdf = true}, quiet);
  const NetDocument& doc = out.net;
  ASSERT_EQ(doc.result, "approximate");
  ASSERT_TRUE(doc.print);
  const LoadedMesh duck = load_mesh(input.mesh, input.format);
  ASSERT_EQ(duck.colour.uvs.size(), duck.mesh.faces.size());
  const Material& material = duck.colour.materials.at(duck.colour.face_materials.at(0));
  const Image texture = decode_image(duck.colour.textures.at(material.texture).bytes);
  const std::string path =
      (std::filesystem::temp_directory_path() / "papernet_colour_auto.pdf").string();
  {
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), std::fclose);
    std::fwrite(out.documents.pdf.data(), 1, out.documents.pdf.size(), f.get());
  }
  Check check;
  for (int page = 0; page < doc.print->pages; ++page) {
    const Raster raster = render(path, page + 1);
    ASSERT_GT(raster.width, 0);
    for (std::size_t f = 0; f < doc.mesh.faces.size(); ++f) {
      const PiecePlacement& placed = doc.print->placements.at(doc.piece[f]);
      if (placed.page != page) continue;
      const std::array<Vec2, 3> p = page_pixels(doc, f);
      if (!(inradius(p) >= 3)) continue;
      const auto& face = doc.mesh.faces[f];
      std::vector<double> errors;
      for (const auto& w : kSamples) {
        const Vec3 point = w[0] * doc.mesh.vertices[face[0]] + w[1] * doc.mesh.vertices[face[1]] +
                           w[2] * doc.mesh.vertices[face[2]];
        double best = std::numeric_limits<double>::infinity();
        std::size_t nearest = 0;
        std::array<double, 3> at{};
        for (std::size_t g = 0; g < duck.mesh.faces.size(); ++g) {
          const auto& s = duck.mesh.faces[g];
          const auto [d2, bary] = closest_on_triangle(
              point, duck.mesh.vertices[s[0]], duck.mesh.vertices[s[1]], duck.mesh.vertices[s[2]]);
          if (d2 < best) best = d2, nearest = g, at = bary;
        }
        const auto& uv = duck.colour.uvs[nearest];
        const auto want = sample(texture, at[0] * uv[0][0] + at[1] * uv[1][0] + at[2] * uv[2][0],
                                 at[0] * uv[0][1] + at[1] * uv[1][1] + at[2] * uv[2][1]);
        const Vec2 q = w[0] * p[0] + w[1] * p[1] + w[2] * p[2];
        const auto printed = raster.at(static_cast<int>(q.x), static_cast<int>(q.y));
        errors.push_back(difference(printed, want));
      }
      const double error = median(errors);
      ++check.faces;
      check.matched += error <= kTolerance;
      check.worst = std::max(check.worst, error);
    }
  }
  std::filesystem::remove(path);
  ASSERT_GT(check.faces, 300u);
  EXPECT_GE(static_cast<double>(check.matched), 0.98 * check.faces)
      << check.matched << " of " << check.faces << "; worst " << check.worst;
  std::printf(
      "Duck (detail auto, approximate): %zu of %zu faces within %.2f of the input's "
      "nearest colour (worst %.3f)\n",
      check.matched, check.faces, kTolerance, check.worst);
}

// SVG pages carry each coloured piece as a PNG in a group "colour" drawn over the faces and tabs
// and under the line art; the PNG decodes to the image's size.
TEST(ColourPrintSvg, PagesHoldOnePngPerPieceBetweenFillsAndLines) {
  JobOptions options;
  options.size_mm = 80;
  options.dpi = kDpi;
  PipelineProgress quiet;
  const UnfoldOutcome out =
      run_pipeline(data_file("rgb_cube.gltf"), options, {}, {.svg_pages = true}, quiet);
  ASSERT_FALSE(out.documents.svg_pages.empty());
  std::size_t images = 0;
  std::size_t coloured_pages = 0;
  ASSERT_TRUE(out.net.print);
  for (int k = 0; k < static_cast<int>(out.documents.svg_pages.size()); ++k) {
    const std::string& svg = out.documents.svg_pages[k];
    // The overview's images are its two views of the model (build_order_test).
    if (k == out.net.print->overview_page) {
      EXPECT_EQ(svg_images(svg).size(), 2u);
      continue;
    }
    const auto colour = svg.find("<g id=\"colour\"");
    if (colour == std::string::npos) continue;
    ++coloured_pages;
    EXPECT_LT(svg.find("<g id=\"tabs\""), colour);
    EXPECT_GT(svg.find("<g id=\"cut\""), colour);
    const std::string prefix = "href=\"data:image/png;base64,";
    for (auto at = svg.find(prefix, colour); at != std::string::npos; at = svg.find(prefix, at)) {
      at += prefix.size();
      const std::string png = detail::decode_base64(svg.substr(at, svg.find('"', at) - at));
      const Image image = decode_image(png);
      EXPECT_GT(image.width, 0);
      EXPECT_GT(image.height, 0);
      ++images;
    }
  }
  // One image per printed piece; the cube's pieces share pages (nested), every page coloured.
  EXPECT_EQ(images, static_cast<std::size_t>(out.print->pieces));
  EXPECT_GE(coloured_pages, 1u);
  EXPECT_LE(coloured_pages, static_cast<std::size_t>(out.print->pieces));
}

// The resolution of a page's colour images (SVG), dots per inch: the largest image's pixels over
// its width; 0 without colour (the overview).
double page_dpi(const std::string& svg) {
  const auto colour = svg.find("<g id=\"colour\"");
  if (colour == std::string::npos) return 0;
  double dpi = 0, widest = 0;
  const std::string prefix = "href=\"data:image/png;base64,";
  for (auto at = svg.find("<image ", colour); at != std::string::npos;
       at = svg.find("<image ", at + 1)) {
    const auto w = svg.find("width=\"", at) + 7;
    const double width_mm = std::stod(svg.substr(w, svg.find('"', w) - w));
    const auto href = svg.find(prefix, at) + prefix.size();
    const Image image =
        decode_image(detail::decode_base64(svg.substr(href, svg.find('"', href) - href)));
    if (width_mm > widest) widest = width_mm, dpi = 25.4 * image.width / width_mm;
  }
  return dpi;
}

// The job's time limit bounds the drawing of coloured pages (docs/colour.md, "Time limit"): the
// Duck given 0.3 s has little or no time left for its pages when they are drawn, so from the
// first sheet on (before any page is timed, at the machine's pace) they print their colour at a
// lower resolution, never rising again, instead of overrunning, and the result says which pages and
// the lowest; every page still has its colour. Given time to spare, every page prints at the
// resolution asked.
TEST(ColourPrintTime, PagesPastTheTimeLimitPrintTheirColourAtALowerResolution) {
  PipelineProgress quiet;
  JobOptions options;
  options.dpi = 150;
  options.time_limit = 0.3;
  const UnfoldOutcome late =
      run_pipeline(data_file("Duck.glb"), options, {}, {.svg_pages = true, .pdf = true}, quiet);
  const auto& pages = late.documents.svg_pages;
  ASSERT_GE(pages.size(), 4u) << "an overview and at least three sheets";
  // Page 1 is the overview, whose two views of the model (build_order_test) are no sheet's colour.
  ASSERT_TRUE(late.net.print);
  ASSERT_EQ(late.net.print->overview_page, 0);
  std::size_t first_lowered = pages.size();
  double before = 150, lowest = 150;
  for (std::size_t i = 1; i < pages.size(); ++i) {
    const double dpi = page_dpi(pages[i]);
    first_lowered = std::min(first_lowered, i);
    EXPECT_GE(dpi, 49) << "page " << i + 1 << " has its colour, at 50 dpi or more";
    EXPECT_LT(dpi, 148) << "page " << i + 1 << " is drawn at a lower resolution";
    EXPECT_LE(dpi, before + 2) << "page " << i + 1 << ": the resolution never rises again";
    before = dpi;
    lowest = std::min(lowest, dpi);
  }
  ASSERT_EQ(first_lowered, 1u);
  const NetRepair* warning = entry_of(late.net.warnings, "colour_resolution_lowered");
  ASSERT_NE(warning, nullptr);
  EXPECT_EQ(warning->count, pages.size() - first_lowered);
  EXPECT_NE(warning->message.find("pages " + std::to_string(first_lowered + 1) + " to " +
                                  std::to_string(pages.size()) + " print"),
            std::string::npos)
      << warning->message;
  // The lowest resolution named, as measured on the page (whole pixels over the image's width).
  std::smatch m;
  ASSERT_TRUE(
      std::regex_search(warning->message, m, std::regex(R"(than 150 dpi \(down to (\d+) dpi\))")))
      << warning->message;
  EXPECT_NEAR(std::stod(m[1].str()), lowest, 2) << warning->message;

  options.time_limit = 1000;
  options.dpi = kDpi;
  lighten(options);  // the budgets, not the clock, end its search and merge
  const UnfoldOutcome spare =
      run_pipeline(data_file("Duck.glb"), options, {}, {.svg_pages = true}, quiet);
  ASSERT_GE(spare.documents.svg_pages.size(), 3u);
  for (std::size_t i = 1; i < spare.documents.svg_pages.size(); ++i)
    EXPECT_NEAR(page_dpi(spare.documents.svg_pages[i]), kDpi, 2) << "page " << i + 1;
  for (const NetRepair& w : spare.net.warnings)
    EXPECT_NE(w.code, "colour_resolution_lowered") << w.message;
}

// With colour none the same pages are line art: the faces print in the pale face fill, not the
// model's colour (the check above would fail on them).
TEST(ColourPrintNone, LineArtLeavesTheFacesUncoloured) {
  if (!has_pdftoppm()) GTEST_SKIP() << "pdftoppm missing: install poppler-utils";
  JobOptions options;
  options.colour = false;
  options.size_mm = 80;
  PipelineProgress quiet;
  const UnfoldOutcome out =
      run_pipeline(data_file("rgb_cube.gltf"), options, {}, {.pdf = true}, quiet);
  const std::string path =
      (std::filesystem::temp_directory_path() / "papernet_colour_none.pdf").string();
  {
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), std::fclose);
    std::fwrite(out.documents.pdf.data(), 1, out.documents.pdf.size(), f.get());
  }
  const Raster raster = render(path, 1);
  std::filesystem::remove(path);
  ASSERT_GT(raster.width, 0);
  std::size_t saturated = 0;
  for (int y = 0; y < raster.height; ++y)
    for (int x = 0; x < raster.width; ++x) {
      const auto c = raster.at(x, y);
      saturated += std::max({c[0], c[1], c[2]}) - std::min({c[0], c[1], c[2]}) > 0.5;
    }
  EXPECT_LT(saturated, static_cast<std::size_t>(raster.width) * raster.height / 100);
}

// Labels over a dark colour print white (docs/print.md, "Labels"): on the milk truck, whose
// tyres and body are near black, the page around a label the SVG draws white is dark in the
// rendered PDF, and around one it draws dark grey light (the paper just past both ends of its
// text); printed without colour, no label is white.
TEST(ColourPrintLabels, LabelsOverDarkColourPrintWhite) {
  if (!has_pdftoppm()) GTEST_SKIP() << "pdftoppm missing: install poppler-utils";
  for (const bool colour : {true, false}) {
    JobOptions options;
    options.colour = colour;
    options.dpi = kDpi;
    lighten(options);
    PipelineProgress quiet;
    const UnfoldOutcome out = run_pipeline(data_file("CesiumMilkTruck/CesiumMilkTruck.gltf"),
                                           options, {}, {.svg_pages = true, .pdf = true}, quiet);
    ASSERT_TRUE(out.net.print);
    const std::string path =
        (std::filesystem::temp_directory_path() / "papernet_colour_labels.pdf").string();
    {
      std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), std::fclose);
      std::fwrite(out.documents.pdf.data(), 1, out.documents.pdf.size(), f.get());
    }
    static const std::regex text(
        "<text x=\"[-0-9.]+\" y=\"[-0-9.]+\" font-size=\"([0-9.]+)\"( fill=\"#ffffff\")? "
        "stroke=\"none\" transform=\"rotate\\(([-0-9.]+) ([-0-9.]+) ([-0-9.]+)\\)\"[^>]*>([^<]+)"
        "</text>");
    std::size_t white = 0, white_on_dark = 0, grey = 0, grey_on_light = 0;
    for (int page = 0; page < static_cast<int>(out.documents.svg_pages.size()); ++page) {
      if (page == out.net.print->overview_page) continue;
      const Raster raster = render(path, page + 1);
      ASSERT_GT(raster.width, 0);
      const std::string labels = svg_group(out.documents.svg_pages[page], "labels");
      for (auto it = std::sregex_iterator(labels.begin(), labels.end(), text);
           it != std::sregex_iterator(); ++it) {
        const double size = std::stod((*it)[1]),
                     turn = std::stod((*it)[3]) * std::numbers::pi / 180;
        const Vec2 centre{std::stod((*it)[4]), std::stod((*it)[5])};
        const double reach = 0.3 * size * static_cast<double>((*it)[6].length()) + 0.6 * size;
        double sum = 0;
        int n = 0;
        for (const double side : {-1.0, 1.0}) {
          const Vec2 at =
              (kDpi / 25.4) * (centre + side * reach * Vec2{std::cos(turn), std::sin(turn)});
          const int x = static_cast<int>(at.x), y = static_cast<int>(at.y);
          if (x < 0 || y < 0 || x >= raster.width || y >= raster.height) continue;
          const auto c = raster.at(x, y);
          sum += 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
          ++n;
        }
        if (n == 0) continue;
        const bool dark = sum / n < 0.4;
        if ((*it)[2].matched) {
          ++white;
          white_on_dark += dark;
        } else {
          ++grey;
          grey_on_light += !dark;
        }
      }
    }
    std::filesystem::remove(path);
    SCOPED_TRACE(colour ? "in colour" : "without colour");
    EXPECT_GT(grey, 60u);  // 100 in colour since pieces merge after the fit search (fewer cuts)
    EXPECT_GE(grey_on_light, grey * 9 / 10) << grey_on_light << " of " << grey;
    if (!colour) {
      EXPECT_EQ(white, 0u);
      continue;
    }
    EXPECT_GT(white, 100u) << "the tyres and the body are near black";
    EXPECT_GE(white_on_dark, white * 9 / 10) << white_on_dark << " of " << white;
  }
}
}  // namespace
}  // namespace papernet::test
