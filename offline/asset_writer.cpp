// asset_writer.cpp - encodes AssetFields into the .dsnt byte layout of format.h: a 1.0 file, a 1.1 file
// with a pyramid section when the fields have pyramid levels, a 1.2 file with the histogram flag and
// section when they have a histogram mapping, a 1.3 file when they have a lattice texton.
#include "dsn/asset_writer.h"
#include "runtime/setup/format_bytes.h"

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

// The loader's step 17 (format.h) on a lattice texton that is to be written.
void validate_lattice_texton(const AssetFields &fields) {
    require(fields.interpolation == DSN_INTERPOLATION_BILINEAR, "a lattice texton needs a bilinear asset");
    require(is_valid_side(fields.lattice_width) && is_valid_side(fields.lattice_height),
            "lattice texton width and height must be odd, 1..255");
    require(fields.lattice_texton.size() ==
                size_t(fields.lattice_width) * fields.lattice_height * fields.channels,
            "lattice texton must hold lattice_width * lattice_height * channels values");
    const int32_t limit = fields.bits == 8 ? 127 : 32767;
    for (uint32_t c = 0; c < fields.channels; c++) {
        int64_t sum = 0, lattice_sum = 0;
        for (size_t i = c; i < fields.texton.size(); i += fields.channels) sum += fields.texton[i];
        for (size_t i = c; i < fields.lattice_texton.size(); i += fields.channels) {
            const int32_t value = fields.lattice_texton[i];
            require(value >= -limit && value <= limit, "lattice texton value outside the quantization range");
            lattice_sum += value;
        }
        require(sum == lattice_sum, "the lattice texton's sum differs from the texton's");
    }
}

// Texton-like values (i8 or i16 little-endian as `bits`) appended to `bytes`.
void append_values(std::vector<unsigned char> &bytes, const std::vector<int32_t> &values, uint32_t bits) {
    for (int32_t value : values) {
        bytes.push_back(uint8_t(value & 0xFF));
        if (bits == 16) bytes.push_back(uint8_t((value >> 8) & 0xFF));
    }
}

// The payload of the lattice texton section (format.h, section kind 3).
std::vector<unsigned char> encode_lattice_texton(const AssetFields &fields) {
    std::vector<unsigned char> payload(DSN_LATTICE_TEXTON_HEADER_SIZE, 0);
    payload[0] = uint8_t(fields.lattice_width);
    payload[1] = uint8_t(fields.lattice_height);
    append_values(payload, fields.lattice_texton, fields.bits);
    return payload;
}

// The loader's step 16 (format.h) on a mapping that is to be written (non-empty tables).
void validate_histogram(const AssetFields &fields) {
    const HistogramMapping &mapping = fields.histogram;
    require(mapping.entry_count >= 2 && mapping.entry_count <= DSN_HISTOGRAM_MAX_ENTRIES,
            "histogram entry count outside 2..1024");
    require(mapping.level_count >= 1 && mapping.level_count <= 1 + fields.pyramid.size(),
            "histogram level count outside 1..1 + pyramid levels");
    require(mapping.step_shift <= DSN_HISTOGRAM_MAX_STEP_SHIFT, "histogram step shift above 16");
    require(mapping.tables.size() == size_t(mapping.level_count) * fields.channels * mapping.entry_count,
            "histogram tables must hold level_count * channels * entry_count values");
    for (int32_t value : mapping.tables)
        require(value >= -DSN_HISTOGRAM_VALUE_LIMIT && value <= DSN_HISTOGRAM_VALUE_LIMIT,
                "histogram table value outside -32767..32767");
    if (fields.channels == 1)
        for (int i = 1; i < 9; i++) require(mapping.rotation[i] == 0, "grey histogram rotation must be 1x1");
    for (uint32_t c = 0; c < 3; c++) {
        require(c < fields.channels || (mapping.centre[c] == 0 && mapping.expected_q16[c] == 0),
                "unused channel histogram fields must be 0");
        require(mapping.expected_q16[c] >= -DSN_HISTOGRAM_EXPECTED_LIMIT &&
                    mapping.expected_q16[c] <= DSN_HISTOGRAM_EXPECTED_LIMIT,
                "histogram expected value outside the tables' range");
    }
}

// The payload of the histogram section (format.h, section kind 2).
std::vector<unsigned char> encode_histogram(const HistogramMapping &mapping) {
    std::vector<unsigned char> payload(DSN_HISTOGRAM_HEADER_SIZE + 2 * mapping.tables.size());
    unsigned char *p = payload.data();
    dsn_write_u16le(p, uint16_t(mapping.entry_count));
    p[2] = uint8_t(mapping.level_count);
    p[3] = uint8_t(mapping.step_shift);
    dsn_write_i32le(p + 4, mapping.input_low_q16);
    for (int i = 0; i < 9; i++) dsn_write_i32le(p + 8 + 4 * i, mapping.rotation[i]);
    for (int c = 0; c < 3; c++) {
        dsn_write_i32le(p + 44 + 4 * c, mapping.centre[c]);
        dsn_write_i32le(p + 56 + 4 * c, mapping.expected_q16[c]);
    }
    for (size_t i = 0; i < mapping.tables.size(); i++)
        dsn_write_u16le(p + DSN_HISTOGRAM_HEADER_SIZE + 2 * i, uint16_t(mapping.tables[i] & 0xFFFF));
    return payload;
}

