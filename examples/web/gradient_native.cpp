// gradient_native.cpp - the native half of module-test.mjs's gradient and surface checks: the value and
// gradient of an asset at the points given, from the native runtime (dsn_lattice_gradient_fixed, or
// dsn_continuous_gradient_fixed at dsn_coordinate_from_double of each coordinate), configured as dsn.mjs
// configures it (the asset's density, the continuous mode allowed), one line per point: the Q16.16
// integers of the value, then of dx, then of dy. In surface mode a point is six numbers, its position
// and its normal, and its line the Q16.16 surface noise there (dsn_surface_point_float's conversions:
// the position as doubles, the normal as floats, no tangent); in filtered-surface mode a point has five
// numbers more, its footprint (dsn_footprint_from_float's four derivatives and max_taps), and its line is
// dsn_surface_filtered_point_fixed's.
// Usage: dsn-web-gradient-native ASSET.dsnt SEED PERIOD_X PERIOD_Y lattice|continuous X Y [X Y ...]
//        dsn-web-gradient-native ASSET.dsnt SEED PERIOD_X PERIOD_Y surface X Y Z NX NY NZ [...]
//        dsn-web-gradient-native ASSET.dsnt SEED PERIOD_X PERIOD_Y filtered-surface X Y Z NX NY NZ
//            UX VX UY VY TAPS [...]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "dsn/dsn.h"

int main(int argc, char **argv) {
    const bool filtered = argc > 5 && std::strcmp(argv[5], "filtered-surface") == 0;
    const bool surface = filtered || (argc > 5 && std::strcmp(argv[5], "surface") == 0);
    const int arity = filtered ? 11 : surface ? 6 : 2;
    if (argc < 6 + arity || (argc - 6) % arity != 0 ||
        (!surface && std::strcmp(argv[5], "lattice") != 0 && std::strcmp(argv[5], "continuous") != 0)) {
        std::fprintf(stderr, "usage: dsn-web-gradient-native ASSET.dsnt SEED PERIOD_X PERIOD_Y "
                             "lattice|continuous X Y [X Y ...] | surface X Y Z NX NY NZ [...] | "
                             "filtered-surface X Y Z NX NY NZ UX VX UY VY TAPS [...]\n");
        return 2;
    }
    std::ifstream file(argv[1], std::ios::binary);
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    const bool continuous = std::strcmp(argv[5], "continuous") == 0;
    dsn_asset asset;
    dsn_noise noise;
    dsn_config config;
    int err = dsn_asset_load(&asset, bytes.data(), bytes.size());
    dsn_config_defaults(&config);
    config.seed = static_cast<uint32_t>(std::strtoul(argv[2], nullptr, 10));
    config.period_x = static_cast<uint32_t>(std::strtoul(argv[3], nullptr, 10));
    config.period_y = static_cast<uint32_t>(std::strtoul(argv[4], nullptr, 10));
    config.flags = DSN_FLAG_ALLOW_LATTICE_CONTINUOUS;
    if (err == DSN_OK) err = dsn_noise_init(&noise, &asset, &config);
    const uint32_t channels = err == DSN_OK ? dsn_noise_channels(&noise) : 0;
    for (int i = 6; err == DSN_OK && surface && i + arity - 1 < argc; i += arity) {
        const float normal[3] = {std::strtof(argv[i + 3], nullptr), std::strtof(argv[i + 4], nullptr),
                                 std::strtof(argv[i + 5], nullptr)};
        dsn_surface_frame frame;
        int32_t value[DSN_MAX_CHANNELS];
        const int64_t position[3] = {dsn_coordinate_from_double(std::strtod(argv[i], nullptr)),
                                     dsn_coordinate_from_double(std::strtod(argv[i + 1], nullptr)),
                                     dsn_coordinate_from_double(std::strtod(argv[i + 2], nullptr))};
        err = dsn_surface_frame_from_float(normal, nullptr, &frame);
        dsn_footprint footprint;
        if (err == DSN_OK && filtered)
            err = dsn_footprint_from_float(
                &footprint, std::strtod(argv[i + 6], nullptr), std::strtod(argv[i + 7], nullptr),
                std::strtod(argv[i + 8], nullptr), std::strtod(argv[i + 9], nullptr),
                static_cast<uint32_t>(std::strtoul(argv[i + 10], nullptr, 10)));
        if (err == DSN_OK)
            err = filtered ? dsn_surface_filtered_point_fixed(&noise, position, &frame, &footprint, value)
                           : dsn_surface_point_fixed(&noise, position, &frame, value);
        for (uint32_t c = 0; err == DSN_OK && c < channels; c++)
            std::printf(c == 0 ? "%d" : " %d", static_cast<int>(value[c]));
        if (err == DSN_OK) std::printf("\n");
    }
    for (int i = 6; err == DSN_OK && !surface && i + 1 < argc; i += 2) {
        int32_t value[DSN_MAX_CHANNELS], dx[DSN_MAX_CHANNELS], dy[DSN_MAX_CHANNELS];
        if (continuous)
            err = dsn_continuous_gradient_fixed(
                &noise, dsn_coordinate_from_double(std::strtod(argv[i], nullptr)),
                dsn_coordinate_from_double(std::strtod(argv[i + 1], nullptr)), value, dx, dy);
        else
            err = dsn_lattice_gradient_fixed(&noise, static_cast<int32_t>(std::strtoll(argv[i], nullptr, 10)),
                                             static_cast<int32_t>(std::strtoll(argv[i + 1], nullptr, 10)),
                                             value, dx, dy);
        if (err != DSN_OK) break;
        const int32_t *parts[3] = {value, dx, dy};
        for (uint32_t k = 0; k < 3 * channels; k++)
            std::printf(k == 0 ? "%d" : " %d", static_cast<int>(parts[k / channels][k % channels]));
        std::printf("\n");
    }
    if (err != DSN_OK) {
        std::fprintf(stderr, "dsn-web-gradient-native: %s\n", dsn_error_message(err));
        return 1;
    }
    return 0;
}
