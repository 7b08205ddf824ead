// The cairo functions the plots call, each loading libcairo on its first call: a command
// that draws no PNG (board, run, pcb: their SVG is plain text) does not map cairo's 17
// libraries (pixman, fontconfig, freetype, X11, xcb...) at start-up, ~1.5 ms of CPU a
// process (docs/performance.md). Add a function here when a plot calls a new one (the link
// fails until then).
#include <cairo-svg.h>
#include <cairo.h>
#include <dlfcn.h>  // dlopen, dlsym

#include <stdexcept>  // std::runtime_error
#include <string>     // std::string

namespace {

void* cairo_symbol(const char* name) {
  static void* library = dlopen("libcairo.so.2", RTLD_NOW | RTLD_LOCAL);
  if (!library)
    throw std::runtime_error(std::string("cannot load cairo for the plot: ") + dlerror());
  void* f = dlsym(library, name);
  if (!f) throw std::runtime_error(std::string("cairo has no ") + name);
  return f;
}

}  // namespace

// Resolved once, on the first call.
#define CAIRO_ON_DEMAND(name) \
  static const auto real = reinterpret_cast<decltype(&name)>(cairo_symbol(#name))

extern "C" {

void cairo_arc(cairo_t* cr, double xc, double yc, double radius, double angle1, double angle2) {
  CAIRO_ON_DEMAND(cairo_arc);
  real(cr, xc, yc, radius, angle1, angle2);
}

void cairo_close_path(cairo_t* cr) {
  CAIRO_ON_DEMAND(cairo_close_path);
  real(cr);
}

cairo_t* cairo_create(cairo_surface_t* target) {
  CAIRO_ON_DEMAND(cairo_create);
  return real(target);
}

void cairo_destroy(cairo_t* cr) {
  CAIRO_ON_DEMAND(cairo_destroy);
  real(cr);
}

void cairo_fill(cairo_t* cr) {
  CAIRO_ON_DEMAND(cairo_fill);
  real(cr);
}

cairo_surface_t* cairo_image_surface_create(cairo_format_t format, int width, int height) {
  CAIRO_ON_DEMAND(cairo_image_surface_create);
  return real(format, width, height);
}

unsigned char* cairo_image_surface_get_data(cairo_surface_t* surface) {
  CAIRO_ON_DEMAND(cairo_image_surface_get_data);
  return real(surface);
}

int cairo_image_surface_get_stride(cairo_surface_t* surface) {
  CAIRO_ON_DEMAND(cairo_image_surface_get_stride);
  return real(surface);
}

void cairo_line_to(cairo_t* cr, double x, double y) {
  CAIRO_ON_DEMAND(cairo_line_to);
  real(cr, x, y);
}

void cairo_mask_surface(cairo_t* cr, cairo_surface_t* surface, double surface_x, double surface_y) {
  CAIRO_ON_DEMAND(cairo_mask_surface);
  real(cr, surface, surface_x, surface_y);
}

void cairo_move_to(cairo_t* cr, double x, double y) {
  CAIRO_ON_DEMAND(cairo_move_to);
  real(cr, x, y);
}

void cairo_new_path(cairo_t* cr) {
  CAIRO_ON_DEMAND(cairo_new_path);
  real(cr);
}

void cairo_new_sub_path(cairo_t* cr) {
  CAIRO_ON_DEMAND(cairo_new_sub_path);
  real(cr);
}

void cairo_paint(cairo_t* cr) {
  CAIRO_ON_DEMAND(cairo_paint);
  real(cr);
}

void cairo_paint_with_alpha(cairo_t* cr, double alpha) {
  CAIRO_ON_DEMAND(cairo_paint_with_alpha);
  real(cr, alpha);
}

void cairo_pop_group_to_source(cairo_t* cr) {
  CAIRO_ON_DEMAND(cairo_pop_group_to_source);
  real(cr);
}

void cairo_push_group(cairo_t* cr) {
  CAIRO_ON_DEMAND(cairo_push_group);
  real(cr);
}

void cairo_rectangle(cairo_t* cr, double x, double y, double width, double height) {
  CAIRO_ON_DEMAND(cairo_rectangle);
  real(cr, x, y, width, height);
}

void cairo_rel_line_to(cairo_t* cr, double dx, double dy) {
  CAIRO_ON_DEMAND(cairo_rel_line_to);
  real(cr, dx, dy);
}

void cairo_restore(cairo_t* cr) {
  CAIRO_ON_DEMAND(cairo_restore);
  real(cr);
}

void cairo_save(cairo_t* cr) {
  CAIRO_ON_DEMAND(cairo_save);
  real(cr);
}

void cairo_scale(cairo_t* cr, double sx, double sy) {
  CAIRO_ON_DEMAND(cairo_scale);
  real(cr, sx, sy);
}

void cairo_select_font_face(cairo_t* cr, const char* family, cairo_font_slant_t slant,
                            cairo_font_weight_t weight) {
  CAIRO_ON_DEMAND(cairo_select_font_face);
  real(cr, family, slant, weight);
}

void cairo_set_dash(cairo_t* cr, const double* dashes, int num_dashes, double offset) {
  CAIRO_ON_DEMAND(cairo_set_dash);
  real(cr, dashes, num_dashes, offset);
}

void cairo_set_fill_rule(cairo_t* cr, cairo_fill_rule_t fill_rule) {
  CAIRO_ON_DEMAND(cairo_set_fill_rule);
  real(cr, fill_rule);
}

void cairo_set_font_size(cairo_t* cr, double size) {
  CAIRO_ON_DEMAND(cairo_set_font_size);
  real(cr, size);
}

void cairo_set_line_cap(cairo_t* cr, cairo_line_cap_t line_cap) {
  CAIRO_ON_DEMAND(cairo_set_line_cap);
  real(cr, line_cap);
}

void cairo_set_line_join(cairo_t* cr, cairo_line_join_t line_join) {
  CAIRO_ON_DEMAND(cairo_set_line_join);
  real(cr, line_join);
}

void cairo_set_line_width(cairo_t* cr, double width) {
  CAIRO_ON_DEMAND(cairo_set_line_width);
  real(cr, width);
}

void cairo_set_operator(cairo_t* cr, cairo_operator_t op) {
  CAIRO_ON_DEMAND(cairo_set_operator);
  real(cr, op);
}

void cairo_set_source_rgb(cairo_t* cr, double red, double green, double blue) {
  CAIRO_ON_DEMAND(cairo_set_source_rgb);
  real(cr, red, green, blue);
}

void cairo_set_source_rgba(cairo_t* cr, double red, double green, double blue, double alpha) {
  CAIRO_ON_DEMAND(cairo_set_source_rgba);
  real(cr, red, green, blue, alpha);
}

void cairo_set_source_surface(cairo_t* cr, cairo_surface_t* surface, double x, double y) {
  CAIRO_ON_DEMAND(cairo_set_source_surface);
  real(cr, surface, x, y);
}

void cairo_show_text(cairo_t* cr, const char* utf8) {
  CAIRO_ON_DEMAND(cairo_show_text);
  real(cr, utf8);
}

const char* cairo_status_to_string(cairo_status_t status) {
  CAIRO_ON_DEMAND(cairo_status_to_string);
  return real(status);
}

void cairo_stroke(cairo_t* cr) {
  CAIRO_ON_DEMAND(cairo_stroke);
  real(cr);
}

void cairo_surface_destroy(cairo_surface_t* surface) {
  CAIRO_ON_DEMAND(cairo_surface_destroy);
  real(surface);
}

void cairo_surface_finish(cairo_surface_t* surface) {
  CAIRO_ON_DEMAND(cairo_surface_finish);
  real(surface);
}

void cairo_surface_flush(cairo_surface_t* surface) {
  CAIRO_ON_DEMAND(cairo_surface_flush);
  real(surface);
}

void cairo_surface_mark_dirty(cairo_surface_t* surface) {
  CAIRO_ON_DEMAND(cairo_surface_mark_dirty);
  real(surface);
}

cairo_status_t cairo_surface_status(cairo_surface_t* surface) {
  CAIRO_ON_DEMAND(cairo_surface_status);
  return real(surface);
}

cairo_status_t cairo_surface_write_to_png(cairo_surface_t* surface, const char* filename) {
  CAIRO_ON_DEMAND(cairo_surface_write_to_png);
  return real(surface, filename);
}

cairo_surface_t* cairo_svg_surface_create(const char* filename, double width_in_points,
                                          double height_in_points) {
  CAIRO_ON_DEMAND(cairo_svg_surface_create);
  return real(filename, width_in_points, height_in_points);
}

void cairo_translate(cairo_t* cr, double tx, double ty) {
  CAIRO_ON_DEMAND(cairo_translate);
  real(cr, tx, ty);
}

}  // extern "C"
