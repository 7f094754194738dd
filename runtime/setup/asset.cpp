/* runtime/setup/asset.cpp - validates a .dsnt asset in place (format.h, in its documented order) and reads
   texton values and pyramid levels; also the static error messages (format.h's error table). A build
   with neither DSN_FILTERING nor DSN_HISTOGRAM leaves the sections unread (format.h: such a runtime reads
   1.1 files as 1.0, refuses 1.2 files with the histogram flag and reads 1.3 bilinear files in continuous
   mode only), which keeps the small build's code as it was. */
#include "setup/format_bytes.h"
#include "setup/init_internal.h" /* DSN_READS_SECTIONS */

namespace {

void clear_asset(dsn_asset *asset) {
    unsigned char *bytes = static_cast<unsigned char *>(static_cast<void *>(asset));
    for (size_t i = 0; i < sizeof *asset; i++) bytes[i] = 0;
}

int check_magic(const unsigned char *bytes) {
    const unsigned char *magic = reinterpret_cast<const unsigned char *>(DSN_FORMAT_MAGIC);
    uint32_t differs = 0; /* bit 0: the first 4 bytes, bit 1: the last 4 */
    for (uint32_t i = 0; i < DSN_FORMAT_MAGIC_SIZE; i++) differs |= uint32_t(bytes[i] != magic[i]) << (i / 4);
    if (differs & 1u) return DSN_ERR_BAD_MAGIC;
    /* Only the CR, LF and SUB bytes differ: the signature of a text-mode transfer. */
    return differs ? DSN_ERR_TEXT_MODE : DSN_OK;
}

/* Steps 3 to 7: sizes, version and checksum. */
int check_envelope(const unsigned char *bytes, size_t size) {
    if (size < DSN_FORMAT_HEADER_SIZE + DSN_FORMAT_CRC_SIZE) return DSN_ERR_TRUNCATED;
    if (dsn_read_u16le(bytes + DSN_OFFSET_VERSION_MAJOR) != DSN_FORMAT_VERSION_MAJOR) return DSN_ERR_VERSION;
    uint32_t header_size = dsn_read_u32le(bytes + DSN_OFFSET_HEADER_SIZE);
    uint32_t total_size = dsn_read_u32le(bytes + DSN_OFFSET_TOTAL_SIZE);
    if (header_size < DSN_FORMAT_HEADER_SIZE || total_size < DSN_FORMAT_CRC_SIZE ||
        header_size > total_size - DSN_FORMAT_CRC_SIZE)
        return DSN_ERR_HEADER_SIZE;
    if (total_size > size) return DSN_ERR_TRUNCATED;
#ifndef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
    uint32_t stored_crc = dsn_read_u32le(bytes + total_size - DSN_FORMAT_CRC_SIZE);
    if (dsn_crc32(0, bytes, total_size - DSN_FORMAT_CRC_SIZE) != stored_crc) return DSN_ERR_CRC;
#endif
    return DSN_OK;
}

/* Step 8: the only flag is the histogram's, from minor 2 on. */
int check_reserved(const unsigned char *bytes) {
    const uint32_t flags = dsn_read_u32le(bytes + DSN_OFFSET_FLAGS);
    if (flags != 0 && (flags != DSN_FLAG_HISTOGRAM ||
                       dsn_read_u16le(bytes + DSN_OFFSET_VERSION_MINOR) < DSN_FORMAT_HISTOGRAM_MINOR))
        return DSN_ERR_RESERVED;
    for (uint32_t i = 0; i < DSN_RESERVED_SIZE; i++)
        if (bytes[DSN_OFFSET_RESERVED + i] != 0) return DSN_ERR_RESERVED;
    return DSN_HISTOGRAM || flags == 0 ? DSN_OK : DSN_ERR_UNSUPPORTED;
}

/* Steps 9 and 10: the texton's shape and the exact file size. */
int read_geometry(dsn_asset *asset, const unsigned char *bytes) {
    asset->channels = bytes[DSN_OFFSET_CHANNELS];
    asset->bits = bytes[DSN_OFFSET_BITS];
    asset->shape = bytes[DSN_OFFSET_SHAPE];
    asset->interpolation = bytes[DSN_OFFSET_INTERPOLATION];
    asset->width = dsn_read_u16le(bytes + DSN_OFFSET_WIDTH);
    asset->height = dsn_read_u16le(bytes + DSN_OFFSET_HEIGHT);
    uint32_t support_size;
    const int err = dsn_internal_check_geometry(asset, &support_size);
    if (err != DSN_OK) return err;
    /* At most 255 * 255 * 3 * 2 bytes; check_envelope has made header_size <= total_size - 4, so the
       difference below cannot wrap. */
    uint32_t texton_bytes = asset->width * asset->height * asset->channels * (asset->bits / 8);
    uint32_t room = dsn_read_u32le(bytes + DSN_OFFSET_TOTAL_SIZE) - DSN_FORMAT_CRC_SIZE -
                    dsn_read_u32le(bytes + DSN_OFFSET_HEADER_SIZE);
    if (room != texton_bytes) return DSN_ERR_TOTAL_SIZE;
    asset->support_size = support_size;
    return DSN_OK;
}

/* Steps 11 and 12: the normalization fields. */
int read_normalization(dsn_asset *asset, const unsigned char *bytes) {
    for (uint32_t c = 0; c < 3; c++) {
        asset->scale[c] = dsn_read_u32le(bytes + DSN_OFFSET_SCALE + 4 * c);
        asset->mean[c] = dsn_read_i32le(bytes + DSN_OFFSET_MEAN + 4 * c);
    }
    for (uint32_t c = 0; c < 9; c++)
        asset->color_transform[c] = dsn_read_i32le(bytes + DSN_OFFSET_COLOR_TRANSFORM + 4 * c);
    for (uint32_t c = 0; c < asset->channels; c++)
        if (asset->scale[c] == 0) return DSN_ERR_SCALE;
    asset->default_impacts_q16 = dsn_read_u32le(bytes + DSN_OFFSET_DEFAULT_IMPACTS);
    uint32_t impacts = asset->default_impacts_q16;
    if (impacts != 0 && (impacts < DSN_IMPACTS_MIN_Q16 || impacts > DSN_IMPACTS_MAX_Q16))
        return DSN_ERR_IMPACTS;
    for (uint32_t c = asset->channels; c < 3; c++)
        if (asset->scale[c] != 0 || asset->mean[c] != 0) return DSN_ERR_RESERVED;
    if (asset->channels == 1)
        for (uint32_t c = 1; c < 9; c++)
            if (asset->color_transform[c] != 0) return DSN_ERR_COLOR_TRANSFORM;
    return DSN_OK;
}

/* Step 13: no reserved value, nothing outside the disk. */
int check_texton(const dsn_asset *asset) {
    for (uint32_t row = 0; row < asset->height; row++)
        for (uint32_t column = 0; column < asset->width; column++) {
            int inside = dsn_in_support(asset->shape, asset->width, row, column);
            for (uint32_t c = 0; c < asset->channels; c++) {
                int32_t value = dsn_asset_texton_value(asset, row, column, c);
                int32_t reserved = asset->bits == 8 ? -128 : -32768;
                if (value == reserved || (!inside && value != 0)) return DSN_ERR_TEXTON;
            }
        }
    return DSN_OK;
}

#if DSN_READS_SECTIONS
/* A section's payload: null when the file has none of that kind. */
struct section {
    const unsigned char *payload;
    uint32_t size;
};

/* Step 14: the sections fill [128, header_size) exactly, each padded with zeros to 4 bytes, a known kind
   at most once (the histogram's is known from minor 2 on, the lattice texton's from minor 3 on). Finds
   the known kinds' payloads (known[kind - 1]). Every comparison is made on the room left, so nothing can
   wrap. */
int find_sections(const unsigned char *bytes, uint32_t header_size, section *known_kinds) {
    const uint32_t minor = dsn_read_u16le(bytes + DSN_OFFSET_VERSION_MINOR);
    const uint32_t kinds = minor >= DSN_FORMAT_LATTICE_TEXTON_MINOR ? 3u
                           : minor >= DSN_FORMAT_HISTOGRAM_MINOR    ? 2u
                                                                    : 1u;
    for (uint32_t offset = DSN_FORMAT_HEADER_SIZE; offset < header_size;) {
        uint32_t room = header_size - offset;
        if (room < DSN_SECTION_HEADER_SIZE) return DSN_ERR_SECTION;
        room -= DSN_SECTION_HEADER_SIZE;
        const uint32_t kind = dsn_read_u32le(bytes + offset);
        const uint32_t size = dsn_read_u32le(bytes + offset + 4);
        const uint32_t padding = (0u - size) & (DSN_SECTION_ALIGNMENT - 1u);
        if (size > room || padding > room - size) return DSN_ERR_SECTION;
        const unsigned char *payload = bytes + offset + DSN_SECTION_HEADER_SIZE;
        for (uint32_t i = 0; i < padding; i++)
            if (payload[size + i] != 0) return DSN_ERR_SECTION;
        if (kind - 1u < kinds) {
            section *known = &known_kinds[kind - 1u];
            if (known->payload != 0) return DSN_ERR_SECTION;
            known->payload = payload;
            known->size = size;
        }
        offset += DSN_SECTION_HEADER_SIZE + size + padding;
    }
    return DSN_OK;
}

/* Step 15: the pyramid's records, its exact size and its values. Sizes stay below 8 * 255 * 255 * 6. */
int read_pyramid(dsn_asset *asset, const unsigned char *payload, uint32_t size) {
    if (size < DSN_PYRAMID_HEADER_SIZE) return DSN_ERR_PYRAMID;
    const uint32_t levels = payload[0];
    if (levels == 0 || levels > DSN_PYRAMID_MAX_LEVELS || (payload[1] | payload[2] | payload[3]) != 0)
        return DSN_ERR_PYRAMID;
    const uint32_t value_size = asset->bits / 8;
    uint32_t expected = DSN_PYRAMID_HEADER_SIZE + DSN_PYRAMID_RECORD_SIZE * levels;
    if (size < expected) return DSN_ERR_PYRAMID;
    for (uint32_t level = 0; level < levels; level++) {
        const unsigned char *record = payload + DSN_PYRAMID_HEADER_SIZE + DSN_PYRAMID_RECORD_SIZE * level;
        const int32_t exponent = dsn_read_i8(record + 2);
        if (record[0] % 2 == 0 || record[1] % 2 == 0 || exponent < DSN_PYRAMID_EXPONENT_MIN ||
            exponent > DSN_PYRAMID_EXPONENT_MAX || record[3] != 0)
            return DSN_ERR_PYRAMID;
        expected += uint32_t(record[0]) * record[1] * asset->channels * value_size;
    }
    if (size != expected) return DSN_ERR_PYRAMID;
    const unsigned char *values = payload + DSN_PYRAMID_HEADER_SIZE + DSN_PYRAMID_RECORD_SIZE * levels;
    const unsigned char *end = payload + size;
    for (; values < end; values += value_size)
        if (value_size == 1 ? values[0] == 0x80 : (values[0] == 0 && values[1] == 0x80))
            return DSN_ERR_PYRAMID;
    asset->pyramid = payload + DSN_PYRAMID_HEADER_SIZE;
    asset->pyramid_levels = levels;
    return DSN_OK;
}

#if DSN_HISTOGRAM
/* Step 16: the flag and the section agree, and the mapping's fields are in range. Sizes stay below
   68 + 2 * 9 * 1024 * 3. */
int read_histogram(dsn_asset *asset, const unsigned char *bytes, section histogram) {
    const int flagged = dsn_read_u32le(bytes + DSN_OFFSET_FLAGS) == DSN_FLAG_HISTOGRAM;
    if (histogram.payload == 0) return flagged ? DSN_ERR_HISTOGRAM : DSN_OK;
    const unsigned char *payload = histogram.payload;
    if (!flagged || histogram.size < DSN_HISTOGRAM_HEADER_SIZE) return DSN_ERR_HISTOGRAM;
    const uint32_t entries = dsn_read_u16le(payload), levels = payload[2], step_shift = payload[3];
    const uint32_t channels = asset->channels;
    if (entries < 2 || entries > DSN_HISTOGRAM_MAX_ENTRIES || levels == 0 ||
        levels > 1u + asset->pyramid_levels || step_shift > DSN_HISTOGRAM_MAX_STEP_SHIFT ||
        histogram.size != DSN_HISTOGRAM_HEADER_SIZE + 2u * levels * entries * channels)
        return DSN_ERR_HISTOGRAM;
    asset->histogram_input_low_q16 = dsn_read_i32le(payload + 4);
    for (uint32_t i = 0; i < 9; i++) {
        asset->histogram_rotation[i] = dsn_read_i32le(payload + 8 + 4 * i);
        if (channels == 1 && i != 0 && asset->histogram_rotation[i] != 0) return DSN_ERR_HISTOGRAM;
    }
    for (uint32_t c = 0; c < 3; c++) {
        const int32_t centre = dsn_read_i32le(payload + 44 + 4 * c);
        const int32_t expected = dsn_read_i32le(payload + 56 + 4 * c);
        if ((c >= channels && (centre != 0 || expected != 0)) || expected < -DSN_HISTOGRAM_EXPECTED_LIMIT ||
            expected > DSN_HISTOGRAM_EXPECTED_LIMIT)
            return DSN_ERR_HISTOGRAM;
        asset->histogram_centre[c] = centre;
        asset->histogram_expected_q16[c] = expected;
    }
    const unsigned char *table = payload + DSN_HISTOGRAM_HEADER_SIZE;
    for (const unsigned char *value = table; value < payload + histogram.size; value += 2)
        if (value[0] == 0 && value[1] == 0x80) return DSN_ERR_HISTOGRAM;
    asset->histogram_table = table;
    asset->histogram_entries = entries;
    asset->histogram_levels = levels;
    asset->histogram_step_shift = step_shift;
    return DSN_OK;
}
#endif

/* The sum of a texton's values of channel c; INT32_MIN (which no sum reaches: |sum| <= 255 * 255 * 32767
   < 2^31 - 1) when one of them is the reserved -128 / -32768. */
int32_t channel_sum(const dsn_asset *asset, uint32_t c) {
    int32_t sum = 0;
    const int32_t reserved = asset->bits == 8 ? -128 : -32768;
    for (uint32_t i = 0; i < asset->width * asset->height; i++) {
        const int32_t value = dsn_asset_texton_value(asset, i / asset->width, i % asset->width, c);
        if (value == reserved) return INT32_MIN;
        sum += value;
    }
    return sum;
}

/* Step 17: the lattice texton's size, values and per-channel sums (equal to the texton's, so that both
   reads share one normalization). */
int read_lattice_texton(dsn_asset *asset, const unsigned char *payload, uint32_t size) {
    dsn_asset lattice = *asset;
    lattice.texton = payload + DSN_LATTICE_TEXTON_HEADER_SIZE;
    lattice.width = payload[0];
    lattice.height = payload[1];
    if (asset->interpolation != DSN_INTERPOLATION_BILINEAR || size < DSN_LATTICE_TEXTON_HEADER_SIZE ||
        (payload[2] | payload[3]) != 0 || lattice.width % 2 == 0 || lattice.height % 2 == 0 ||
        size != DSN_LATTICE_TEXTON_HEADER_SIZE +
                    lattice.width * lattice.height * asset->channels * (asset->bits / 8))
        return DSN_ERR_LATTICE_TEXTON;
    for (uint32_t c = 0; c < asset->channels; c++)
        if (channel_sum(&lattice, c) != channel_sum(asset, c)) return DSN_ERR_LATTICE_TEXTON;
    asset->lattice_texton = lattice.texton;
    asset->lattice_width = lattice.width;
    asset->lattice_height = lattice.height;
    return DSN_OK;
}

/* Steps 14 to 17, for files of minor version 1 and later (16 from minor 2 on, 17 from minor 3 on). */
int read_sections(dsn_asset *asset, const unsigned char *bytes) {
    if (dsn_read_u16le(bytes + DSN_OFFSET_VERSION_MINOR) < DSN_FORMAT_SECTIONS_MINOR) return DSN_OK;
    section known[3] = {{0, 0}, {0, 0}, {0, 0}}; /* pyramid, histogram, lattice texton */
    int err = find_sections(bytes, dsn_read_u32le(bytes + DSN_OFFSET_HEADER_SIZE), known);
    if (err == DSN_OK && known[0].payload != 0) err = read_pyramid(asset, known[0].payload, known[0].size);
#if DSN_HISTOGRAM
    if (err == DSN_OK) err = read_histogram(asset, bytes, known[1]);
#endif
    if (err == DSN_OK && known[2].payload != 0)
        err = read_lattice_texton(asset, known[2].payload, known[2].size);
    return err;
}
#endif

int load(dsn_asset *asset, const unsigned char *bytes, size_t size) {
    if (size < DSN_FORMAT_MAGIC_SIZE) return DSN_ERR_TRUNCATED;
    int err = check_magic(bytes);
    if (err == DSN_OK) err = check_envelope(bytes, size);
    if (err == DSN_OK) err = check_reserved(bytes);
    if (err == DSN_OK) err = read_geometry(asset, bytes);
    if (err == DSN_OK) err = read_normalization(asset, bytes);
    if (err != DSN_OK) return err;
    asset->texton = bytes + dsn_read_u32le(bytes + DSN_OFFSET_HEADER_SIZE);
    err = check_texton(asset);
#if DSN_READS_SECTIONS
    if (err == DSN_OK) err = read_sections(asset, bytes);
#endif
    if (err != DSN_OK) return err;
    asset->version_minor = dsn_read_u16le(bytes + DSN_OFFSET_VERSION_MINOR);
    asset->bake_iterations = dsn_read_u32le(bytes + DSN_OFFSET_BAKE_ITERATIONS);
    asset->bake_seed = dsn_read_u32le(bytes + DSN_OFFSET_BAKE_SEED);
    asset->bake_rme_q24 = dsn_read_u32le(bytes + DSN_OFFSET_BAKE_RME);
    asset->exemplar_width = dsn_read_u16le(bytes + DSN_OFFSET_EXEMPLAR_WIDTH);
    asset->exemplar_height = dsn_read_u16le(bytes + DSN_OFFSET_EXEMPLAR_HEIGHT);
    return DSN_OK;
}

} // namespace

