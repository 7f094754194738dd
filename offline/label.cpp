// label.cpp - draw_label: stb_easy_font's quads filled pixel by pixel.
#include "label.h"

#include <algorithm>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace dsn {

void draw_label(std::vector<unsigned char> &rgb, int width, int height, int x, int y, const std::string &text,
                int scale, unsigned char grey) {
    std::vector<char> buffer(text.begin(), text.end());
    buffer.push_back('\0');
    std::vector<float> vertices(text.size() * 300 + 64); // ~270 bytes of quads per character, 16 per vertex
    unsigned char color[4] = {grey, grey, grey, 255};
    const int quads = stb_easy_font_print(0, 0, buffer.data(), color, vertices.data(),
                                          int(vertices.size() * sizeof(float)));
    for (int q = 0; q < quads; q++) {
        const float *v = &vertices[size_t(q) * 16]; // 4 vertices of (x, y, z, colour)
        const int left = x + int(v[0] * float(scale)), top = y + int(v[1] * float(scale));
        const int right = x + int(v[8] * float(scale)), bottom = y + int(v[9] * float(scale));
        for (int py = std::max(0, top); py < std::min(height, bottom); py++)
            for (int px = std::max(0, left); px < std::min(width, right); px++)
                std::fill_n(&rgb[(size_t(py) * size_t(width) + size_t(px)) * 3], 3, grey);
    }
}

int label_width(const std::string &text, int scale) {
    std::vector<char> buffer(text.begin(), text.end());
    buffer.push_back('\0');
    return stb_easy_font_width(buffer.data()) * scale;
}

} // namespace dsn
