// label.h - text drawn into an 8-bit RGB picture (the labels of the bake preview and of the demo's
// contact sheet), rasterized from stb_easy_font's quads. Internal to libdsn_bake.a.
#ifndef DSN_OFFLINE_LABEL_H
#define DSN_OFFLINE_LABEL_H

#include <string>
#include <vector>

namespace dsn {

// Draws `text` with its top-left corner at (x, y) of the width x height RGB picture `rgb` (3 bytes per
// pixel, row-major), `scale` pixels per font unit (a line is about 12 scale pixels high), every channel
// set to `grey`; what falls outside the picture is clipped.
void draw_label(std::vector<unsigned char> &rgb, int width, int height, int x, int y, const std::string &text,
                int scale, unsigned char grey);

// Width in pixels of `text` drawn at `scale`.
int label_width(const std::string &text, int scale);

} // namespace dsn

#endif // DSN_OFFLINE_LABEL_H
