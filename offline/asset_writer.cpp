// asset_writer.cpp - encodes AssetFields into the .dsnt byte layout of format.h: a 1.0 file, or a 1.1 file
// with a pyramid section when the fields have pyramid levels.
#include "dsn/asset_writer.h"
#include "../runtime/format_bytes.h"

#include <cstring>
#include <stdexcept>
#include <string>

namespace dsn {
namespace {

void require(bool condition, const char *message) {
    if (!condition) throw std::invalid_argument(std::string("asset: ") + message);
}

bool is_valid_side(uint32_t side) { return side >= 1 && side <= DSN_FORMAT_MAX_SIDE && side % 2 == 1; }

// The same checks as the loader's steps 9-13 (format.h), so that no written asset is rejected.
void validate(const AssetFields &fields) {
    require(fields.channels == 1 || fields.channels == 3, "channels must be 1 or 3");
    require(fields.bits == 8 || fields.bits == 16, "bits must be 8 or 16");
    require(fields.shape == DSN_SHAPE_RECTANGLE || fields.shape == DSN_SHAPE_DISK, "unknown shape");
    require(fields.shape != DSN_SHAPE_DISK || fields.width == fields.height, "a disk texton must be square");
    require(fields.interpolation == DSN_INTERPOLATION_LATTICE ||
                fields.interpolation == DSN_INTERPOLATION_BILINEAR,
            "unknown interpolation");
    require(is_valid_side(fields.width) && is_valid_side(fields.height),
            "texton width and height must be odd, 1..255");
    require(fields.default_impacts_q16 == 0 || (fields.default_impacts_q16 >= DSN_IMPACTS_MIN_Q16 &&
                                                fields.default_impacts_q16 <= DSN_IMPACTS_MAX_Q16),
            "default impacts per pixel out of range");
    for (uint32_t c = 0; c < 3; c++) {
        bool used = c < fields.channels;
        require(!used || fields.scale[c] != 0, "a used channel has scale 0");
        require(used || (fields.scale[c] == 0 && fields.mean[c] == 0), "unused channel fields must be 0");
    }
    if (fields.channels == 1)
        for (int i = 1; i < 9; i++) require(fields.color_transform[i] == 0, "grey transform must be 1x1");
    require(fields.exemplar_width <= 0xFFFFu && fields.exemplar_height <= 0xFFFFu,
            "exemplar size must fit 16 bits");
    require(fields.texton.size() == size_t(fields.width) * fields.height * fields.channels,
            "texton must hold width * height * channels values");
    const int32_t limit = fields.bits == 8 ? 127 : 32767;
    size_t index = 0;
    for (uint32_t row = 0; row < fields.height; row++)
        for (uint32_t column = 0; column < fields.width; column++)
            for (uint32_t c = 0; c < fields.channels; c++, index++) {
                int32_t value = fields.texton[index];
                require(value >= -limit && value <= limit, "texton value outside the quantization range");
                require(value == 0 || dsn_in_support(fields.shape, fields.width, row, column),
                        "texton value outside the disk support");
            }
    require(fields.pyramid.size() <= DSN_PYRAMID_MAX_LEVELS, "at most 8 pyramid levels");
    for (const PyramidLevel &level : fields.pyramid) {
        require(is_valid_side(level.width) && is_valid_side(level.height),
                "pyramid level width and height must be odd, 1..255");
        require(level.exponent >= DSN_PYRAMID_EXPONENT_MIN && level.exponent <= DSN_PYRAMID_EXPONENT_MAX,
                "pyramid level exponent outside -24..24");
        require(level.values.size() == size_t(level.width) * level.height * fields.channels,
                "pyramid level must hold width * height * channels values");
        for (int32_t value : level.values)
            require(value >= -limit && value <= limit, "pyramid value outside the quantization range");
    }
}

// The payload of the pyramid section (format.h, section kind 1).
std::vector<unsigned char> encode_pyramid(const AssetFields &fields) {
    const size_t value_bytes = fields.bits / 8;
    std::vector<unsigned char> payload(DSN_PYRAMID_HEADER_SIZE +
                                       DSN_PYRAMID_RECORD_SIZE * fields.pyramid.size());
    payload[0] = uint8_t(fields.pyramid.size());
    for (size_t l = 0; l < fields.pyramid.size(); l++) {
        unsigned char *record = &payload[DSN_PYRAMID_HEADER_SIZE + DSN_PYRAMID_RECORD_SIZE * l];
        record[0] = uint8_t(fields.pyramid[l].width);
        record[1] = uint8_t(fields.pyramid[l].height);
        record[2] = uint8_t(fields.pyramid[l].exponent & 0xFF);
    }
    for (const PyramidLevel &level : fields.pyramid)
        for (int32_t value : level.values) {
            payload.push_back(uint8_t(value & 0xFF));
            if (value_bytes == 2) payload.push_back(uint8_t((value >> 8) & 0xFF));
        }
    return payload;
}

} // namespace

void set_identity_color_transform(AssetFields &fields) {
    for (int i = 0; i < 9; i++) fields.color_transform[i] = 0;
    for (uint32_t c = 0; c < fields.channels && c < 3; c++) fields.color_transform[c * 3 + c] = DSN_Q24_ONE;
}

std::vector<unsigned char> encode_asset(const AssetFields &fields) {
    validate(fields);
    const size_t value_bytes = fields.bits / 8;
    const bool has_pyramid = !fields.pyramid.empty();
    const std::vector<unsigned char> pyramid =
        has_pyramid ? encode_pyramid(fields) : std::vector<unsigned char>();
    const size_t padding =
        (DSN_SECTION_ALIGNMENT - pyramid.size() % DSN_SECTION_ALIGNMENT) % DSN_SECTION_ALIGNMENT;
    const size_t header_size =
        DSN_FORMAT_HEADER_SIZE + (has_pyramid ? DSN_SECTION_HEADER_SIZE + pyramid.size() + padding : 0);
    const size_t total = header_size + fields.texton.size() * value_bytes + DSN_FORMAT_CRC_SIZE;
    std::vector<unsigned char> bytes(total, 0);
    unsigned char *p = bytes.data();
    std::memcpy(p, DSN_FORMAT_MAGIC, DSN_FORMAT_MAGIC_SIZE);
    dsn_write_u16le(p + DSN_OFFSET_VERSION_MAJOR, DSN_FORMAT_VERSION_MAJOR);
    dsn_write_u16le(p + DSN_OFFSET_VERSION_MINOR,
                    has_pyramid ? DSN_FORMAT_SECTIONS_MINOR : DSN_FORMAT_VERSION_MINOR_PLAIN);
    dsn_write_u32le(p + DSN_OFFSET_HEADER_SIZE, uint32_t(header_size));
    dsn_write_u32le(p + DSN_OFFSET_TOTAL_SIZE, uint32_t(total));
    p[DSN_OFFSET_CHANNELS] = uint8_t(fields.channels);
    p[DSN_OFFSET_BITS] = uint8_t(fields.bits);
    p[DSN_OFFSET_SHAPE] = uint8_t(fields.shape);
    p[DSN_OFFSET_INTERPOLATION] = uint8_t(fields.interpolation);
    dsn_write_u16le(p + DSN_OFFSET_WIDTH, uint16_t(fields.width));
    dsn_write_u16le(p + DSN_OFFSET_HEIGHT, uint16_t(fields.height));
    dsn_write_u32le(p + DSN_OFFSET_DEFAULT_IMPACTS, fields.default_impacts_q16);
    for (int c = 0; c < 3; c++) {
        dsn_write_u32le(p + DSN_OFFSET_SCALE + 4 * c, fields.scale[c]);
        dsn_write_i32le(p + DSN_OFFSET_MEAN + 4 * c, fields.mean[c]);
    }
    for (int i = 0; i < 9; i++)
        dsn_write_i32le(p + DSN_OFFSET_COLOR_TRANSFORM + 4 * i, fields.color_transform[i]);
    dsn_write_u32le(p + DSN_OFFSET_BAKE_ITERATIONS, fields.bake_iterations);
    dsn_write_u32le(p + DSN_OFFSET_BAKE_SEED, fields.bake_seed);
    dsn_write_u32le(p + DSN_OFFSET_BAKE_RME, fields.bake_rme_q24);
    dsn_write_u16le(p + DSN_OFFSET_EXEMPLAR_WIDTH, uint16_t(fields.exemplar_width));
    dsn_write_u16le(p + DSN_OFFSET_EXEMPLAR_HEIGHT, uint16_t(fields.exemplar_height));
    if (has_pyramid) {
        dsn_write_u32le(p + DSN_FORMAT_HEADER_SIZE, DSN_SECTION_PYRAMID);
        dsn_write_u32le(p + DSN_FORMAT_HEADER_SIZE + 4, uint32_t(pyramid.size()));
        std::memcpy(p + DSN_FORMAT_HEADER_SIZE + DSN_SECTION_HEADER_SIZE, pyramid.data(), pyramid.size());
    }
    unsigned char *texton = p + header_size;
    for (size_t i = 0; i < fields.texton.size(); i++) {
        if (value_bytes == 1)
            texton[i] = uint8_t(fields.texton[i] & 0xFF);
        else
            dsn_write_u16le(texton + 2 * i, uint16_t(fields.texton[i] & 0xFFFF));
    }
    dsn_write_u32le(p + total - DSN_FORMAT_CRC_SIZE, dsn_crc32(0, p, total - DSN_FORMAT_CRC_SIZE));
    return bytes;
}

} // namespace dsn
