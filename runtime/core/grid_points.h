/* runtime/core/grid_points.h - the points of a grid tile (dsn.h's dsn_grid) in the tile's order, for the
   tiles evaluated point by point (continuous, filtered and gradient): pixel (i, j) is origin + i column_step
   + j row_step modulo 2^64, stepped by additions, its values at index (j width + i) channels of the
   output. Internal to libdsn; not installed. */
#ifndef DSN_GRID_POINTS_H
#define DSN_GRID_POINTS_H

#include <stddef.h>
#include <stdint.h>

#include "dsn/dsn.h"

/* visit(index, x, y) for every pixel of a width x height tile, row by row. */
template <typename Visit>
inline void dsn_grid_points(const dsn_grid *grid, uint32_t width, uint32_t height, uint32_t channels,
                            const Visit &visit) {
    uint64_t row_x = static_cast<uint64_t>(grid->origin_x), row_y = static_cast<uint64_t>(grid->origin_y);
    size_t index = 0;
    for (uint32_t j = 0; j < height; j++) {
        uint64_t point_x = row_x, point_y = row_y;
        for (uint32_t i = 0; i < width; i++, index += channels) {
            visit(index, point_x, point_y);
            point_x += static_cast<uint64_t>(grid->column_step_x);
            point_y += static_cast<uint64_t>(grid->column_step_y);
        }
        row_x += static_cast<uint64_t>(grid->row_step_x);
        row_y += static_cast<uint64_t>(grid->row_step_y);
    }
}

#endif /* DSN_GRID_POINTS_H */
