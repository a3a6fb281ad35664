#include "print/pdf.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <memory>

#include "core/errors.h"

namespace papernet {

namespace {

constexpr double kPt = 72.0 / 25.4;  // PDF points per millimetre

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void set_rgb(cairo_t* cr, unsigned rgb) {
  cairo_set_source_rgb(cr, ((rgb >> 16) & 255) / 255.0, ((rgb >> 8) & 255) / 255.0,
                       (rgb & 255) / 255.0);
}

void trace(cairo_t* cr, const Shape& s) {
  cairo_move_to(cr, s.points[0].x, s.points[0].y);
  for (std::size_t i = 1; i < s.points.size(); ++i) cairo_line_to(cr, s.points[i].x, s.points[i].y);
  if (s.closed) cairo_close_path(cr);
}

void draw(cairo_t* cr, const PageDrawing& d) {
  cairo_save(cr);
  cairo_rectangle(cr, d.clip_lo.x, d.clip_lo.y, d.clip_hi.x - d.clip_lo.x,
                  d.clip_hi.y - d.clip_lo.y);
  cairo_clip(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  auto fill_layer = [&](Layer layer, unsigned rgb) {
    set_rgb(cr, rgb);
    for (const Shape& s : d.shapes)
      if (s.layer == layer) trace(cr, s), cairo_fill(cr);
  };
  auto stroke_layer = [&](Layer layer, unsigned rgb, double width,
                          std::initializer_list<double> dash, bool key = false) {
    set_rgb(cr, rgb);
    cairo_set_line_width(cr, width);
    cairo_set_dash(cr, dash.size() ? dash.begin() : nullptr, static_cast<int>(dash.size()), 0);
    for (const Shape& s : d.shapes)
      if (s.layer == layer && s.text.empty() && !s.light && s.key == key) trace(cr, s);
    cairo_stroke(cr);
    set_rgb(cr, 0xffffff);  // lines over a dark colour, as light text is
    for (const Shape& s : d.shapes)
      if (s.layer == layer && s.text.empty() && s.light && s.key == key) trace(cr, s);
    cairo_stroke(cr);
  };
  // The fold and cut lines, of the net (key false) or of the key in the margin (key true).
  auto stroke_lines = [&](bool key) {
    stroke_layer(Layer::Cut, 0x000000, 0.25, {}, key);
    stroke_layer(Layer::Mountain, 0xc0392b, 0.2, {2, 1}, key);
    stroke_layer(Layer::Valley, 0x1f5fbf, 0.2, {2, 0.7, 0.4, 0.7}, key);
  };
  auto text_layer = [&](Layer layer, unsigned rgb) {
    set_rgb(cr, rgb);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    for (const Shape& s : d.shapes) {
      if (s.layer != layer || s.text.empty()) continue;
      cairo_save(cr);
      if (s.light) set_rgb(cr, 0xffffff);
      cairo_translate(cr, s.points[0].x, s.points[0].y);
      cairo_rotate(cr, s.angle_deg * 3.14159265358979323846 / 180);
      cairo_set_font_size(cr, s.size);
      cairo_text_extents_t ext;
      cairo_text_extents(cr, s.text.c_str(), &ext);
      cairo_move_to(cr, s.start ? 0 : -0.5 * ext.x_advance, 0.35 * s.size);
      cairo_show_text(cr, s.text.c_str());
      cairo_restore(cr);
    }
  };
  fill_layer(Layer::Faces, 0xf3f6fb);
  fill_layer(Layer::Tabs, 0xe2e2e2);
  for (const PageImage& image : d.images) {
    cairo_save(cr);
    cairo_translate(cr, image.at.x, image.at.y);
    cairo_scale(cr, image.width / cairo_image_surface_get_width(image.surface.get()),
                image.height / cairo_image_surface_get_height(image.surface.get()));
    cairo_set_source_surface(cr, image.surface.get(), 0, 0);
    cairo_paint(cr);
    cairo_restore(cr);
  }
  set_rgb(cr, 0xfbf1d3);  // glue strips: filled, outlined as cut, seam dotted, labelled
  for (const Shape& s : d.shapes)
    if (s.layer == Layer::Strips && s.closed) trace(cr, s), cairo_fill(cr);
  set_rgb(cr, 0x000000);
  cairo_set_line_width(cr, 0.25);
  for (const Shape& s : d.shapes)
    if (s.layer == Layer::Strips && s.closed) trace(cr, s);
  cairo_stroke(cr);
  set_rgb(cr, 0x777777);
  cairo_set_line_width(cr, 0.15);
  const double seam_dash[] = {1, 0.8};
  cairo_set_dash(cr, seam_dash, 2, 0);
  for (const Shape& s : d.shapes)
    if (s.layer == Layer::Strips && !s.closed && s.text.empty()) trace(cr, s);
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0);
  stroke_lines(false);
  stroke_layer(Layer::Leaders, 0x333333, 0.15, {});
  text_layer(Layer::Labels, 0x333333);
  text_layer(Layer::Strips, 0x333333);
  // Marks and the key live in the margins: unclipped. The key's samples are capped as the lines
  // they stand for.
  cairo_restore(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  stroke_lines(true);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  stroke_layer(Layer::Marks, 0x777777, 0.15, {1, 1});
  text_layer(Layer::Marks, 0x777777);
}

}  // namespace

struct PdfWriter::Cairo {
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface{nullptr,
                                                                             cairo_surface_destroy};
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr{nullptr, cairo_destroy};
};

PdfWriter::PdfWriter(const PrintLayout& layout, double width_mm, double height_mm,
                     const std::string& title)
    : cairo_(std::make_unique<Cairo>()) {
  cairo_surface_t* surface =
      cairo_pdf_surface_create_for_stream(append, &bytes_, width_mm * kPt, height_mm * kPt);
  cairo_->surface.reset(surface);
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS)
    throw IOException(std::string("cannot create PDF: ") +
                      cairo_status_to_string(cairo_surface_status(surface)));
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, "papernet");
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE,
                                 title.empty() ? "papernet paper net" : title.c_str());
  // The counts the SVG carries as data-* attributes, for tools that read PDF metadata.
  const std::string subject = std::to_string(layout.faces.size()) + " faces, " +
                              std::to_string(layout.cut_edges) + " cut edges, " +
                              std::to_string(layout.tabs.size()) + " tabs, " +
                              std::to_string(layout.strips.size()) + " glue strips, " +
                              std::to_string(layout.omitted_tabs.size()) + " tabs omitted";
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_SUBJECT, subject.c_str());
  cairo_->cr.reset(cairo_create(surface));
  cairo_scale(cairo_->cr.get(), kPt, kPt);  // draw in millimetres
}

PdfWriter::~PdfWriter() = default;

void PdfWriter::add_page(const PageDrawing& page) {
  draw(cairo_->cr.get(), page);
  cairo_show_page(cairo_->cr.get());
}

std::string PdfWriter::finish() {
  cairo_->cr.reset();
  cairo_surface_t* surface = cairo_->surface.get();
  cairo_surface_finish(surface);
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS)
    throw IOException(std::string("writing PDF failed: ") +
                      cairo_status_to_string(cairo_surface_status(surface)));
  cairo_->surface.reset();
  return std::move(bytes_);
}

std::string write_pdf(const PrintLayout& layout, const PageLayout& pages,
                      const PrintColour* colour) {
  PdfWriter pdf(layout, pages.width, pages.height, pages.title);
  for (int i = 0; i < static_cast<int>(pages.pages.size()); ++i)
    pdf.add_page(draw_page(layout, pages, i, colour));
  return pdf.finish();
}

}  // namespace papernet
