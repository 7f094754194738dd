// fuzz_image_input.cpp - arbitrary bytes -> the baker's image input (size caps before decoding) -> when an
// image comes out, a tiny bake of its top-left corner, whose asset the runtime loader must accept.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "dsn/bake.h"
#include "dsn/dsn.h"
#include "fuzz_input.h"

namespace {

// The top-left corner, small enough that a bake takes microseconds.
dsn::Image corner(const dsn::Image &image, int side) {
    dsn::Image small;
    small.width = image.width < side ? image.width : side;
    small.height = image.height < side ? image.height : side;
    small.channels = image.channels;
    small.values.resize(size_t(small.width) * size_t(small.height) * size_t(small.channels));
    for (int c = 0; c < small.channels; c++)
        for (int y = 0; y < small.height; y++)
            for (int x = 0; x < small.width; x++) small.at(x, y, c) = image.at(x, y, c);
    return small;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    dsn::Image image;
    std::vector<std::string> warnings;
    try {
        image = dsn::decode_exemplar(data, size, "fuzz", &warnings);
    } catch (const std::runtime_error &) {
        return 0; // refused with a message: what bad input should get
    }
    fuzz_require(image.width > 0 && image.height > 0 && (image.channels == 1 || image.channels == 3));
    fuzz_require(image.values.size() == size_t(image.width) * size_t(image.height) * size_t(image.channels));
    for (double value : image.values) fuzz_require(value >= 0.0 && value <= 1.0);

    FuzzInput options_input(data, size < 8 ? size : 8);
    dsn::BakeOptions options;
    options.radius = 1 + int(options_input.byte() % 2u);
    options.shape = options_input.byte() & 1u;
    options.iterations = 2;
    options.bits = (options_input.byte() & 1u) ? 16 : 8;
    options.interpolation = options_input.byte() & 1u;
    dsn::BakeResult result;
    try {
        const dsn::Image small = corner(image, 12);
        dsn::check_bake_input(small, options);
        result = dsn::bake(small, options);
    } catch (const std::runtime_error &) {
        return 0; // too small, constant, ...: refused with a message
    } catch (const std::invalid_argument &) {
        return 0;
    }
    dsn_asset asset;
    fuzz_require(dsn_asset_load(&asset, result.asset.data(), result.asset.size()) == DSN_OK);
    return 0;
}
