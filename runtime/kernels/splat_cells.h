/* runtime/kernels/splat_cells.h - the texton (or a pyramid level) as the vector splat of grids reads it
   (splat_row.h): one 64-bit record per cell and channel, a cell being the 2 x 2 texels whose top-left texel
   is (row, column) for row in [-1, height - 1] and column in [-1, width - 1] (texels outside the window are
   0), so that every pixel within reach reads one record per channel, wherever it lies, with no bounds check.
   Built per tile by grid_splat.cpp. Internal to libdsn; not installed.

   A record holds four int16 words, low first: -(TL + TR), TR - TL, -(BL + BR - TL - TR) and
   TL - TR - BL + BR (T, B: top and bottom row; L, R: left and right column). Multiplied-and-added in
   pairs with the words (-32768, a - 32768), a the upper weight across, they give
     32768 (TL + TR) + (a - 32768) (TR - TL)                  = 65536 TL + a (TR - TL)      = upper,
     32768 (BL + BR - TL - TR) + (a - 32768) (TL - TR - BL + BR) = 65536 (BL - TL) + a (...) = lower - upper,
   interior_channel's two integers (bilinear_texton.h, splat_row.h), each below 2^25 and every word within
   int16 for 8-bit textons; 16-bit textons have no records. */
#ifndef DSN_SPLAT_CELLS_H
#define DSN_SPLAT_CELLS_H

#include "core/bilinear_texton.h"
#include "kernels/kernels.h"

/* DSN_SPLAT_CELLS: the x86 kernels read records (the tile builds them); elsewhere the runs go pixel by
   pixel and no table is kept on the stack. */
#if defined(__SSE2__) && !DSN_SMALL_CODE
#define DSN_SPLAT_CELLS 1
#else
#define DSN_SPLAT_CELLS 0
#endif

namespace {

/* Records kept on the tile call's stack at most (64 KB): RGB textons up to 49 x 49 (radius 24), grey up to
   89 x 89; larger ones go pixel by pixel. */
const uint32_t splat_cell_capacity = 8192;

inline uint64_t splat_word(int32_t value) {
    return static_cast<uint64_t>(static_cast<uint32_t>(value) & 0xFFFFu);
}

/* Value `channel` of texel (row, column) of the texture; 0 outside its window (-1 too: unsigned). */
inline int32_t texture_texel(const dsn_splat_texture &texture, uint32_t row, uint32_t column,
                             uint32_t channel) {
    if (row >= texture.height || column >= texture.width) return 0;
    const uint32_t index = (row * texture.stride + column) * texture.channels + channel;
    return texture.bits == 8 ? dsn_read_i8(texture.values + index)
                             : dsn_read_i16le(texture.values + 2u * index);
}

/* Fills `cells` (`capacity` records at most) and sets *cell_row (cells per row: width + 1 + margin; each
   cell has one record per channel, in order, RGB cells padded to 4), and returns the records used, or 0
   when the texture has no records (16-bit, or too large). A margin of 1 adds a row and a column of cells
   past the window, all zero: the gradient's runs reach offsets of exactly the reach (grid_splat.h). */
inline uint32_t make_splat_cells(const dsn_splat_texture &texture, uint64_t *cells, uint32_t capacity,
                                 uint32_t *cell_row, uint32_t margin) {
    const uint32_t channels = texture.channels, columns = texture.width + 1u + margin,
                   rows = texture.height + 1u + margin;
    const uint32_t cell_records = channels == 3 ? 4u : 1u;
    if (texture.bits != 8 || static_cast<uint64_t>(columns) * rows * cell_records > capacity) return 0;
    *cell_row = columns;
    uint64_t *record = cells;
    for (uint32_t row = 0; row < rows; row++)
        for (uint32_t column = 0; column < columns; column++)
            for (uint32_t c = 0; c < cell_records; c++) {
                if (c == channels) { /* the padding */
                    *record++ = 0;
                    continue;
                }
                /* Texel indices row - 1 and column - 1: -1 wraps to 0xFFFFFFFF, outside like width. */
                const int32_t top_left = texture_texel(texture, row - 1u, column - 1u, c),
                              top_right = texture_texel(texture, row - 1u, column, c),
                              bottom_left = texture_texel(texture, row, column - 1u, c),
                              bottom_right = texture_texel(texture, row, column, c);
                *record++ = splat_word(-(top_left + top_right)) | splat_word(top_right - top_left) << 16 |
                            splat_word(top_left + top_right - bottom_left - bottom_right) << 32 |
                            splat_word(top_left - top_right - bottom_left + bottom_right) << 48;
            }
    return columns * rows * cell_records;
}

} // namespace

#endif /* DSN_SPLAT_CELLS_H */
