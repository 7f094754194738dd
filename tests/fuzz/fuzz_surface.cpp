// fuzz_surface.cpp - the surface noise's inputs (dsn.h, "Surface noise"): bytes -> a small asset (grey or
// RGB, 8 or 16 bits, any odd size up to 31, any values), a density and a seed -> init; then float vectors of
// any bits (NaN, infinities, subnormals, zero, parallel tangents) through dsn_surface_frame_from_float, and
// frames of any int32 components, at positions of any int64; with the asset's pyramid (one input in two),
// the filtered point too, under footprints of any int64 steps and any taps. Invariants: a frame either fails
// with its output zeroed or is unit and orthogonal to 2^-26; an evaluation either succeeds or fails with its
// output zeroed (DSN_ERR_ARGUMENT exactly for a frame out of range, or a footprint's max_taps 0 or above
// DSN_FILTER_MAX_TAPS); the same call gives the same bits; the batch gives the points' bits.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "dsn/asset_writer.h"
#include "dsn/dsn.h"
#include "fuzz_input.h"
#include "offline/bake_internal.h"

namespace {

dsn::AssetFields asset_from(FuzzInput &input) {
    dsn::AssetFields fields;
    fields.channels = (input.byte() & 1u) ? 3u : 1u;
    fields.bits = (input.byte() & 1u) ? 16u : 8u;
    fields.interpolation = DSN_INTERPOLATION_BILINEAR;
    fields.width = 2u * (input.byte() % 16u) + 1u;
    fields.height = 2u * (input.byte() % 16u) + 1u;
    const int32_t peak = fields.bits == 8 ? 127 : 32767;
    for (uint32_t i = 0; i < fields.width * fields.height * fields.channels; i++) {
        const int32_t value = int32_t(int16_t(input.u32()));
        fields.texton.push_back(fields.bits == 8 ? value % (peak + 1) : (value == -32768 ? 0 : value));
    }
    for (uint32_t c = 0; c < fields.channels; c++) {
        fields.scale[c] = 1u << (20 + input.byte() % 12u);
        fields.mean[c] = int32_t(input.u32() >> 4);
    }
    dsn::set_identity_color_transform(fields);
    return fields;
}

float float_from(FuzzInput &input) {
    const uint32_t bits = input.u32();
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

double length_squared(const int32_t *v) {
    double sum = 0;
    for (int i = 0; i < 3; i++) sum += double(v[i]) * double(v[i]);
    return sum / 1152921504606846976.0; // 2^60
}

double dot(const int32_t *a, const int32_t *b) {
    double sum = 0;
    for (int i = 0; i < 3; i++) sum += double(a[i]) * double(b[i]);
    return sum / 1152921504606846976.0;
}

bool zeroed(const int32_t *values, uint32_t count) {
    for (uint32_t i = 0; i < count; i++)
        if (values[i] != 0) return false;
    return true;
}

void check_frame(FuzzInput &input, dsn_surface_frame *frame) {
    float normal[3], tangent[3];
    for (float &v : normal) v = float_from(input);
    for (float &v : tangent) v = float_from(input);
    const bool with_tangent = input.byte() & 1u;
    std::memset(frame, 0x5A, sizeof *frame);
    const int err = dsn_surface_frame_from_float(normal, with_tangent ? tangent : nullptr, frame);
    const int32_t *vectors[3] = {frame->tangent, frame->bitangent, frame->normal};
    if (err != DSN_OK) {
        fuzz_require(err == DSN_ERR_ARGUMENT);
        for (const int32_t *v : vectors) fuzz_require(zeroed(v, 3));
        return;
    }
    const double tolerance = 1.0 / (1 << 26);
    for (const int32_t *v : vectors) fuzz_require(std::fabs(length_squared(v) - 1) < tolerance);
    fuzz_require(std::fabs(dot(frame->tangent, frame->normal)) < tolerance);
    fuzz_require(std::fabs(dot(frame->bitangent, frame->normal)) < tolerance);
    fuzz_require(std::fabs(dot(frame->tangent, frame->bitangent)) < tolerance);
}

// The filtered point under a footprint of any steps (shifted down by any amount, so that small ones come
// too) and any taps: an error with its output zeroed, or the same bits twice.
void check_filtered(FuzzInput &input, const dsn_noise &noise, const int64_t *position,
                    const dsn_surface_frame &frame, uint32_t channels) {
    dsn_footprint footprint;
    int64_t *steps[4] = {&footprint.column_step_x, &footprint.column_step_y, &footprint.row_step_x,
                         &footprint.row_step_y};
    for (int64_t *step : steps)
        *step = int64_t(uint64_t(input.u32()) | uint64_t(input.u32()) << 32) >> (input.byte() % 64u);
    footprint.max_taps = input.byte() % (DSN_FILTER_MAX_TAPS + 2u);
    int32_t out[DSN_MAX_CHANNELS] = {7, 7, 7}, again[DSN_MAX_CHANNELS] = {9, 9, 9};
    const int err = dsn_surface_filtered_point_fixed(&noise, position, &frame, &footprint, out);
    if (footprint.max_taps == 0 || footprint.max_taps > DSN_FILTER_MAX_TAPS)
        fuzz_require(err == DSN_ERR_ARGUMENT);
    fuzz_require(err == DSN_OK || err == DSN_ERR_ARGUMENT || err == DSN_ERR_COST);
    if (err != DSN_OK) {
        fuzz_require(zeroed(out, channels));
        return;
    }
    fuzz_require(dsn_surface_filtered_point_fixed(&noise, position, &frame, &footprint, again) == DSN_OK);
    fuzz_require(std::memcmp(out, again, channels * sizeof out[0]) == 0);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FuzzInput input(data, size);
    dsn::AssetFields fields = asset_from(input);
    const bool filtered = input.byte() & 1u;
    if (filtered) fields.pyramid = dsn::texton_pyramid(fields);
    const std::vector<unsigned char> bytes = dsn::encode_asset(fields);
    dsn_asset asset;
    if (dsn_asset_load(&asset, bytes.data(), bytes.size()) != DSN_OK) return 0;
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = input.u32();
    config.impacts_q16 = DSN_IMPACTS_MIN_Q16 + input.u32() % (64u << 16);
    dsn_noise noise;
    if (dsn_noise_init(&noise, &asset, &config) != DSN_OK) return 0;
    const uint32_t channels = dsn_noise_channels(&noise);

    std::vector<int64_t> positions;
    std::vector<dsn_surface_frame> frames;
    std::vector<int32_t> values;
    for (int k = 0; k < 4 && input.position < input.size; k++) {
        dsn_surface_frame frame;
        if (input.byte() & 1u) {
            check_frame(input, &frame);
        } else {
            int32_t *components = &frame.tangent[0];
            for (int i = 0; i < 9; i++) components[i] = input.i32() >> (input.byte() % 32u);
        }
        int64_t position[3];
        for (int64_t &p : position) p = int64_t(uint64_t(input.u32()) | uint64_t(input.u32()) << 32);
        int32_t out[DSN_MAX_CHANNELS] = {7, 7, 7}, again[DSN_MAX_CHANNELS] = {9, 9, 9};
        const int err = dsn_surface_point_fixed(&noise, position, &frame, out);
        bool in_range = true;
        for (int i = 0; i < 9; i++)
            in_range = in_range && (&frame.tangent[0])[i] >= -DSN_FRAME_ONE &&
                       (&frame.tangent[0])[i] <= DSN_FRAME_ONE;
        fuzz_require((err == DSN_ERR_ARGUMENT) == !in_range);
        fuzz_require(err == DSN_OK || err == DSN_ERR_ARGUMENT || err == DSN_ERR_COST);
        if (err != DSN_OK) {
            fuzz_require(zeroed(out, channels));
            continue;
        }
        fuzz_require(dsn_surface_point_fixed(&noise, position, &frame, again) == DSN_OK);
        fuzz_require(std::memcmp(out, again, channels * sizeof out[0]) == 0);
        if (filtered) check_filtered(input, noise, position, frame, channels);
        positions.insert(positions.end(), position, position + 3);
        frames.push_back(frame);
        values.insert(values.end(), out, out + channels);
    }
    std::vector<int32_t> batch(values.size());
    fuzz_require(dsn_surface_batch_fixed(&noise, positions.data(), frames.data(), uint32_t(frames.size()),
                                         batch.data()) == DSN_OK);
    fuzz_require(batch == values);
    return 0;
}