#if DSN_READS_SECTIONS
/* An asset's pyramid and lattice texton as the loader leaves them: each pointer null with its sizes 0, or
   pointing where the loader points it, into a section of its kind (payload after the u32 kind and u32
   size) that steps 15 and 17 accept with those very sizes. Reads the caller's buffer around the pointers:
   a pointer moved elsewhere cannot be told from a valid one, but its sizes are those of what it points at,
   so no read goes past the section that the bytes there describe. */
int dsn_internal_check_sections(const dsn_asset *asset) {
    dsn_asset read = *asset;
    read.pyramid = read.lattice_texton = 0;
    read.pyramid_levels = read.lattice_width = read.lattice_height = 0;
    if (asset->pyramid != 0) {
        const unsigned char *payload = asset->pyramid - DSN_PYRAMID_HEADER_SIZE;
        if (dsn_read_u32le(payload - DSN_SECTION_HEADER_SIZE) != DSN_SECTION_PYRAMID ||
            read_pyramid(&read, payload, dsn_read_u32le(payload - 4)) != DSN_OK)
            return DSN_ERR_ARGUMENT;
    }
    if (asset->lattice_texton != 0) {
        const unsigned char *payload = asset->lattice_texton - DSN_LATTICE_TEXTON_HEADER_SIZE;
        if (dsn_read_u32le(payload - DSN_SECTION_HEADER_SIZE) != DSN_SECTION_LATTICE_TEXTON ||
            read_lattice_texton(&read, payload, dsn_read_u32le(payload - 4)) != DSN_OK)
            return DSN_ERR_ARGUMENT;
    }
    return read.pyramid == asset->pyramid && read.pyramid_levels == asset->pyramid_levels &&
                   read.lattice_texton == asset->lattice_texton &&
                   read.lattice_width == asset->lattice_width && read.lattice_height == asset->lattice_height
               ? DSN_OK
               : DSN_ERR_ARGUMENT;
}
#endif