// Appends one section (kind, size, payload, zero padding to 4 bytes) to the header bytes.
void append_section(std::vector<unsigned char> &header, uint32_t kind,
                    const std::vector<unsigned char> &payload) {
    const size_t start = header.size();
    const size_t padding =
        (DSN_SECTION_ALIGNMENT - payload.size() % DSN_SECTION_ALIGNMENT) % DSN_SECTION_ALIGNMENT;
    header.resize(start + DSN_SECTION_HEADER_SIZE + payload.size() + padding, 0);
    dsn_write_u32le(&header[start], kind);
    dsn_write_u32le(&header[start + 4], uint32_t(payload.size()));
    std::memcpy(&header[start + DSN_SECTION_HEADER_SIZE], payload.data(), payload.size());
}

// The payload of the pyramid section (format.h, section kind 1).
std::vector<unsigned char> encode_pyramid(const AssetFields &fields) {
    std::vector<unsigned char> payload(DSN_PYRAMID_HEADER_SIZE +
                                       DSN_PYRAMID_RECORD_SIZE * fields.pyramid.size());
    payload[0] = uint8_t(fields.pyramid.size());
    for (size_t l = 0; l < fields.pyramid.size(); l++) {
        unsigned char *record = &payload[DSN_PYRAMID_HEADER_SIZE + DSN_PYRAMID_RECORD_SIZE * l];
        record[0] = uint8_t(fields.pyramid[l].width);
        record[1] = uint8_t(fields.pyramid[l].height);
        record[2] = uint8_t(fields.pyramid[l].exponent & 0xFF);
    }
    for (const PyramidLevel &level : fields.pyramid) append_values(payload, level.values, fields.bits);
    return payload;
}

} // namespace

void set_identity_color_transform(AssetFields &fields) {
    for (int i = 0; i < 9; i++) fields.color_transform[i] = 0;
    for (uint32_t c = 0; c < fields.channels && c < 3; c++) fields.color_transform[c * 3 + c] = DSN_Q24_ONE;
}

std::vector<unsigned char> encode_asset(const AssetFields &fields) {
    validate(fields);
    const bool has_histogram = !fields.histogram.tables.empty();
    if (has_histogram) validate_histogram(fields);
    const size_t value_bytes = fields.bits / 8;
    const bool has_pyramid = !fields.pyramid.empty();
    const bool has_lattice_texton = !fields.lattice_texton.empty();
    if (has_lattice_texton) validate_lattice_texton(fields);
    std::vector<unsigned char> header(DSN_FORMAT_HEADER_SIZE, 0);
    if (has_pyramid) append_section(header, DSN_SECTION_PYRAMID, encode_pyramid(fields));
    if (has_histogram) append_section(header, DSN_SECTION_HISTOGRAM, encode_histogram(fields.histogram));
    if (has_lattice_texton) append_section(header, DSN_SECTION_LATTICE_TEXTON, encode_lattice_texton(fields));
    const size_t header_size = header.size();
    const size_t total = header_size + fields.texton.size() * value_bytes + DSN_FORMAT_CRC_SIZE;
    std::vector<unsigned char> bytes(total, 0);
    unsigned char *p = bytes.data();
    std::memcpy(p, header.data(), header_size);
    std::memcpy(p, DSN_FORMAT_MAGIC, DSN_FORMAT_MAGIC_SIZE);
    dsn_write_u16le(p + DSN_OFFSET_VERSION_MAJOR, DSN_FORMAT_VERSION_MAJOR);
    dsn_write_u16le(p + DSN_OFFSET_VERSION_MINOR, has_lattice_texton ? DSN_FORMAT_LATTICE_TEXTON_MINOR
                                                  : has_histogram    ? DSN_FORMAT_HISTOGRAM_MINOR
                                                  : has_pyramid      ? DSN_FORMAT_SECTIONS_MINOR
                                                                     : DSN_FORMAT_VERSION_MINOR_PLAIN);
    dsn_write_u32le(p + DSN_OFFSET_HEADER_SIZE, uint32_t(header_size));
    dsn_write_u32le(p + DSN_OFFSET_TOTAL_SIZE, uint32_t(total));
    dsn_write_u32le(p + DSN_OFFSET_FLAGS, has_histogram ? DSN_FLAG_HISTOGRAM : 0u);
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
