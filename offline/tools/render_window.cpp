// render_window.cpp - the window a rendering tool covers (render_window.h).
#include "render_window.h"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>

#include "command_line.h"

namespace dsn {
namespace {

int64_t q32_step(double texels) { return static_cast<int64_t>(std::llround(texels * 4294967296.0)); }

} // namespace

int32_t lattice_origin(const std::string &text) {
    char *end = nullptr;
    errno = 0;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0 || value < -4294967296LL || value > 4294967295LL)
        throw UsageError("--origin: '" + text + "' is not an integer (use --mode continuous for reals)");
    const uint32_t wrapped = static_cast<uint32_t>(static_cast<unsigned long long>(value));
    return wrapped >= 0x80000000u ? static_cast<int32_t>(wrapped - 0x80000000u) + INT32_MIN
                                  : static_cast<int32_t>(wrapped);
}

dsn_grid rotated_grid(const std::string &origin_x, const std::string &origin_y, double scale,
                      double rotate_degrees) {
    return rotated_grid(origin_x, origin_y, scale, scale, rotate_degrees);
}

dsn_grid rotated_grid(const std::string &origin_x, const std::string &origin_y, double scale_x,
                      double scale_y, double rotate_degrees) {
    const double radians = std::fmod(rotate_degrees, 360.0) * 3.14159265358979323846 / 180.0;
    const double cosine = std::cos(radians), sine = std::sin(radians);
    dsn_grid grid;
    grid.origin_x = dsn_coordinate_from_double(parse_real("--origin", origin_x));
    grid.origin_y = dsn_coordinate_from_double(parse_real("--origin", origin_y));
    grid.column_step_x = q32_step(cosine / scale_x);
    grid.column_step_y = q32_step(sine / scale_x);
    grid.row_step_x = q32_step(-sine / scale_y);
    grid.row_step_y = q32_step(cosine / scale_y);
    return grid;
}

} // namespace dsn