int dsn_internal_check_geometry(const dsn_asset *asset, uint32_t *support_size) {
    if (asset->channels != 1 && asset->channels != 3) return DSN_ERR_CHANNELS;
    if (asset->bits != 8 && asset->bits != 16) return DSN_ERR_BITS;
    if (asset->shape > DSN_SHAPE_DISK || (asset->shape == DSN_SHAPE_DISK && asset->width != asset->height))
        return DSN_ERR_SHAPE;
    if (asset->interpolation > DSN_INTERPOLATION_BILINEAR) return DSN_ERR_INTERPOLATION;
    if (asset->width % 2 == 0 || asset->width > DSN_FORMAT_MAX_SIDE || asset->height % 2 == 0 ||
        asset->height > DSN_FORMAT_MAX_SIDE)
        return DSN_ERR_DIMENSIONS;
    *support_size = dsn_support_size(asset->shape, asset->width, asset->height);
    return DSN_OK;
}

extern "C" int dsn_asset_load(dsn_asset *asset, const void *bytes, size_t size) {
    if (asset == 0) return DSN_ERR_NULL;
    clear_asset(asset);
    if (bytes == 0) return DSN_ERR_NULL;
    int err = load(asset, static_cast<const unsigned char *>(bytes), size);
    if (err != DSN_OK) clear_asset(asset);
    return err;
}

