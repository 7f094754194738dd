// render_window.h - the window a rendering tool covers, read from its command line (part of
// libdsn_tools.a): every tool that renders (dsn-render, dsn-gpu-render) reads --origin, --scale and
// --rotate through these, so their outputs for the same options are the same pixels.
#ifndef DSN_TOOLS_RENDER_WINDOW_H
#define DSN_TOOLS_RENDER_WINDOW_H

#include <stdint.h>

#include <string>

#include "dsn/dsn.h"

namespace dsn {

// A lattice origin: a decimal integer taken modulo 2^32 (-1 and 4294967295 are the same point). UsageError
// naming --origin otherwise.
int32_t lattice_origin(const std::string &text);

// The continuous grid of a rotated, scaled window: pixel (i, j) samples
// origin + (i cos a - j sin a, i sin a + j cos a) / scale, a = rotate_degrees. The angle is reduced
// exactly (fmod) before any trigonometry, so a huge angle keeps its meaning. The origin is two decimal
// reals (UsageError naming --origin otherwise).
dsn_grid rotated_grid(const std::string &origin_x, const std::string &origin_y, double scale,
                      double rotate_degrees);
// The same with a scale of its own along the window's x and y (before the rotation): pixel (i, j)
// samples origin + (i cos a / scale_x - j sin a / scale_y, i sin a / scale_x + j cos a / scale_y).
// Equal scales give rotated_grid's steps bit for bit.
dsn_grid rotated_grid(const std::string &origin_x, const std::string &origin_y, double scale_x,
                      double scale_y, double rotate_degrees);

} // namespace dsn

#endif // DSN_TOOLS_RENDER_WINDOW_H
