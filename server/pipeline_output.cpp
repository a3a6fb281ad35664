#include "server/pipeline_output.h"

#include "core/io/write_mesh.h"
#include "core/unfold/net_check.h"
#include "print/pdf.h"
#include "print/print_output.h"
#include "print/svg.h"

namespace papernet::server {

namespace {

PrintOptions print_options(const JobOptions& options) {
  PrintOptions print;
  if (options.size_mm) print.size_mm = *options.size_mm;
  if (options.scale) print.scale = *options.scale;
  print.flat_angle_deg = options.flat_fold_degrees;
  print.tabs = options.tabs;
  print.tab_room_budget = options.tab_room_budget;
  return print;
}

}  // namespace

NetCheckReport make_room_for_tabs(const Mesh& mesh, Net& net, const JobOptions& options,
                                  double seconds, Progress& progress) {
  PrintOptions print = print_options(options);
  print.tab_room_seconds = seconds;
  TabClearanceResult room = make_tab_room(mesh, net, print, progress);
  if (room.moves > 0) {
    NetCheckReport report = check_net(mesh, room.net);
    if (report.ok()) {
      net = std::move(room.net);
      return report;
    }
  }
  return check_net(mesh, net);
}

PrintFiles render_print_files(const Mesh& mesh, const Net& net, const JobOptions& options) {
  OutputOptions out;
  out.print = print_options(options);
  out.paper = options.paper != papernet::PaperSize::None;
  if (out.paper) out.page.paper = parse_paper(paper_name(options.paper));
  out.page.margin_mm = options.margin_mm;

  PrintFiles files;
  PrintLayout layout = layout_net(mesh, net, out.print);
  files.coverage = layout.metrics.coverage;
  files.aspect_ratio = layout.metrics.aspect_ratio;
  const PageLayout pages = paginate(layout, out.page);
  files.pages = static_cast<int>(pages.pages.size());
  files.cut_edges = static_cast<std::size_t>(layout.cut_edges);
  files.tabs = layout.tabs.size();
  files.strips = layout.strips.size();
  files.pdf = write_pdf(layout, pages);
  if (out.paper && pages.pages.size() == 1)
    files.svg = write_page_svgs(layout, pages).front();
  else
    files.svg = write_net_svg(layout, out.page.margin_mm);
  files.glb = write_glb(mesh);
  return files;
}

}  // namespace papernet::server
