#include "api/print_output.h"

#include <algorithm>
#include <fstream>

#include "api/mesh_export.h"
#include "api/pdf.h"
#include "api/svg.h"
#include "core/errors.h"

namespace papernet {

namespace {

std::string extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw IOException("cannot write '" + path + "'");
}

}  // namespace

bool is_print_output(const std::string& path) {
  const std::string ext = extension(path);
  return ext == "svg" || ext == "pdf" || ext == "glb" || ext == "obj";
}

std::vector<std::string> write_output_file(const std::string& path, const Mesh& mesh,
                                           const Net& net, const OutputOptions& options) {
  const std::string ext = extension(path);
  if (ext == "glb" || ext == "obj") {
    write_file(path, ext == "glb" ? write_glb(mesh) : write_obj(mesh));
    return {path};
  }
  if (ext != "svg" && ext != "pdf")
    throw InvalidInputException("unknown output type '" + path +
                                "': use .svg, .pdf, .glb, .obj (or .json for the net)");
  PrintLayout layout = layout_net(mesh, net, options.print);
  if (ext == "svg" && !options.paper) {
    write_file(path, write_net_svg(layout, options.page.margin_mm));
    return {path};
  }
  const PageLayout pages = paginate(layout, options.page);
  if (ext == "pdf") {
    write_file(path, write_pdf(layout, pages));
    return {path};
  }
  const std::vector<std::string> svgs = write_page_svgs(layout, pages);
  if (svgs.size() == 1) {
    write_file(path, svgs[0]);
    return {path};
  }
  std::vector<std::string> written;
  const std::string stem = path.substr(0, path.size() - 4);
  for (std::size_t i = 0; i < svgs.size(); ++i) {
    written.push_back(stem + "-" + std::to_string(i + 1) + ".svg");
    write_file(written.back(), svgs[i]);
  }
  return written;
}

}  // namespace papernet