extern "C" int32_t dsn_asset_texton_value(const dsn_asset *asset, uint32_t row, uint32_t column,
                                          uint32_t channel) {
    if (asset == 0 || asset->texton == 0 || row >= asset->height || column >= asset->width ||
        channel >= asset->channels)
        return 0;
    uint32_t index = (row * asset->width + column) * asset->channels + channel;
    return asset->bits == 8 ? dsn_read_i8(asset->texton + index) : dsn_read_i16le(asset->texton + 2 * index);
}

#if DSN_FILTERING
extern "C" int dsn_asset_level(const dsn_asset *asset, uint32_t level, dsn_level *out) {
    if (out == 0) return DSN_ERR_NULL;
    out->values = 0;
    out->width = out->height = 0;
    out->exponent = 0;
    if (asset == 0 || asset->texton == 0) return DSN_ERR_NULL;
    if (level > asset->pyramid_levels || (level != 0 && asset->pyramid == 0)) return DSN_ERR_ARGUMENT;
    if (level == 0) {
        out->values = asset->texton;
        out->width = asset->width;
        out->height = asset->height;
        return DSN_OK;
    }
    /* The values follow the records, level after level. */
    const uint32_t value_size = asset->channels * (asset->bits / 8);
    const unsigned char *values = asset->pyramid + DSN_PYRAMID_RECORD_SIZE * asset->pyramid_levels;
    for (uint32_t previous = 0; previous + 1 < level; previous++) {
        const unsigned char *record = asset->pyramid + DSN_PYRAMID_RECORD_SIZE * previous;
        values += uint32_t(record[0]) * record[1] * value_size;
    }
    const unsigned char *record = asset->pyramid + DSN_PYRAMID_RECORD_SIZE * (level - 1);
    out->values = values;
    out->width = record[0];
    out->height = record[1];
    out->exponent = dsn_read_i8(record + 2);
    return DSN_OK;
}
#endif

extern "C" const char *dsn_error_message(int code) {
    switch (code) {
#define DSN_ERROR_MESSAGE_CASE(name, value, message)                                                         \
    case name:                                                                                               \
        return message;
        DSN_LIST_ERRORS(DSN_ERROR_MESSAGE_CASE)
#undef DSN_ERROR_MESSAGE_CASE
    default:
        return "unknown error code";
    }
}
