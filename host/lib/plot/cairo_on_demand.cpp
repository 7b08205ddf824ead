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

// Defines cairo's function `name`: it resolves the real one once, on its first call, and
// hands the call on.
#define CAIRO_FORWARD(result, name, params, args)                                    \
  result name params {                                                               \
    static const auto real = reinterpret_cast<decltype(&name)>(cairo_symbol(#name)); \
    return real args;                                                                \
  }

extern "C" {

CAIRO_FORWARD(void, cairo_arc,
              (cairo_t * cr, double xc, double yc, double radius, double angle1, double angle2),
              (cr, xc, yc, radius, angle1, angle2))
CAIRO_FORWARD(void, cairo_close_path, (cairo_t * cr), (cr))
CAIRO_FORWARD(cairo_t*, cairo_create, (cairo_surface_t * target), (target))
CAIRO_FORWARD(void, cairo_destroy, (cairo_t * cr), (cr))
CAIRO_FORWARD(void, cairo_fill, (cairo_t * cr), (cr))
CAIRO_FORWARD(cairo_surface_t*, cairo_image_surface_create,
              (cairo_format_t format, int width, int height), (format, width, height))
CAIRO_FORWARD(unsigned char*, cairo_image_surface_get_data, (cairo_surface_t * surface), (surface))
CAIRO_FORWARD(int, cairo_image_surface_get_stride, (cairo_surface_t * surface), (surface))
CAIRO_FORWARD(void, cairo_line_to, (cairo_t * cr, double x, double y), (cr, x, y))
CAIRO_FORWARD(void, cairo_mask_surface,
              (cairo_t * cr, cairo_surface_t* surface, double surface_x, double surface_y),
              (cr, surface, surface_x, surface_y))
CAIRO_FORWARD(void, cairo_move_to, (cairo_t * cr, double x, double y), (cr, x, y))
CAIRO_FORWARD(void, cairo_new_path, (cairo_t * cr), (cr))
CAIRO_FORWARD(void, cairo_new_sub_path, (cairo_t * cr), (cr))
CAIRO_FORWARD(void, cairo_paint, (cairo_t * cr), (cr))
CAIRO_FORWARD(void, cairo_paint_with_alpha, (cairo_t * cr, double alpha), (cr, alpha))
CAIRO_FORWARD(void, cairo_pop_group_to_source, (cairo_t * cr), (cr))
CAIRO_FORWARD(void, cairo_push_group, (cairo_t * cr), (cr))
CAIRO_FORWARD(void, cairo_rectangle,
              (cairo_t * cr, double x, double y, double width, double height),
              (cr, x, y, width, height))
CAIRO_FORWARD(void, cairo_rel_line_to, (cairo_t * cr, double dx, double dy), (cr, dx, dy))
CAIRO_FORWARD(void, cairo_restore, (cairo_t * cr), (cr))
CAIRO_FORWARD(void, cairo_save, (cairo_t * cr), (cr))
CAIRO_FORWARD(void, cairo_scale, (cairo_t * cr, double sx, double sy), (cr, sx, sy))
CAIRO_FORWARD(void, cairo_select_font_face,
              (cairo_t * cr, const char* family, cairo_font_slant_t slant,
               cairo_font_weight_t weight),
              (cr, family, slant, weight))
CAIRO_FORWARD(void, cairo_set_dash,
              (cairo_t * cr, const double* dashes, int num_dashes, double offset),
              (cr, dashes, num_dashes, offset))
CAIRO_FORWARD(void, cairo_set_fill_rule, (cairo_t * cr, cairo_fill_rule_t fill_rule),
              (cr, fill_rule))
CAIRO_FORWARD(void, cairo_set_font_size, (cairo_t * cr, double size), (cr, size))
CAIRO_FORWARD(void, cairo_set_line_cap, (cairo_t * cr, cairo_line_cap_t line_cap), (cr, line_cap))
CAIRO_FORWARD(void, cairo_set_line_join, (cairo_t * cr, cairo_line_join_t line_join),
              (cr, line_join))
CAIRO_FORWARD(void, cairo_set_line_width, (cairo_t * cr, double width), (cr, width))
CAIRO_FORWARD(void, cairo_set_operator, (cairo_t * cr, cairo_operator_t op), (cr, op))
CAIRO_FORWARD(void, cairo_set_source_rgb, (cairo_t * cr, double red, double green, double blue),
              (cr, red, green, blue))
CAIRO_FORWARD(void, cairo_set_source_rgba,
              (cairo_t * cr, double red, double green, double blue, double alpha),
              (cr, red, green, blue, alpha))
CAIRO_FORWARD(void, cairo_set_source_surface,
              (cairo_t * cr, cairo_surface_t* surface, double x, double y), (cr, surface, x, y))
CAIRO_FORWARD(void, cairo_show_text, (cairo_t * cr, const char* utf8), (cr, utf8))
CAIRO_FORWARD(const char*, cairo_status_to_string, (cairo_status_t status), (status))
CAIRO_FORWARD(void, cairo_stroke, (cairo_t * cr), (cr))
CAIRO_FORWARD(void, cairo_surface_destroy, (cairo_surface_t * surface), (surface))
CAIRO_FORWARD(void, cairo_surface_finish, (cairo_surface_t * surface), (surface))
CAIRO_FORWARD(void, cairo_surface_flush, (cairo_surface_t * surface), (surface))
CAIRO_FORWARD(void, cairo_surface_mark_dirty, (cairo_surface_t * surface), (surface))
CAIRO_FORWARD(cairo_status_t, cairo_surface_status, (cairo_surface_t * surface), (surface))
CAIRO_FORWARD(cairo_status_t, cairo_surface_write_to_png,
              (cairo_surface_t * surface, const char* filename), (surface, filename))
CAIRO_FORWARD(cairo_surface_t*, cairo_svg_surface_create,
              (const char* filename, double width_in_points, double height_in_points),
              (filename, width_in_points, height_in_points))
CAIRO_FORWARD(void, cairo_translate, (cairo_t * cr, double tx, double ty), (cr, tx, ty))
}  // extern "C"
