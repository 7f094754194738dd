/* dsn/dsn.glsl - the discrete spot noise evaluated in a shader, with exactly the bits of the C runtime.

   What it does
     dsn_lattice_point_fixed and dsn_continuous_point_fixed return what the C functions of the same names
     (dsn/dsn.h) write, bit for bit: the same impulses from the same hashes, the same exact Poisson counts,
     the same fixed-point normalization. Everything is unsigned 32-bit arithmetic (64-bit values are
     uvec2(low, high)): no float on the evaluation path, so every GPU and driver gives the same bits.
     The float and 8-bit conversions of the API edge are integer too.
     Gradients (for bump and normal mapping): dsn_lattice_gradient_fixed and
     dsn_continuous_gradient_fixed give the value and its derivatives per texel along x and y, the bits
     of the C functions of the same names (dsn.h, "Gradients"): the lattice noise's forward differences,
     the continuous noise's exact derivative (one-sided, toward +x and +y, on a texel edge). A continuous
     gradient walks the value's impulses and reads its texels, with four more wide products per impulse
     and channel (on llvmpipe about 1.1-1.3 times the value); a lattice one walks the window of the point
     and its two neighbours and reads three texels per impulse (on llvmpipe 3-5 times the value).
     Mixing (dsn.h, "Mixing"): dsn_mix_lattice_point_fixed and dsn_mix_continuous_point_fixed give the
     bits of the C functions of the same names, from the words of dsn_gpu_mix_pack (a mix and its
     control); dsn_word must then read word dsn_word_base + index of the buffer (below). One walk over
     material 0's impulses within the largest reach, each impulse reading its weights (four samples
     per material) and one texton: no shortcut where the weights are one material's alone.
     Workgroup tiles (compute shaders that #define DSN_GLSL_TILES 1 before this file): a workgroup lists
     the impulses that reach its window of points once, in 8 KB of shared memory, and each invocation
     sums its point from that list (dsn_lattice_tile_point_fixed, dsn_continuous_tile_point_fixed): the
     bits of the point functions, without their per-point hashing (see "Workgroup tiles" below).
     Surface noise (dsn.h, "Surface noise"): dsn_surface_point (float position, normal and tangent, as a
     fragment shader has them) and dsn_surface_point_fixed (a Q32.32 position and a Q2.30 frame) give the
     bits of dsn_surface_point_float and dsn_surface_point_fixed; dsn_surface_frame_from_float_bits those
     of dsn_surface_frame_from_float. A point walks the ~27 cubes around it, a few hundred impulses.

   Versions
     GLSL 4.30 core and GLSL ES 3.10 (compute and fragment shaders) multiply 32 x 32 -> 64 bits with
     umulExtended / imulExtended. GLSL ES 3.00 (WebGL2) has neither: there the wide products are built
     from 16-bit limbs (the same bits). The choice is automatic; #define DSN_GLSL_LIMBS 1 before this file
     forces the limbs anywhere, 0 forbids them.

   How to use it
     Pack a configured noise on the CPU with dsn_gpu_pack (dsn/gpu.h: the layout of the words), put the
     words in a shader storage buffer, a uniform buffer or an R32UI texture, and define how to read word
     `index` of it, before or after this file (GLSL has no #include: paste the sources in one string):
         #version 430
         layout(std430, binding = 0) readonly buffer Noise { uint noise_words[]; };
         uint dsn_word(uint index) { return noise_words[index]; }
         ... this file ...
         ivec3 value = dsn_lattice_point_fixed(ivec2(x, y));   // Q16.16, 65536 is 1.0
         ivec3 v, dx, dy;                                       // or the value with its gradient
         dsn_continuous_gradient_fixed(x_q32, y_q32, v, dx, dy); // Q16.16 per texel
     Grey noises fill .x only (the other channels are 0). Coordinates wrap as in the C API: lattice points
     are int32, continuous points are Q32.32 texel coordinates as uvec2(low, high) per axis (see
     dsn_coordinate_from_float and dsn_coordinate_from_double_bits for conversions). A point costs
     tens of hashes and a few hundred word reads (the README gives counts): meant for shaders that
     need the exact bits (previews matching an offline reference, data), not as the cheapest noise.
     GLSL ES: this file declares `precision highp int;`; code before it (dsn_word, say) needs its own
     highp declarations (integer samplers too). The layout of dsn/gpu.h, version 4.
     A mix: pack it with dsn_gpu_mix_pack (dsn/gpu.h) and define dsn_word after this file, so that it
     sees dsn_word_base:
         uint dsn_word(uint index) { return noise_words[dsn_word_base + index]; }
         ivec3 value = dsn_mix_continuous_point_fixed(x_q32, y_q32);  // or dsn_mix_lattice_point_fixed
         vec3 rgb = dsn_mix_color(value);                              // the mix's channels */

#ifndef DSN_GLSL_LIMBS
#if defined(GL_ES) && __VERSION__ < 310
#define DSN_GLSL_LIMBS 1
#else
#define DSN_GLSL_LIMBS 0
#endif
#endif

#ifdef GL_ES
precision highp int;
precision highp float;
#endif

/* Word `index` of the packed noise: defined by the shader that includes this file. */
uint dsn_word(uint index);

/* Where index 0 of dsn_word lies in the buffer: always 0 for one noise. The mixing functions (below) move
   it to each material's words in turn, so a shader that mixes defines dsn_word, after this file, as
   reading word dsn_word_base + index of its buffer. */
uint dsn_word_base = 0u;

/* ---- The layout (dsn/gpu.h) ---- */
const uint DSN_WORD_CHANNELS = 3u;
const uint DSN_WORD_WIDTH = 5u;
const uint DSN_WORD_HEIGHT = 6u;
const uint DSN_WORD_RADIUS = 7u; /* x, then y */
const uint DSN_WORD_CELL_SHIFT = 9u;
const uint DSN_WORD_PERIOD = 10u; /* x, then y */
const uint DSN_WORD_SEED_COLUMN = 12u;
const uint DSN_WORD_SEED_ROW = 13u;
const uint DSN_WORD_GAIN_SHIFT = 14u;
const uint DSN_WORD_POISSON_PARTS = 15u;
const uint DSN_WORD_POISSON_SIZE = 16u;
const uint DSN_WORD_CONTINUOUS = 17u;
const uint DSN_WORD_GAIN = 18u;
const uint DSN_WORD_OFFSET = 36u;
const uint DSN_WORD_LATTICE_WIDTH = 42u; /* the lattice evaluators' texton: width, height, radii, start */
const uint DSN_WORD_LATTICE_HEIGHT = 43u;
const uint DSN_WORD_LATTICE_RADIUS = 44u; /* x, then y */
const uint DSN_WORD_LATTICE_TEXTON = 46u;
const uint DSN_WORD_QUADS = 47u; /* where the texton's 2 x 2 quads start */
const uint DSN_WORD_POISSON_CDF = 48u;
const uint DSN_WORD_POISSON_GUIDE = 144u;
const uint DSN_WORD_TEXTON = 216u;

/* ---- 64-bit arithmetic on uvec2(low, high), modulo 2^64 ---- */

uvec2 dsn_add64(uvec2 a, uvec2 b) {
    uint low = a.x + b.x;
    return uvec2(low, a.y + b.y + (low < a.x ? 1u : 0u));
}

uvec2 dsn_sub64(uvec2 a, uvec2 b) { return uvec2(a.x - b.x, a.y - b.y - (a.x < b.x ? 1u : 0u)); }

/* |value| of a signed value; a <= b of unsigned ones. */
uvec2 dsn_magnitude64(uvec2 value) { return int(value.y) < 0 ? dsn_sub64(uvec2(0u), value) : value; }
bool dsn_at_most64(uvec2 a, uvec2 b) { return a.y < b.y || (a.y == b.y && a.x <= b.x); }

/* a * b as 64 bits. Without umulExtended: four 16 x 16 -> 32-bit products, as the C runtime's
   configuration code builds its 128-bit products from 32-bit halves. */
uvec2 dsn_multiply_wide(uint a, uint b) {
#if DSN_GLSL_LIMBS
    uint a0 = a & 0xFFFFu, a1 = a >> 16u, b0 = b & 0xFFFFu, b1 = b >> 16u;
    uint low_low = a0 * b0, low_high = a0 * b1, high_low = a1 * b0;
    uint middle = (low_low >> 16u) + (low_high & 0xFFFFu) + (high_low & 0xFFFFu);
    return uvec2((middle << 16u) | (low_low & 0xFFFFu),
                 a1 * b1 + (low_high >> 16u) + (high_low >> 16u) + (middle >> 16u));
#else
    uint high, low;
    umulExtended(a, b, high, low);
    return uvec2(low, high);
#endif
}

/* Signed a * b as a 64-bit two's-complement value: the unsigned product less 2^32 b when a < 0 and
   2^32 a when b < 0 (modulo 2^64). */
uvec2 dsn_multiply_signed_wide(int a, int b) {
#if DSN_GLSL_LIMBS
    uvec2 product = dsn_multiply_wide(uint(a), uint(b));
    if (a < 0) product.y -= uint(b);
    if (b < 0) product.y -= uint(a);
    return product;
#else
    int high, low;
    imulExtended(a, b, high, low);
    return uvec2(uint(low), uint(high));
#endif
}

/* Signed a times unsigned b. */
uvec2 dsn_multiply_mixed_wide(int a, uint b) {
    uvec2 product = dsn_multiply_wide(uint(a), b);
    if (a < 0) product.y -= b;
    return product;
}

uvec2 dsn_multiply64(uvec2 a, uvec2 b) {
    uvec2 product = dsn_multiply_wide(a.x, b.x);
    product.y += a.x * b.y + a.y * b.x;
    return product;
}

/* Shifts by 0 .. 63 (GLSL leaves 32-bit shifts by 32 or more undefined: each case is split). */
uvec2 dsn_shift_left64(uvec2 x, uint n) {
    if (n == 0u) return x;
    if (n >= 32u) return uvec2(0u, x.x << (n - 32u));
    return uvec2(x.x << n, (x.y << n) | (x.x >> (32u - n)));
}

uvec2 dsn_shift_right64(uvec2 x, uint n) {
    if (n == 0u) return x;
    if (n >= 32u) return uvec2(x.y >> (n - 32u), 0u);
    return uvec2((x.x >> n) | (x.y << (32u - n)), x.y >> n);
}

/* x ^ (x >> n), 0 < n < 32 */
uvec2 dsn_xor_shift64(uvec2 x, uint n) {
    return uvec2(x.x ^ ((x.x >> n) | (x.y << (32u - n))), x.y ^ (x.y >> n));
}

/* ---- Hashing (the runtime's lowbias32, SplitMix64 finalizer and cell keys) ---- */

uint dsn_mix32(uint x) {
    x ^= x >> 16u;
    x *= 0x7FEB352Du;
    x ^= x >> 15u;
    x *= 0x846CA68Bu;
    x ^= x >> 16u;
    return x;
}

uvec2 dsn_mix64(uvec2 x) {
    x = dsn_xor_shift64(x, 30u);
    x = dsn_multiply64(x, uvec2(0x1CE4E5B9u, 0xBF58476Du));
    x = dsn_xor_shift64(x, 27u);
    x = dsn_multiply64(x, uvec2(0x133111EBu, 0x94D049BBu));
    return dsn_xor_shift64(x, 31u);
}

uint dsn_row_key(uint cell_y) { return dsn_mix32(cell_y + dsn_word(DSN_WORD_SEED_ROW)); }

uint dsn_cell_key_in_row(uint cell_x, uint row_key) {
    return dsn_mix32((cell_x ^ dsn_word(DSN_WORD_SEED_COLUMN)) + row_key);
}

uint dsn_cell_stream(uint key, uint index) { return dsn_mix32(key + index * 0x9E3779B9u); }

/* Pair `index` of a cell's packed positions: mix64(key 2^32 + index 0x9E3779B97F4A7C15). */
uvec2 dsn_position_pair(uint key, uint index) {
    uvec2 x = dsn_multiply_wide(index, 0x7F4A7C15u);
    x.y += index * 0x9E3779B9u + key;
    return dsn_mix64(x);
}

/* ---- Exact Poisson counts ---- */

uint dsn_poisson_draw(uint uniform_value) {
    uint size = dsn_word(DSN_WORD_POISSON_SIZE);
    uint n = dsn_word(DSN_WORD_POISSON_GUIDE + (uniform_value >> 26u));
    while (n < size && uniform_value >= dsn_word(DSN_WORD_POISSON_CDF + n)) n++;
    return n;
}

uint dsn_cell_impulse_count(uint key) {
    uint count = dsn_poisson_draw(key), parts = dsn_word(DSN_WORD_POISSON_PARTS);
    for (uint part = 1u; part < parts; part++) count += dsn_poisson_draw(dsn_cell_stream(key, part));
    return count;
}

/* ---- Packed positions ---- */

/* log2 of the bits of one impulse's field: 3 (a byte) for cells of side <= 16, else 4 (16 bits). */
uint dsn_field_shift(uint cell_shift) { return cell_shift <= 4u ? 3u : 4u; }

/* The field of impulse k from the pair that holds it: x in the low half, y in the high half. */
uint dsn_field_in_pair(uvec2 pair, uint k, uint field_shift) {
    uint bit = (k & ((1u << (6u - field_shift)) - 1u)) << field_shift;
    return ((bit >= 32u ? pair.y : pair.x) >> (bit & 31u)) & (0xFFFFFFFFu >> (32u - (1u << field_shift)));
}

/* 16-bit in-cell positions of an impulse for the continuous mode, x low and y high: the top half_bits
   bits of each from the packed field, the rest from the impulse's fraction hash. */
uint dsn_impulse_position(uint field, uint fraction, uint half_bits) {
    uint x = ((field & ((1u << half_bits) - 1u)) << (16u - half_bits)) | ((fraction & 0xFFFFu) >> half_bits);
    uint y = ((field >> half_bits) << (16u - half_bits)) | ((fraction >> 16u) >> half_bits);
    return x | (y << 16u);
}

/* The same for impulse k of the cell with this key. */
uint dsn_impulse_hash(uint key, uint k, uint cell_shift) {
    uint field_shift = dsn_field_shift(cell_shift);
    uint field = dsn_field_in_pair(dsn_position_pair(key, k >> (6u - field_shift)), k, field_shift);
    return dsn_impulse_position(field, dsn_cell_stream(key, 0x80000000u + k), 1u << (field_shift - 1u));
}

/* ---- The cells that can reach a window, along one axis (periodic or not) ---- */

struct dsn_axis {
    uint radius, shift, period, window_length, start, copies_before, span_count;
};

struct dsn_span {
    uint first_cell, cell_count, base, last_position;
};

dsn_axis dsn_axis_init(uint coordinate, uint window_length, uint radius, uint shift, uint period) {
    dsn_axis axis = dsn_axis(radius, shift, period, window_length, coordinate, 0u, 1u);
    if (period != 0u) {
        uint start =
            (coordinate & 0x80000000u) != 0u ? period - 1u - (~coordinate) % period : coordinate % period;
        uint extent = window_length - 1u + radius, rest = extent % period;
        axis.start = start;
        axis.copies_before = start >= radius ? 0u : 1u + (radius - 1u - start) / period;
        axis.span_count = axis.copies_before + extent / period + (rest >= period - start ? 1u : 0u) + 1u;
    }
    return axis;
}

dsn_span dsn_axis_span(dsn_axis axis, uint index) {
    dsn_span span;
    uint mask = (1u << axis.shift) - 1u, low = axis.start - axis.radius;
    if (axis.period == 0u) {
        span.first_cell = low >> axis.shift;
        span.cell_count = (((low & mask) + axis.window_length - 1u + 2u * axis.radius) >> axis.shift) + 1u;
        span.base = axis.start + axis.radius;
        span.last_position = 0xFFFFFFFFu;
    } else {
        uint copy_start = (index - axis.copies_before) * axis.period;
        uint first = index == 0u ? low - copy_start : 0u;
        uint last = index == axis.span_count - 1u
                        ? axis.start + axis.window_length - 1u + axis.radius - copy_start
                        : axis.period - 1u;
        span.first_cell = first >> axis.shift;
        span.cell_count = (last >> axis.shift) - span.first_cell + 1u;
        span.base = axis.start + axis.radius - copy_start;
        span.last_position = axis.period - 1u;
    }
    return span;
}

uint dsn_span_cell(dsn_span span, uint i, uint shift) {
    return (span.first_cell + i) & (0xFFFFFFFFu >> shift);
}

/* ---- Normalization: Q_k sums -> Q16.16 ---- */

/* round(accumulated / 2^shift) saturated to int32, shift 1 .. 32 (init keeps it in 8 .. 32). */
int dsn_round_saturate(uvec2 accumulated, uint shift) {
    uvec2 t = dsn_add64(accumulated, uvec2(1u << (shift - 1u), 0u));
    uint low;
    int high;
    if (shift >= 32u) {
        low = t.y;
        high = int(t.y) < 0 ? -1 : 0;
    } else {
        low = (t.x >> shift) | (t.y << (32u - shift));
        high = int(t.y) >> shift; /* arithmetic: GLSL extends the sign */
    }
    if (high == (int(low) < 0 ? -1 : 0)) return int(low);
    return high < 0 ? int(0x80000000u) : 0x7FFFFFFF;
}

/* |gain| < 2^29: its low word, read as int, is the whole value. */
int dsn_gain(uint c, uint k) { return int(dsn_word(DSN_WORD_GAIN + 2u * (3u * c + k))); }

uvec2 dsn_offset(uint c) {
    return uvec2(dsn_word(DSN_WORD_OFFSET + 2u * c), dsn_word(DSN_WORD_OFFSET + 2u * c + 1u));
}

/* From `accumulated`: the noise's offset (the mean) for a value, zero for a difference of sums. */
int dsn_normalize_channel_from(uint c, uint channels, uvec3 sums, uvec2 accumulated) {
    accumulated = dsn_add64(accumulated, dsn_multiply_signed_wide(dsn_gain(c, 0u), int(sums.x)));
    if (channels == 3u) {
        accumulated = dsn_add64(accumulated, dsn_multiply_signed_wide(dsn_gain(c, 1u), int(sums.y)));
        accumulated = dsn_add64(accumulated, dsn_multiply_signed_wide(dsn_gain(c, 2u), int(sums.z)));
    }
    return dsn_round_saturate(accumulated, dsn_word(DSN_WORD_GAIN_SHIFT));
}

/* with_mean: a value (the noise's offset added); else a gradient's difference of sums (no mean). */
ivec3 dsn_normalize_from(uvec3 sums, bool with_mean) {
    uint channels = dsn_word(DSN_WORD_CHANNELS);
    ivec3 result = ivec3(0);
    for (uint c = 0u; c < channels; c++) {
        int value = dsn_normalize_channel_from(c, channels, sums, with_mean ? dsn_offset(c) : uvec2(0u));
        if (c == 0u)
            result.x = value;
        else if (c == 1u)
            result.y = value;
        else
            result.z = value;
    }
    return result;
}

ivec3 dsn_normalize(uvec3 sums) { return dsn_normalize_from(sums, true); }

/* The same for sums with 32 more fraction bits (Q.32, the continuous mode's): the whole parts as above,
   the fractions added once, rounded down, before the final rounding. */
int dsn_normalize_q32_channel_from(uint c, uint channels, uvec2 sums[3], uvec2 accumulated) {
    uvec2 fractions = uvec2(0u);
    for (uint k = 0u; k < channels; k++) {
        int gain = dsn_gain(c, k);
        accumulated = dsn_add64(accumulated, dsn_multiply_signed_wide(gain, int(sums[k].y)));
        fractions = dsn_add64(fractions, dsn_multiply_mixed_wide(gain, sums[k].x));
    }
    int carried = int(fractions.y);
    accumulated = dsn_add64(accumulated, uvec2(uint(carried), carried < 0 ? 0xFFFFFFFFu : 0u));
    return dsn_round_saturate(accumulated, dsn_word(DSN_WORD_GAIN_SHIFT));
}

/* From the offsets (int64 pairs per channel) at word `offsets`, or from zero where it is 0. */
ivec3 dsn_normalize_q32_from(uvec2 sums[3], uint offsets) {
    uint channels = dsn_word(DSN_WORD_CHANNELS);
    ivec3 result = ivec3(0);
    for (uint c = 0u; c < channels; c++) {
        uint at = offsets + 2u * c;
        uvec2 offset = offsets == 0u ? uvec2(0u) : uvec2(dsn_word(at), dsn_word(at + 1u));
        int value = dsn_normalize_q32_channel_from(c, channels, sums, offset);
        if (c == 0u)
            result.x = value;
        else if (c == 1u)
            result.y = value;
        else
            result.z = value;
    }
    return result;
}

/* with_mean: a value (the noise's offset added); else a derivative's sums (no mean). */
ivec3 dsn_normalize_q32(uvec2 sums[3], bool with_mean) {
    return dsn_normalize_q32_from(sums, with_mean ? DSN_WORD_OFFSET : 0u);
}

/* ---- Lattice per point ---- */

uvec3 dsn_lattice_texton_entry(uint entry, uint channels) {
    uint at = dsn_word(DSN_WORD_LATTICE_TEXTON) + entry * channels;
    if (channels != 3u) return uvec3(dsn_word(at), 0u, 0u);
    return uvec3(dsn_word(at), dsn_word(at + 1u), dsn_word(at + 2u));
}

/* The texton index of an impulse at in-cell offset 0 along one axis (span base - cell origin) and the
   last acceptable in-cell offset (a period cuts the last cell). */
uvec2 dsn_lattice_cell_on_axis(dsn_span span, uint cell, uint shift) {
    uint origin = cell << shift, room = span.last_position - origin, side = (1u << shift) - 1u;
    return uvec2(span.base - origin, room < side ? room : side);
}

/* The channel sums Q_k (modulo 2^32) at lattice point (x, y): every impulse whose texton window holds
   the point adds its texton entry. With `east` (or `south`) the walk covers the window of the point and
   its neighbour (x + 1, y) (or (x, y + 1)) and also gives that neighbour's sums (else 0). */
void dsn_lattice_window_sums(uint x, uint y, bool east, bool south, out uvec3 at_point, out uvec3 at_east,
                             out uvec3 at_south) {
    uint shift = dsn_word(DSN_WORD_CELL_SHIFT), channels = dsn_word(DSN_WORD_CHANNELS);
    uint width = dsn_word(DSN_WORD_LATTICE_WIDTH), height = dsn_word(DSN_WORD_LATTICE_HEIGHT);
    uint field_shift = dsn_field_shift(shift), per_pair_shift = 6u - field_shift;
    uint half_bits = 1u << (field_shift - 1u), half_mask = (1u << half_bits) - 1u, drop = half_bits - shift;
    dsn_axis axis_x = dsn_axis_init(x, east ? 2u : 1u, dsn_word(DSN_WORD_LATTICE_RADIUS), shift,
                                    dsn_word(DSN_WORD_PERIOD));
    dsn_axis axis_y = dsn_axis_init(y, south ? 2u : 1u, dsn_word(DSN_WORD_LATTICE_RADIUS + 1u), shift,
                                    dsn_word(DSN_WORD_PERIOD + 1u));
    at_point = uvec3(0u);
    at_east = uvec3(0u);
    at_south = uvec3(0u);
    for (uint span_index_y = 0u; span_index_y < axis_y.span_count; span_index_y++) {
        dsn_span span_y = dsn_axis_span(axis_y, span_index_y);
        for (uint i = 0u; i < span_y.cell_count; i++) {
            uint cell_y = dsn_span_cell(span_y, i, shift), row_key = dsn_row_key(cell_y);
            uvec2 in_y = dsn_lattice_cell_on_axis(span_y, cell_y, shift);
            for (uint span_index_x = 0u; span_index_x < axis_x.span_count; span_index_x++) {
                dsn_span span_x = dsn_axis_span(axis_x, span_index_x);
                for (uint j = 0u; j < span_x.cell_count; j++) {
                    uint cell_x = dsn_span_cell(span_x, j, shift);
                    uvec2 in_x = dsn_lattice_cell_on_axis(span_x, cell_x, shift);
                    uint key = dsn_cell_key_in_row(cell_x, row_key), count = dsn_cell_impulse_count(key);
                    uvec2 pair = uvec2(0u);
                    for (uint k = 0u; k < count; k++) {
                        if ((k & ((1u << per_pair_shift) - 1u)) == 0u)
                            pair = dsn_position_pair(key, k >> per_pair_shift);
                        uint field = dsn_field_in_pair(pair, k, field_shift);
                        uint offset_x = (field & half_mask) >> drop,
                             offset_y = ((field >> half_bits) & half_mask) >> drop;
                        if (offset_x > in_x.y || offset_y > in_y.y) continue;
                        /* unsigned: -1 (in reach of a neighbour only) is outside the window */
                        uint column = in_x.x - offset_x, row = in_y.x - offset_y;
                        if (column < width && row < height)
                            at_point += dsn_lattice_texton_entry(row * width + column, channels);
                        if (east && column + 1u < width && row < height)
                            at_east += dsn_lattice_texton_entry(row * width + column + 1u, channels);
                        if (south && row + 1u < height && column < width)
                            at_south += dsn_lattice_texton_entry((row + 1u) * width + column, channels);
                    }
                }
            }
        }
    }
}

uvec3 dsn_lattice_sums(uint x, uint y) {
    uvec3 at_point, at_east, at_south;
    dsn_lattice_window_sums(x, y, false, false, at_point, at_east, at_south);
    return at_point;
}

/* Q16.16 values at lattice point p (int32 coordinates, wrapping like the C API's). */
ivec3 dsn_lattice_point_fixed(ivec2 p) { return dsn_normalize(dsn_lattice_sums(uint(p.x), uint(p.y))); }

/* The value at lattice point p and its forward differences dx = F(p + (1, 0)) - F(p) and
   dy = F(p + (0, 1)) - F(p) of the noise before its rounding (coordinates + 1 modulo 2^32), Q16.16:
   dsn_lattice_gradient_fixed's bits. One walk covers the point and both neighbours; on a periodic axis
   the coordinate 0x7FFFFFFF takes its neighbour (-2^31, reduced on its own) from a walk of its own. */
void dsn_lattice_gradient_fixed(ivec2 p, out ivec3 value, out ivec3 dx, out ivec3 dy) {
    uint x = uint(p.x), y = uint(p.y);
    bool east_apart = dsn_word(DSN_WORD_PERIOD) != 0u && x == 0x7FFFFFFFu;
    bool south_apart = dsn_word(DSN_WORD_PERIOD + 1u) != 0u && y == 0x7FFFFFFFu;
    uvec3 at_point = uvec3(0u), at_east = uvec3(0u), at_south = uvec3(0u);
    for (uint walk = 0u; walk < 3u; walk++) {
        if ((walk == 1u && !east_apart) || (walk == 2u && !south_apart)) continue;
        uvec3 sums, east, south;
        dsn_lattice_window_sums(walk == 1u ? x + 1u : x, walk == 2u ? y + 1u : y,
                                walk == 0u && !east_apart, walk == 0u && !south_apart, sums, east, south);
        if (walk == 0u) {
            at_point = sums;
            at_east = east;
            at_south = south;
        } else if (walk == 1u) {
            at_east = sums;
        } else {
            at_south = sums;
        }
    }
    value = dsn_normalize_from(at_point, true);
    dx = dsn_normalize_from(at_east - at_point, false);
    dy = dsn_normalize_from(at_south - at_point, false);
}

/* ---- Continuous per point ---- */

/* The 2 x 2 texels of `channel` with their top-left at (row, column): (above left, above right, below
   left, below right), 0 outside the window: the texton's quad (dsn/gpu.h), two words. */
ivec4 dsn_corners(uint row, uint column, uint channel, uint width, uint height, uint channels) {
    /* quads from row and column -1 (unsigned: row + 1 > height is outside, -1 included) */
    bool inside = row + 1u <= height && column + 1u <= width;
    uint quad = ((row + 1u) * (width + 1u) + column + 1u) * channels + channel;
    uint at = dsn_word(DSN_WORD_QUADS) + 2u * quad;
    uint above = inside ? dsn_word(at) : 0u, below = inside ? dsn_word(at + 1u) : 0u;
    return ivec4(int(above << 16u) >> 16, int(above) >> 16, int(below << 16u) >> 16, int(below) >> 16);
}

/* weights (1 - column_weight, column_weight, 1 - row_weight, row_weight) in Q0.16, multiples of 2^8 (the
   8-bit weights, dsn.h's continuous mode): in 32-bit words, each row's weighted pair in units of 2^-8
   (within 2^23) and the read, a weighted mean of the corners times 2^16 (within int32), then times 2^16
   as the 64-bit term. */
uvec2 dsn_bilinear(ivec4 corners, ivec4 weights) {
    ivec4 steps = weights >> 8;
    int upper = steps.x * corners.x + steps.y * corners.y;
    int lower = steps.x * corners.z + steps.y * corners.w;
    int read = steps.z * upper + steps.w * lower;
    return uvec2(uint(read) << 16u, uint(read >> 16));
}

/* The bilinear texton's slope per 2^-16 texel along x, (1 - row_weight)(b - a) + row_weight (d - c)
   (corners a b / c d), or along y with the weights and corners transposed: below 2^32 in magnitude. */
uvec2 dsn_slope(int a, int b, int c, int d, int lower_weight, int upper_weight) {
    return dsn_add64(dsn_multiply_signed_wide(lower_weight, b - a),
                     dsn_multiply_signed_wide(upper_weight, d - c));
}

/* One axis of an impulse seen from the point: false when it lies beyond the period or out of reach;
   else the texton index of the lower bracketing texel (0xFFFFFFFF for -1) and the upper one's weight.
   fraction: the low word of the point's coordinate. With entry_edge (the gradient) an impulse exactly
   at the edge where it enters the reach (offset -(radius + 1) texels) is kept: its value is 0, its
   slope is not. `shifted`: the point-minus-impulse offset plus radius + 1 texels, Q32.32. */
bool dsn_impulse_bracket(uint fraction, dsn_axis axis, dsn_span span, uint cell_origin, uint bits16,
                         bool entry_edge, out uint lower_index, out uint upper_weight, out uvec2 shifted) {
    lower_index = 0u;
    upper_weight = 0u;
    uint whole = 1u + span.base - axis.radius - cell_origin;
    uvec2 in_cell = dsn_shift_left64(uvec2(bits16, 0u), 16u + axis.shift);
    /* offset + (radius + 1) texels; the high word is a small signed number for any impulse in reach */
    shifted = dsn_sub64(uvec2(fraction, whole + axis.radius + 1u), in_cell);
    if (cell_origin + (bits16 >> (16u - axis.shift)) > span.last_position) return false;
    int high = int(shifted.y);
    if (high < 0 || (high == 0 && shifted.x == 0u && !entry_edge) || high >= int(2u * axis.radius + 2u))
        return false;
    lower_index = shifted.y - 1u;
    upper_weight = (shifted.x >> 16u) & 0xFF00u;
    return true;
}

/* The sums (Q.32 per channel, modulo 2^64) of every impulse of the window around (x, y); with `slopes`
   also those of the partial derivatives per 2^-16 texel (and the impulses at the entry edge). */
void dsn_continuous_sums(uvec2 x, uvec2 y, bool slopes, out uvec2 sums[3], out uvec2 slope_x[3],
                         out uvec2 slope_y[3]) {
    uint shift = dsn_word(DSN_WORD_CELL_SHIFT), channels = dsn_word(DSN_WORD_CHANNELS);
    uint width = dsn_word(DSN_WORD_WIDTH), height = dsn_word(DSN_WORD_HEIGHT);
    dsn_axis px = dsn_axis_init(x.y - 1u, 3u, dsn_word(DSN_WORD_RADIUS), shift, dsn_word(DSN_WORD_PERIOD));
    dsn_axis py =
        dsn_axis_init(y.y - 1u, 3u, dsn_word(DSN_WORD_RADIUS + 1u), shift, dsn_word(DSN_WORD_PERIOD + 1u));
    uint field_shift = dsn_field_shift(shift), per_pair_shift = 6u - field_shift;
    uint half_bits = 1u << (field_shift - 1u), half_mask = (1u << half_bits) - 1u, drop = half_bits - shift;
    uint diameter_x = 2u * px.radius + 2u, diameter_y = 2u * py.radius + 2u;
    for (uint c = 0u; c < 3u; c++) {
        sums[c] = uvec2(0u);
        slope_x[c] = uvec2(0u);
        slope_y[c] = uvec2(0u);
    }
    for (uint sy = 0u; sy < py.span_count; sy++) {
        dsn_span span_y = dsn_axis_span(py, sy);
        for (uint sx = 0u; sx < px.span_count; sx++) {
            dsn_span span_x = dsn_axis_span(px, sx);
            for (uint j = 0u; j < span_y.cell_count; j++) {
                uint cell_y = dsn_span_cell(span_y, j, shift), row_key = dsn_row_key(cell_y);
                /* reach - lattice offset is the impulse's distance in whole texels from radius + 1 texels
                   before the point: beyond [0, 2 radius + 2] it cannot reach the point (the fraction moves
                   it by less than a texel), so the fraction hash and exact test are left out. */
                uint reach_y = 1u + span_y.base - (cell_y << shift) + 1u;
                for (uint i = 0u; i < span_x.cell_count; i++) {
                    uint cell_x = dsn_span_cell(span_x, i, shift),
                         reach_x = 1u + span_x.base - (cell_x << shift) + 1u;
                    uint key = dsn_cell_key_in_row(cell_x, row_key), count = dsn_cell_impulse_count(key);
                    uvec2 pair = uvec2(0u);
                    for (uint k = 0u; k < count; k++) {
                        if ((k & ((1u << per_pair_shift) - 1u)) == 0u)
                            pair = dsn_position_pair(key, k >> per_pair_shift);
                        uint field = dsn_field_in_pair(pair, k, field_shift);
                        if (reach_x - ((field & half_mask) >> drop) > diameter_x ||
                            reach_y - (((field >> half_bits) & half_mask) >> drop) > diameter_y)
                            continue;
                        uint hash =
                            dsn_impulse_position(field, dsn_cell_stream(key, 0x80000000u + k), half_bits);
                        uint row, row_weight, column, column_weight;
                        uvec2 shifted_x, shifted_y;
                        if (!dsn_impulse_bracket(y.x, py, span_y, cell_y << shift, hash >> 16u, slopes, row,
                                                 row_weight, shifted_y))
                            continue;
                        if (!dsn_impulse_bracket(x.x, px, span_x, cell_x << shift, hash & 0xFFFFu, slopes,
                                                 column, column_weight, shifted_x))
                            continue;
                        ivec4 weights = ivec4(int(65536u - column_weight), int(column_weight),
                                              int(65536u - row_weight), int(row_weight));
                        for (uint c = 0u; c < channels; c++) {
                            ivec4 corners = dsn_corners(row, column, c, width, height, channels);
                            sums[c] = dsn_add64(sums[c], dsn_bilinear(corners, weights));
                            if (!slopes) continue;
                            slope_x[c] = dsn_add64(slope_x[c], dsn_slope(corners.x, corners.y, corners.z,
                                                                         corners.w, weights.z, weights.w));
                            slope_y[c] = dsn_add64(slope_y[c], dsn_slope(corners.x, corners.z, corners.y,
                                                                         corners.w, weights.x, weights.y));
                        }
                    }
                }
            }
        }
    }
}

/* Q16.16 values at the continuous point (x, y), each a Q32.32 coordinate as uvec2(low, high); all 0
   when the noise may not be used in continuous mode (dsn_continuous_check). */
ivec3 dsn_continuous_point_fixed(uvec2 x, uvec2 y) {
    if (dsn_word(DSN_WORD_CONTINUOUS) == 0u) return ivec3(0);
    uvec2 sums[3], slope_x[3], slope_y[3];
    dsn_continuous_sums(x, y, false, sums, slope_x, slope_y);
    return dsn_normalize_q32(sums, true);
}

/* The value at the continuous point (x, y) (as dsn_continuous_point_fixed) and its exact partial
   derivatives per texel, Q16.16: dsn_continuous_gradient_fixed's bits (one-sided, toward +x and +y, on
   a texel edge of some impulse). All 0 when the noise may not be used in continuous mode. */
void dsn_continuous_gradient_fixed(uvec2 x, uvec2 y, out ivec3 value, out ivec3 dx, out ivec3 dy) {
    value = ivec3(0);
    dx = ivec3(0);
    dy = ivec3(0);
    if (dsn_word(DSN_WORD_CONTINUOUS) == 0u) return;
    uvec2 sums[3], slope_x[3], slope_y[3];
    dsn_continuous_sums(x, y, true, sums, slope_x, slope_y);
    /* per 2^-16 texel to per texel, with the value sums' 32 fraction bits (modulo 2^64) */
    for (uint c = 0u; c < 3u; c++) {
        slope_x[c] = dsn_shift_left64(slope_x[c], 16u);
        slope_y[c] = dsn_shift_left64(slope_y[c], 16u);
    }
    value = dsn_normalize_q32(sums, true);
    dx = dsn_normalize_q32(slope_x, false);
    dy = dsn_normalize_q32(slope_y, false);
}

/* ---- Workgroup tiles (compute shaders that #define DSN_GLSL_TILES 1 before this file) ----
   A workgroup evaluates a window of points together: its invocations share out the cells that can reach
   the window, list the impulses that do (their texton indices, or their positions, relative to the
   window) in shared memory, and each invocation then sums its own point from that list. No hash is
   computed twice, and the sums are those of the point functions (the same impulses, added modulo 2^32 or
   2^64 in any order): the same bits. The caller places the barriers, in main():
       dsn_tile_begin();                                  barrier();
       dsn_lattice_tile_list(origin, size);               barrier();
       ivec3 value = dsn_lattice_tile_point_fixed(origin, size, p);
   and likewise dsn_continuous_tile_list and dsn_continuous_tile_point_fixed over a box of points (for a
   grid, dsn_grid_tile_box gives the box of a workgroup's pixels). Every invocation passes the same window.
   A point outside the window, a window on a periodic axis across the int32 sign change (where the
   reduction modulo the period breaks the coordinates' contiguity) or a list past DSN_TILE_CAPACITY
   impulses falls back on the point functions. */
#ifdef DSN_GLSL_TILES
#if DSN_GLSL_TILES

const uint DSN_TILE_CAPACITY = 512u; /* 8 KB of shared memory */
shared uint dsn_tile_count;
shared uvec4 dsn_tile_list[DSN_TILE_CAPACITY];

void dsn_tile_begin() {
    if (gl_LocalInvocationIndex == 0u) dsn_tile_count = 0u;
}

void dsn_tile_add(uvec4 entry) {
    uint slot = atomicAdd(dsn_tile_count, 1u);
    if (slot < DSN_TILE_CAPACITY) dsn_tile_list[slot] = entry;
}

/* Whether this invocation lists cell `index` of the window's cells (each takes every n-th). */
bool dsn_tile_cell_is_mine(uint index) {
    return index % (gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z) == gl_LocalInvocationIndex;
}

/* Whether `length` coordinates from `first` on an axis of this period cross the int32 sign change. */
bool dsn_tile_breaks(uint first, uint length, uint period) {
    uint until_sign_change = 0x80000000u - first;
    return period != 0u && until_sign_change != 0u && until_sign_change < length;
}

bool dsn_lattice_tile_breaks(ivec2 origin, uvec2 size) {
    return dsn_tile_breaks(uint(origin.x), size.x, dsn_word(DSN_WORD_PERIOD)) ||
           dsn_tile_breaks(uint(origin.y), size.y, dsn_word(DSN_WORD_PERIOD + 1u));
}

/* Lists the impulses that reach the window of size.x x size.y lattice points from `origin`: each as the
   texton entry, column and row that it adds at the window's first point (at point origin + (i, j):
   column + i and row + j, when within the texton, at entry + j width + i). */
void dsn_lattice_tile_list(ivec2 origin, uvec2 size) {
    if (dsn_lattice_tile_breaks(origin, size)) return;
    uint shift = dsn_word(DSN_WORD_CELL_SHIFT);
    uint width = dsn_word(DSN_WORD_LATTICE_WIDTH), height = dsn_word(DSN_WORD_LATTICE_HEIGHT);
    uint field_shift = dsn_field_shift(shift), per_pair_shift = 6u - field_shift;
    uint half_bits = 1u << (field_shift - 1u), half_mask = (1u << half_bits) - 1u, drop = half_bits - shift;
    dsn_axis axis_x = dsn_axis_init(uint(origin.x), size.x, dsn_word(DSN_WORD_LATTICE_RADIUS), shift,
                                    dsn_word(DSN_WORD_PERIOD));
    dsn_axis axis_y = dsn_axis_init(uint(origin.y), size.y, dsn_word(DSN_WORD_LATTICE_RADIUS + 1u), shift,
                                    dsn_word(DSN_WORD_PERIOD + 1u));
    uint cell_index = 0u;
    for (uint span_index_y = 0u; span_index_y < axis_y.span_count; span_index_y++) {
        dsn_span span_y = dsn_axis_span(axis_y, span_index_y);
        for (uint i = 0u; i < span_y.cell_count; i++) {
            uint cell_y = dsn_span_cell(span_y, i, shift);
            uvec2 in_y = dsn_lattice_cell_on_axis(span_y, cell_y, shift);
            for (uint span_index_x = 0u; span_index_x < axis_x.span_count; span_index_x++) {
                dsn_span span_x = dsn_axis_span(axis_x, span_index_x);
                for (uint j = 0u; j < span_x.cell_count; j++, cell_index++) {
                    if (!dsn_tile_cell_is_mine(cell_index)) continue;
                    uint cell_x = dsn_span_cell(span_x, j, shift);
                    uvec2 in_x = dsn_lattice_cell_on_axis(span_x, cell_x, shift);
                    uint key = dsn_cell_key_in_row(cell_x, dsn_row_key(cell_y));
                    uint count = dsn_cell_impulse_count(key);
                    uvec2 pair = uvec2(0u);
                    for (uint k = 0u; k < count; k++) {
                        if ((k & ((1u << per_pair_shift) - 1u)) == 0u)
                            pair = dsn_position_pair(key, k >> per_pair_shift);
                        uint field = dsn_field_in_pair(pair, k, field_shift);
                        uint offset_x = (field & half_mask) >> drop,
                             offset_y = ((field >> half_bits) & half_mask) >> drop;
                        if (offset_x > in_x.y || offset_y > in_y.y) continue;
                        /* within the texton at some point of the window: column in [1 - size.x, width) */
                        uint column = in_x.x - offset_x, row = in_y.x - offset_y;
                        if (column + size.x - 1u < width + size.x - 1u &&
                            row + size.y - 1u < height + size.y - 1u)
                            dsn_tile_add(uvec4(row * width + column, column, row, 0u));
                    }
                }
            }
        }
    }
}

/* Q16.16 values at lattice point p of the listed window: dsn_lattice_point_fixed's bits. */
ivec3 dsn_lattice_tile_point_fixed(ivec2 origin, uvec2 size, ivec2 p) {
    uint i = uint(p.x) - uint(origin.x), j = uint(p.y) - uint(origin.y);
    bool listed = i < size.x && j < size.y && dsn_tile_count <= DSN_TILE_CAPACITY &&
                  !dsn_lattice_tile_breaks(origin, size);
    uint count = listed ? dsn_tile_count : 0u;
    uint channels = dsn_word(DSN_WORD_CHANNELS);
    uint width = dsn_word(DSN_WORD_LATTICE_WIDTH), height = dsn_word(DSN_WORD_LATTICE_HEIGHT);
    uvec3 sums = uvec3(0u);
    uint moved = j * width + i;
    for (uint e = 0u; e < count; e++) {
        uvec4 entry = dsn_tile_list[e];
        if (entry.y + i < width && entry.z + j < height)
            sums += dsn_lattice_texton_entry(entry.x + moved, channels);
    }
    /* the fallback after the loop, as a statement (see dsn_continuous_tile_point_fixed) */
    ivec3 value = dsn_normalize(sums);
    if (!listed) value = dsn_lattice_point_fixed(p);
    return value;
}

/* The most whole texels a continuous tile's box may span per axis (beyond, the points go on their own). */
const uint DSN_TILE_MOST_EXTENT = 256u;

/* The box of the grid points origin + i column_step + j row_step (Q32.32, (x low, x high, y low,
   y high)) for the pixels first + [0, size): its low corner and its extent in whole texels (the points'
   integer parts lie within [low, low + extent]); extent 0xFFFFFFFF where the box is too large. */
void dsn_grid_tile_box(uvec4 origin, uvec4 column_step, uvec4 row_step, uvec2 first, uvec2 size,
                       out uvec2 low_x, out uvec2 low_y, out uvec2 extent) {
    uvec2 corner[2], low[2];
    for (uint axis = 0u; axis < 2u; axis++) {
        uvec2 along_row = axis == 0u ? column_step.xy : column_step.zw;
        uvec2 along_column = axis == 0u ? row_step.xy : row_step.zw;
        corner[axis] = dsn_add64(axis == 0u ? origin.xy : origin.zw,
                                 dsn_add64(dsn_multiply64(uvec2(first.x, 0u), along_row),
                                           dsn_multiply64(uvec2(first.y, 0u), along_column)));
        uvec2 a = dsn_multiply64(uvec2(size.x - 1u, 0u), along_row);
        uvec2 b = dsn_multiply64(uvec2(size.y - 1u, 0u), along_column);
        /* the steps' spans, each under 2^24 texels in magnitude, so that low and high stay in order */
        bool small = dsn_at_most64(dsn_magnitude64(a), uvec2(0u, 0x1000000u)) &&
                     dsn_at_most64(dsn_magnitude64(b), uvec2(0u, 0x1000000u));
        uvec2 below = dsn_add64(int(a.y) < 0 ? a : uvec2(0u), int(b.y) < 0 ? b : uvec2(0u));
        uvec2 above = dsn_add64(int(a.y) < 0 ? uvec2(0u) : a, int(b.y) < 0 ? uvec2(0u) : b);
        low[axis] = dsn_add64(corner[axis], below);
        uvec2 high = dsn_add64(corner[axis], above);
        uint whole = high.y - low[axis].y;
        extent[axis] = small && whole <= DSN_TILE_MOST_EXTENT ? whole : 0xFFFFFFFFu;
    }
    low_x = low[0];
    low_y = low[1];
}

bool dsn_continuous_tile_breaks(uvec2 low_x, uvec2 low_y, uvec2 extent) {
    return extent.x > DSN_TILE_MOST_EXTENT || extent.y > DSN_TILE_MOST_EXTENT ||
           dsn_tile_breaks(low_x.y - 1u, extent.x + 3u, dsn_word(DSN_WORD_PERIOD)) ||
           dsn_tile_breaks(low_y.y - 1u, extent.y + 3u, dsn_word(DSN_WORD_PERIOD + 1u));
}

/* Lists the impulses that may reach a continuous point whose integer parts lie within [low, low +
   extent] per axis: each as its offset from the texel low (Q32.32 per axis, (x, y)), its point-to-impulse
   offset being the point's offset from that texel plus this one (the per-point walk's windows of three
   texels, [floor - 1, floor + 1] plus the radius, lie within the box's, [floor(low) - 1, floor(low) +
   extent + 1] plus the radius). */
void dsn_continuous_tile_list(uvec2 low_x, uvec2 low_y, uvec2 extent) {
    if (dsn_word(DSN_WORD_CONTINUOUS) == 0u || dsn_continuous_tile_breaks(low_x, low_y, extent)) return;
    uint shift = dsn_word(DSN_WORD_CELL_SHIFT);
    dsn_axis px = dsn_axis_init(low_x.y - 1u, extent.x + 3u, dsn_word(DSN_WORD_RADIUS), shift,
                                dsn_word(DSN_WORD_PERIOD));
    dsn_axis py = dsn_axis_init(low_y.y - 1u, extent.y + 3u, dsn_word(DSN_WORD_RADIUS + 1u), shift,
                                dsn_word(DSN_WORD_PERIOD + 1u));
    uint field_shift = dsn_field_shift(shift), per_pair_shift = 6u - field_shift;
    uint half_bits = 1u << (field_shift - 1u), half_mask = (1u << half_bits) - 1u, drop = half_bits - shift;
    uint diameter_x = 2u * px.radius + 2u + extent.x, diameter_y = 2u * py.radius + 2u + extent.y;
    uint cell_index = 0u;
    for (uint sy = 0u; sy < py.span_count; sy++) {
        dsn_span span_y = dsn_axis_span(py, sy);
        for (uint j = 0u; j < span_y.cell_count; j++) {
            uint cell_y = dsn_span_cell(span_y, j, shift);
            /* as the point's walk's, for the farthest point of the box */
            uint reach_y = 1u + span_y.base - (cell_y << shift) + 1u + extent.y;
            for (uint sx = 0u; sx < px.span_count; sx++) {
                dsn_span span_x = dsn_axis_span(px, sx);
                for (uint i = 0u; i < span_x.cell_count; i++, cell_index++) {
                    if (!dsn_tile_cell_is_mine(cell_index)) continue;
                    uint cell_x = dsn_span_cell(span_x, i, shift),
                         reach_x = 1u + span_x.base - (cell_x << shift) + 1u + extent.x;
                    uint key = dsn_cell_key_in_row(cell_x, dsn_row_key(cell_y));
                    uint count = dsn_cell_impulse_count(key);
                    uvec2 pair = uvec2(0u);
                    for (uint k = 0u; k < count; k++) {
                        if ((k & ((1u << per_pair_shift) - 1u)) == 0u)
                            pair = dsn_position_pair(key, k >> per_pair_shift);
                        uint field = dsn_field_in_pair(pair, k, field_shift);
                        if (reach_x - ((field & half_mask) >> drop) > diameter_x ||
                            reach_y - (((field >> half_bits) & half_mask) >> drop) > diameter_y)
                            continue;
                        uint hash =
                            dsn_impulse_position(field, dsn_cell_stream(key, 0x80000000u + k), half_bits);
                        if ((cell_x << shift) + ((hash & 0xFFFFu) >> (16u - shift)) > span_x.last_position ||
                            (cell_y << shift) + ((hash >> 16u) >> (16u - shift)) > span_y.last_position)
                            continue;
                        /* texel low - impulse: (1 + span base - radius - cell origin) texels less the in-cell
                           position, as dsn_impulse_bracket's offset for a point at low */
                        uint whole_x = 1u + span_x.base - px.radius - (cell_x << shift);
                        uint whole_y = 1u + span_y.base - py.radius - (cell_y << shift);
                        uvec2 offset_x = dsn_sub64(uvec2(0u, whole_x),
                                                   dsn_shift_left64(uvec2(hash & 0xFFFFu, 0u), 16u + shift));
                        uvec2 offset_y = dsn_sub64(uvec2(0u, whole_y),
                                                   dsn_shift_left64(uvec2(hash >> 16u, 0u), 16u + shift));
                        dsn_tile_add(uvec4(offset_x, offset_y));
                    }
                }
            }
        }
    }
}

/* One axis of a listed impulse seen from the point `coordinate` (its texel `low` the box's): false out of
   reach; else the lower texel's index and the upper one's weight, as dsn_impulse_bracket gives them. */
bool dsn_tile_bracket(uvec2 offset, uvec2 coordinate, uint low, uint radius, out uint lower_index,
                      out uint upper_weight) {
    uvec2 shifted = dsn_add64(offset, uvec2(coordinate.x, coordinate.y - low + radius + 1u));
    int high = int(shifted.y);
    lower_index = shifted.y - 1u;
    upper_weight = (shifted.x >> 16u) & 0xFF00u;
    return high > 0 ? high < int(2u * radius + 2u) : high == 0 && shifted.x != 0u;
}

/* Q16.16 values at the continuous point (x, y) of the listed box: dsn_continuous_point_fixed's bits. */
ivec3 dsn_continuous_tile_point_fixed(uvec2 low_x, uvec2 low_y, uvec2 extent, uvec2 x, uvec2 y) {
    bool listed = dsn_word(DSN_WORD_CONTINUOUS) != 0u && x.y - low_x.y <= extent.x &&
                  y.y - low_y.y <= extent.y && dsn_tile_count <= DSN_TILE_CAPACITY &&
                  !dsn_continuous_tile_breaks(low_x, low_y, extent);
    uint count = listed ? dsn_tile_count : 0u;
    uint channels = dsn_word(DSN_WORD_CHANNELS);
    uint width = dsn_word(DSN_WORD_WIDTH), height = dsn_word(DSN_WORD_HEIGHT);
    uint radius_x = dsn_word(DSN_WORD_RADIUS), radius_y = dsn_word(DSN_WORD_RADIUS + 1u);
    uvec2 sum_x = uvec2(0u), sum_y = uvec2(0u), sum_z = uvec2(0u); /* the channels' */
    for (uint e = 0u; e < count; e++) {
        uvec4 entry = dsn_tile_list[e];
        uint row, row_weight, column, column_weight;
        if (!dsn_tile_bracket(entry.zw, y, low_y.y, radius_y, row, row_weight) ||
            !dsn_tile_bracket(entry.xy, x, low_x.y, radius_x, column, column_weight))
            continue;
        ivec4 weights = ivec4(int(65536u - column_weight), int(column_weight), int(65536u - row_weight),
                              int(row_weight));
        /* the channels unrolled: a loop over them indexing the sums runs several times slower on some
           compilers */
        ivec4 corners = dsn_corners(row, column, 0u, width, height, channels);
        sum_x = dsn_add64(sum_x, dsn_bilinear(corners, weights));
        if (channels != 3u) continue;
        corners = dsn_corners(row, column, 1u, width, height, channels);
        sum_y = dsn_add64(sum_y, dsn_bilinear(corners, weights));
        corners = dsn_corners(row, column, 2u, width, height, channels);
        sum_z = dsn_add64(sum_z, dsn_bilinear(corners, weights));
    }
    uvec2 sums[3];
    sums[0] = sum_x;
    sums[1] = sum_y;
    sums[2] = sum_z;
    /* The fallback after the loop, as a statement: an early return before the loop, or a conditional
       expression, costs llvmpipe the loop's speed (2.5-3x). */
    ivec3 value = dsn_normalize_q32(sums, true);
    if (!listed) value = dsn_continuous_point_fixed(x, y);
    return value;
}

#endif
#endif /* DSN_GLSL_TILES */

/* ---- Mixing (dsn.h, "Mixing"): the words of dsn_gpu_mix_pack (dsn/gpu.h) ---- */

const uint DSN_MIX_WORD_COUNT = 3u;
const uint DSN_MIX_WORD_CHANNELS = 4u;
const uint DSN_MIX_WORD_RADIUS = 5u;         /* x, then y */
const uint DSN_MIX_WORD_LATTICE_RADIUS = 7u; /* x, then y */
const uint DSN_MIX_WORD_MATERIAL = 9u;       /* where material m's words start */
const uint DSN_MIX_WORD_CONTROL = 13u;

/* Component i < 4 of v. The mix never indexes a vector or an array by a value that may differ between
   invocations (an impulse's material): softpipe, Mesa's reference rasterizer, gets such indexing wrong
   where llvmpipe does not. Writes go through a loop over the four slots instead. */
uint dsn_mix_at(uvec4 v, uint i) { return i == 0u ? v.x : i == 1u ? v.y : i == 2u ? v.z : v.w; }

/* Word `index` of the whole mix buffer, whichever material's words dsn_word reads now. */
uint dsn_mix_word(uint index) {
    uint saved = dsn_word_base;
    dsn_word_base = 0u;
    uint word = dsn_word(index);
    dsn_word_base = saved;
    return word;
}

/* The control (dsn_mix_control) as packed: the word where it starts and its fields. */
struct dsn_mix_grid {
    uint start, width, height, shift, flags, count;
    int origin_x, origin_y;
};

dsn_mix_grid dsn_mix_grid_read() {
    uint start = dsn_mix_word(DSN_MIX_WORD_CONTROL);
    return dsn_mix_grid(start, dsn_mix_word(start), dsn_mix_word(start + 1u), dsn_mix_word(start + 2u),
                        dsn_mix_word(start + 5u), dsn_mix_word(DSN_MIX_WORD_COUNT),
                        int(dsn_mix_word(start + 3u)), int(dsn_mix_word(start + 4u)));
}

/* One axis of the grid's bilinear read at a Q32.32 position: (lower sample, upper sample, the upper one's
   8-bit weight), the lower sample floor((position - origin) / 2^shift) clamped or wrapped. */
uvec3 dsn_mix_axis(uvec2 position, int origin, uint shift, uint size, bool periodic) {
    uvec2 relative = uvec2(position.x, position.y - uint(origin));
    /* floor of the signed whole part over 2^shift, through a 2^31 bias; in [-2^31, 2^31) */
    int index = int(((relative.y ^ 0x80000000u) >> shift) - (0x80000000u >> shift));
    uint fraction = dsn_shift_right64(relative, 24u + shift).x & 0xFFu;
    uint first, second;
    if (periodic) {
        first = index < 0 ? size - 1u - (~uint(index)) % size : uint(index) % size;
        second = first + 1u == size ? 0u : first + 1u;
    } else {
        first = index < 0 ? 0u : index >= int(size) ? size - 1u : uint(index);
        second = index < -1 ? 0u : index >= int(size) - 1 ? size - 1u : uint(index + 1);
    }
    return uvec3(first, second, fraction);
}

/* Material m's weight byte at sample (column, row). */
uint dsn_mix_sample(dsn_mix_grid grid, uint column, uint row, uint m) {
    uint i = (row * grid.width + column) * grid.count + m;
    return (dsn_mix_word(grid.start + 6u + (i >> 2u)) >> (8u * (i & 3u))) & 0xFFu;
}

/* The running sums V_0 + .. + V_m of the weights at a Q32.32 position (the last, T, in [count - 1]). */
uvec4 dsn_mix_cumulative(dsn_mix_grid grid, uvec2 x, uvec2 y) {
    uvec3 ax = dsn_mix_axis(x, grid.origin_x, grid.shift, grid.width, (grid.flags & 1u) != 0u);
    uvec3 ay = dsn_mix_axis(y, grid.origin_y, grid.shift, grid.height, (grid.flags & 2u) != 0u);
    uvec4 cumulative = uvec4(0u);
    uint total = 0u;
    for (uint m = 0u; m < grid.count; m++) {
        uint upper =
            (256u - ax.z) * dsn_mix_sample(grid, ax.x, ay.x, m) + ax.z * dsn_mix_sample(grid, ax.y, ay.x, m);
        uint lower =
            (256u - ax.z) * dsn_mix_sample(grid, ax.x, ay.y, m) + ax.z * dsn_mix_sample(grid, ax.y, ay.y, m);
        total += ((256u - ay.z) * upper + ay.z * lower) >> 8u;
        cumulative[m] = total;
    }
    return cumulative;
}

/* The material that impulse k of the cell with this key picks at its lattice position (x, y): the first m
   with floor(h T / 2^32) < V_0 + .. + V_m; material 0 where T is 0. */
uint dsn_mix_pick(dsn_mix_grid grid, uint key, uint k, uint x, uint y) {
    uvec4 cumulative = dsn_mix_cumulative(grid, uvec2(0u, x), uvec2(0u, y));
    uint total = dsn_mix_at(cumulative, grid.count - 1u);
    if (total == 0u) return 0u;
    uint draw = dsn_multiply_wide(dsn_cell_stream(key, 0xC0000000u + k), total).y;
    uint m = 0u;
    while (m + 1u < grid.count && draw >= dsn_mix_at(cumulative, m)) m++;
    return m;
}

/* The point's weights in Q2.14, summing to 2^14: differences of floor(2^14 cumulative / T). */
uvec4 dsn_mix_point_weights(dsn_mix_grid grid, uvec2 x, uvec2 y) {
    uvec4 cumulative = dsn_mix_cumulative(grid, x, y), weights = uvec4(0u);
    uint total = dsn_mix_at(cumulative, grid.count - 1u), before = 0u;
    for (uint m = 0u; m < grid.count; m++) {
        uint upto = total == 0u ? 16384u : (dsn_mix_at(cumulative, m) << 14u) / total;
        weights[m] = upto - before;
        before = upto;
    }
    return weights;
}

/* floor(offset weight / 2^14) of an int64 offset (two's complement), weight <= 2^14. */
uvec2 dsn_mix_weighted_offset(uvec2 offset, uint weight) {
    uvec2 high = uvec2((offset.x >> 14u) | (offset.y << 18u), uint(int(offset.y) >> 14));
    uvec2 whole = dsn_multiply64(high, uvec2(weight, 0u));
    return dsn_add64(whole, uvec2(((offset.x & 0x3FFFu) * weight) >> 14u, 0u));
}

/* The materials' values summed: `totals` per channel (int64 as uvec2), a grey material's value in each. */
void dsn_mix_add_value(ivec3 value, uint channels, inout uvec2 totals[3]) {
    for (uint c = 0u; c < 3u; c++) {
        int v = channels == 1u ? value.x : c == 0u ? value.x : c == 1u ? value.y : value.z;
        totals[c] = dsn_add64(totals[c], uvec2(uint(v), v < 0 ? 0xFFFFFFFFu : 0u));
    }
}

/* The totals saturated to int32, the mix's channels (grey: .x only). */
ivec3 dsn_mix_output(uvec2 totals[3]) {
    ivec3 result = ivec3(0);
    for (uint c = 0u; c < dsn_mix_word(DSN_MIX_WORD_CHANNELS); c++) {
        int high = int(totals[c].y), low = int(totals[c].x);
        int value = high == (low < 0 ? -1 : 0) ? low : high < 0 ? int(0x80000000u) : 0x7FFFFFFF;
        if (c == 0u)
            result.x = value;
        else if (c == 1u)
            result.y = value;
        else
            result.z = value;
    }
    return result;
}

/* The words of every material's pack, and whether each may be read in continuous mode. */
uvec4 dsn_mix_bases(out bool continuous) {
    uvec4 bases = uvec4(0u);
    continuous = true;
    for (uint m = 0u; m < dsn_mix_word(DSN_MIX_WORD_COUNT); m++) {
        bases[m] = dsn_mix_word(DSN_MIX_WORD_MATERIAL + m);
        continuous = continuous && dsn_mix_word(bases[m] + DSN_WORD_CONTINUOUS) != 0u;
    }
    return bases;
}

/* Q16.16 values of the mix at lattice point p: one walk of material 0's impulses within the largest
   lattice reach, each impulse adding its picked material's lattice texton entry to that material's sums;
   then each material's sums normalized from its weighted mean, and summed (dsn_mix_lattice_point_fixed's
   bits). */
ivec3 dsn_mix_lattice_point_fixed(ivec2 p) {
    bool continuous;
    uvec4 bases = dsn_mix_bases(continuous);
    dsn_mix_grid grid = dsn_mix_grid_read();
    uint x = uint(p.x), y = uint(p.y);
    uint reach_x = dsn_mix_word(DSN_MIX_WORD_LATTICE_RADIUS),
         reach_y = dsn_mix_word(DSN_MIX_WORD_LATTICE_RADIUS + 1u);
    uvec3 sums[4];
    for (uint m = 0u; m < 4u; m++) sums[m] = uvec3(0u);
    dsn_word_base = bases.x;
    uint shift = dsn_word(DSN_WORD_CELL_SHIFT);
    uint field_shift = dsn_field_shift(shift), per_pair_shift = 6u - field_shift;
    uint half_bits = 1u << (field_shift - 1u), half_mask = (1u << half_bits) - 1u, drop = half_bits - shift;
    dsn_axis axis_x = dsn_axis_init(x, 1u, reach_x, shift, dsn_word(DSN_WORD_PERIOD));
    dsn_axis axis_y = dsn_axis_init(y, 1u, reach_y, shift, dsn_word(DSN_WORD_PERIOD + 1u));
    for (uint span_index_y = 0u; span_index_y < axis_y.span_count; span_index_y++) {
        dsn_span span_y = dsn_axis_span(axis_y, span_index_y);
        for (uint i = 0u; i < span_y.cell_count; i++) {
            uint cell_y = dsn_span_cell(span_y, i, shift), row_key = dsn_row_key(cell_y);
            uvec2 in_y = dsn_lattice_cell_on_axis(span_y, cell_y, shift);
            for (uint span_index_x = 0u; span_index_x < axis_x.span_count; span_index_x++) {
                dsn_span span_x = dsn_axis_span(axis_x, span_index_x);
                for (uint j = 0u; j < span_x.cell_count; j++) {
                    uint cell_x = dsn_span_cell(span_x, j, shift);
                    uvec2 in_x = dsn_lattice_cell_on_axis(span_x, cell_x, shift);
                    uint key = dsn_cell_key_in_row(cell_x, row_key), count = dsn_cell_impulse_count(key);
                    uvec2 pair = uvec2(0u);
                    for (uint k = 0u; k < count; k++) {
                        if ((k & ((1u << per_pair_shift) - 1u)) == 0u)
                            pair = dsn_position_pair(key, k >> per_pair_shift);
                        uint field = dsn_field_in_pair(pair, k, field_shift);
                        uint offset_x = (field & half_mask) >> drop,
                             offset_y = ((field >> half_bits) & half_mask) >> drop;
                        if (offset_x > in_x.y || offset_y > in_y.y) continue;
                        /* indices in the walk's window (radius reach); the impulse at x + reach - column */
                        uint column = in_x.x - offset_x, row = in_y.x - offset_y;
                        if (column > 2u * reach_x || row > 2u * reach_y) continue;
                        uint m = dsn_mix_pick(grid, key, k, x + reach_x - column, y + reach_y - row);
                        dsn_word_base = dsn_mix_at(bases, m);
                        uint width = dsn_word(DSN_WORD_LATTICE_WIDTH),
                             height = dsn_word(DSN_WORD_LATTICE_HEIGHT);
                        uint own_column = column - reach_x + dsn_word(DSN_WORD_LATTICE_RADIUS);
                        uint own_row = row - reach_y + dsn_word(DSN_WORD_LATTICE_RADIUS + 1u);
                        uvec3 entry = own_column < width && own_row < height
                                          ? dsn_lattice_texton_entry(own_row * width + own_column,
                                                                     dsn_word(DSN_WORD_CHANNELS))
                                          : uvec3(0u);
                        for (uint slot = 0u; slot < 4u; slot++)
                            if (slot == m) sums[slot] += entry;
                        dsn_word_base = bases.x;
                    }
                }
            }
        }
    }
    uvec4 weights = dsn_mix_point_weights(grid, uvec2(0u, x), uvec2(0u, y));
    uvec2 totals[3];
    for (uint c = 0u; c < 3u; c++) totals[c] = uvec2(0u);
    for (uint m = 0u; m < grid.count; m++) {
        dsn_word_base = dsn_mix_at(bases, m);
        uint channels = dsn_word(DSN_WORD_CHANNELS);
        ivec3 value = ivec3(0);
        for (uint c = 0u; c < channels; c++) {
            int v = dsn_normalize_channel_from(c, channels, sums[m],
                                               dsn_mix_weighted_offset(dsn_offset(c), dsn_mix_at(weights, m)));
            if (c == 0u)
                value.x = v;
            else if (c == 1u)
                value.y = v;
            else
                value.z = v;
        }
        dsn_mix_add_value(value, channels, totals);
    }
    dsn_word_base = 0u;
    return dsn_mix_output(totals);
}

/* Q16.16 values of the mix at the continuous point (x, y), Q32.32 as uvec2(low, high): one walk of material
   0's impulses within the largest reach, each impulse reading its picked material's texton bilinearly
   (dsn_mix_continuous_point_fixed's bits); all 0 when a material may not be used in continuous mode. */
ivec3 dsn_mix_continuous_point_fixed(uvec2 x, uvec2 y) {
    bool continuous;
    uvec4 bases = dsn_mix_bases(continuous);
    if (!continuous) return ivec3(0);
    dsn_mix_grid grid = dsn_mix_grid_read();
    uint reach_x = dsn_mix_word(DSN_MIX_WORD_RADIUS), reach_y = dsn_mix_word(DSN_MIX_WORD_RADIUS + 1u);
    uvec2 sums[12];
    for (uint s = 0u; s < 12u; s++) sums[s] = uvec2(0u);
    dsn_word_base = bases.x;
    uint shift = dsn_word(DSN_WORD_CELL_SHIFT);
    dsn_axis px = dsn_axis_init(x.y - 1u, 3u, reach_x, shift, dsn_word(DSN_WORD_PERIOD));
    dsn_axis py = dsn_axis_init(y.y - 1u, 3u, reach_y, shift, dsn_word(DSN_WORD_PERIOD + 1u));
    uint field_shift = dsn_field_shift(shift), per_pair_shift = 6u - field_shift;
    uint half_bits = 1u << (field_shift - 1u), half_mask = (1u << half_bits) - 1u, drop = half_bits - shift;
    uint diameter_x = 2u * reach_x + 2u, diameter_y = 2u * reach_y + 2u;
    for (uint sy = 0u; sy < py.span_count; sy++) {
        dsn_span span_y = dsn_axis_span(py, sy);
        for (uint sx = 0u; sx < px.span_count; sx++) {
            dsn_span span_x = dsn_axis_span(px, sx);
            for (uint j = 0u; j < span_y.cell_count; j++) {
                uint cell_y = dsn_span_cell(span_y, j, shift), row_key = dsn_row_key(cell_y);
                uint room_y = 1u + span_y.base - (cell_y << shift) + 1u; /* as dsn_continuous_sums */
                for (uint i = 0u; i < span_x.cell_count; i++) {
                    uint cell_x = dsn_span_cell(span_x, i, shift),
                         room_x = 1u + span_x.base - (cell_x << shift) + 1u;
                    uint key = dsn_cell_key_in_row(cell_x, row_key), count = dsn_cell_impulse_count(key);
                    uvec2 pair = uvec2(0u);
                    for (uint k = 0u; k < count; k++) {
                        if ((k & ((1u << per_pair_shift) - 1u)) == 0u)
                            pair = dsn_position_pair(key, k >> per_pair_shift);
                        uint field = dsn_field_in_pair(pair, k, field_shift);
                        if (room_x - ((field & half_mask) >> drop) > diameter_x ||
                            room_y - (((field >> half_bits) & half_mask) >> drop) > diameter_y)
                            continue;
                        uint hash =
                            dsn_impulse_position(field, dsn_cell_stream(key, 0x80000000u + k), half_bits);
                        uint row, row_weight, column, column_weight;
                        uvec2 shifted_x, shifted_y;
                        if (!dsn_impulse_bracket(y.x, py, span_y, cell_y << shift, hash >> 16u, false, row,
                                                 row_weight, shifted_y) ||
                            !dsn_impulse_bracket(x.x, px, span_x, cell_x << shift, hash & 0xFFFFu, false,
                                                 column, column_weight, shifted_x))
                            continue;
                        /* the impulse's lattice position: the floor of point - offset, where shifted is the
                           offset + reach + 1 texels */
                        uint at_x = dsn_sub64(uvec2(x.x, x.y + reach_x + 1u), shifted_x).y;
                        uint at_y = dsn_sub64(uvec2(y.x, y.y + reach_y + 1u), shifted_y).y;
                        uint m = dsn_mix_pick(grid, key, k, at_x, at_y);
                        dsn_word_base = dsn_mix_at(bases, m);
                        uint width = dsn_word(DSN_WORD_WIDTH), height = dsn_word(DSN_WORD_HEIGHT);
                        uint channels = dsn_word(DSN_WORD_CHANNELS);
                        /* the same offset in the material's own window; texels beyond it read 0 */
                        uint own_row = row - reach_y + dsn_word(DSN_WORD_RADIUS + 1u);
                        uint own_column = column - reach_x + dsn_word(DSN_WORD_RADIUS);
                        ivec4 weights = ivec4(int(65536u - column_weight), int(column_weight),
                                              int(65536u - row_weight), int(row_weight));
                        uvec2 added[3];
                        for (uint c = 0u; c < 3u; c++)
                            added[c] = c < channels ? dsn_bilinear(dsn_corners(own_row, own_column, c, width,
                                                                               height, channels),
                                                                   weights)
                                                    : uvec2(0u);
                        for (uint slot = 0u; slot < 4u; slot++)
                            if (slot == m)
                                for (uint c = 0u; c < 3u; c++)
                                    sums[3u * slot + c] = dsn_add64(sums[3u * slot + c], added[c]);
                        dsn_word_base = bases.x;
                    }
                }
            }
        }
    }
    uvec4 weights = dsn_mix_point_weights(grid, x, y);
    uvec2 totals[3];
    for (uint c = 0u; c < 3u; c++) totals[c] = uvec2(0u);
    for (uint m = 0u; m < grid.count; m++) {
        dsn_word_base = dsn_mix_at(bases, m);
        uint channels = dsn_word(DSN_WORD_CHANNELS);
        uvec2 material_sums[3] = uvec2[3](sums[3u * m], sums[3u * m + 1u], sums[3u * m + 2u]);
        ivec3 value = ivec3(0);
        for (uint c = 0u; c < channels; c++) {
            int v = dsn_normalize_q32_channel_from(c, channels, material_sums,
                                                   dsn_mix_weighted_offset(dsn_offset(c), dsn_mix_at(weights, m)));
            if (c == 0u)
                value.x = v;
            else if (c == 1u)
                value.y = v;
            else
                value.z = v;
        }
        dsn_mix_add_value(value, channels, totals);
    }
    dsn_word_base = 0u;
    return dsn_mix_output(totals);
}

/* ---- Coordinates (the C API's conversions, from the IEEE bits) ---- */

/* sign * mantissa * 2^exponent * 2^32 rounded toward minus infinity, modulo 2^64. */
uvec2 dsn_coordinate_from_parts(bool negative, uvec2 mantissa, int exponent) {
    int shift = exponent + 32;
    uvec2 magnitude = uvec2(0u);
    bool inexact = false;
    if (shift >= 0 && shift < 64) {
        magnitude = dsn_shift_left64(mantissa, uint(shift));
    } else if (shift < 0) {
        uint right = shift > -63 ? uint(-shift) : 63u;
        magnitude = dsn_shift_right64(mantissa, right);
        inexact = dsn_shift_left64(magnitude, right) != mantissa;
    }
    if (!negative) return magnitude;
    return dsn_sub64(dsn_sub64(uvec2(0u), magnitude), uvec2(inexact ? 1u : 0u, 0u));
}

/* A double, given as its IEEE-754 bits uvec2(low word, high word), as a Q32.32 coordinate: exactly
   dsn_coordinate_from_double. */
uvec2 dsn_coordinate_from_double_bits(uvec2 bits) {
    uint exponent = (bits.y >> 20u) & 0x7FFu;
    if (exponent == 0x7FFu) return uvec2(0u);
    uvec2 mantissa = uvec2(bits.x, (bits.y & 0xFFFFFu) | (exponent == 0u ? 0u : 0x100000u));
    int power = (exponent == 0u ? 1 : int(exponent)) - 1075;
    return dsn_coordinate_from_parts((bits.y >> 31u) != 0u, mantissa, power);
}

/* A float, given as its IEEE-754 bits, as a Q32.32 coordinate: exactly dsn_coordinate_from_float. */
uvec2 dsn_coordinate_from_float_bits(uint bits) {
    uint exponent = (bits >> 23u) & 0xFFu;
    if (exponent == 0xFFu) return uvec2(0u);
    uvec2 mantissa = uvec2((bits & 0x7FFFFFu) | (exponent == 0u ? 0u : 0x800000u), 0u);
    int power = (exponent == 0u ? 1 : int(exponent)) - 150;
    return dsn_coordinate_from_parts((bits >> 31u) != 0u, mantissa, power);
}

/* The same from a float value (a GPU may flush subnormal inputs to zero: pass the bits to keep them). */
uvec2 dsn_coordinate_from_float(float value) {
    return dsn_coordinate_from_float_bits(floatBitsToUint(value));
}

/* ---- Surface noise (dsn.h, "Surface noise"): a 3-D point, its frame, no parameterization ---- */

const uint DSN_WORD_SURFACE_OFFSET = 208u; /* offset[3], int64 pairs */
const uint DSN_WORD_SURFACE_CUBES = 214u;  /* the most cubes a walk may visit */
const int DSN_FRAME_ONE = 0x40000000;      /* 1.0 in a frame's Q2.30 */

/* Signed 64-bit helpers (two's complement uvec2). */
uvec2 dsn_from_int(int value) { return uvec2(uint(value), value < 0 ? 0xFFFFFFFFu : 0u); }

/* value / 2^n rounded toward minus infinity, n in 1 .. 31. */
uvec2 dsn_floor_shift64(uvec2 value, uint n) {
    return uvec2((value.x >> n) | (value.y << (32u - n)), uint(int(value.y) >> n));
}

/* The same, for a quotient known to fit an int. */
int dsn_floor_shift_int(uvec2 value, uint n) { return int((value.x >> n) | (value.y << (32u - n))); }

uint dsn_cube_key(uvec3 cube) {
    return dsn_cell_key_in_row(cube.x, dsn_mix32(dsn_row_key(cube.y) + cube.z * 0x9E3779B9u));
}

/* The slab's window W(|w| / H) in Q16 at the distance `across` (Q32.32) from the plane. */
uint dsn_slab_window(uvec2 across, uint shift) {
    uvec2 texels = dsn_shift_right64(dsn_magnitude64(across), 16u); /* Q.16 */
    if (texels.y != 0u) return 0u;
    uvec2 s = dsn_shift_right64(dsn_multiply_wide(texels.x, 89878u), 16u + shift);
    if (s.y != 0u || s.x >= 65536u) return 0u;
    if (s.x <= 32768u) return 65536u;
    uint u = 2u * s.x - 65536u, square = (u * u) >> 16u;
    return 65536u - dsn_shift_right64(dsn_multiply_wide(square, 196608u - 2u * u), 16u).x;
}

/* The cubes (first, count) within `extent` (Q32.32) of a coordinate. */
uvec2 dsn_cube_range(uvec2 position, uvec2 extent, uint shift) {
    uint first = dsn_sub64(position, extent).y >> shift, last = dsn_add64(position, extent).y >> shift;
    return uvec2(first, ((last - first) & (0xFFFFFFFFu >> shift)) + 1u);
}

/* The point, its frame (tangent, bitangent, normal) and the sums of its impulses. */
struct dsn_surface_state {
    uvec2 position[3];
    ivec3 frame[3];
    uvec2 sums[3];
};

/* One axis of an impulse's offset (Q32.32) from the point: false beyond the reach (-(radius + 1),
   radius + 1) texels; else the offset plus radius + 1 texels, whose high word less 1 is the lower texel's
   index and whose bits 16-31 are the upper texel's weight (bilinear_texton.h's bracket). */
bool dsn_surface_bracket(uvec2 offset, uint radius, out uvec2 shifted) {
    shifted = dsn_add64(offset, uvec2(0u, radius + 1u));
    int high = int(shifted.y);
    return high > 0 ? high < int(2u * radius + 2u) : high == 0 && shifted.x != 0u;
}

/* An impulse at offsets (Q32.32) along the tangent (columns) and bitangent (rows) with its window:
   the texton read bilinearly there, weighted, into the sums. */
void dsn_surface_visit(inout dsn_surface_state state, uvec2 along_x, uvec2 along_y, uint window) {
    uvec2 shifted_x, shifted_y;
    bool in_x = dsn_surface_bracket(along_x, dsn_word(DSN_WORD_RADIUS), shifted_x);
    bool in_y = dsn_surface_bracket(along_y, dsn_word(DSN_WORD_RADIUS + 1u), shifted_y);
    uint width = dsn_word(DSN_WORD_WIDTH), height = dsn_word(DSN_WORD_HEIGHT);
    uint channels = dsn_word(DSN_WORD_CHANNELS);
    uint column_weight = (shifted_x.x >> 16u) & 0xFF00u, row_weight = (shifted_y.x >> 16u) & 0xFF00u;
    ivec4 weights = ivec4(int(65536u - column_weight), int(column_weight), int(65536u - row_weight),
                          int(row_weight));
    for (uint c = 0u; c < (in_x && in_y ? channels : 0u); c++) {
        ivec4 corners = dsn_corners(shifted_y.y - 1u, shifted_x.y - 1u, c, width, height, channels);
        uvec2 texton = dsn_multiply64(dsn_bilinear(corners, weights), uvec2(window, 0u));
        state.sums[c] = dsn_add64(state.sums[c], dsn_floor_shift64(texton, 16u));
    }
}

/* The impulses of one cube (surface_walk.h's visit_cube): each offset from the point is the cube
   origin's less the impulse's position in the cube, so the dot products are exact. */
void dsn_surface_cube(inout dsn_surface_state state, uvec3 cube, uint shift) {
    uint key = dsn_cube_key(cube), count = dsn_cell_impulse_count(key);
    uvec2 origin_dot[3];
    for (uint v = 0u; v < 3u; v++) origin_dot[v] = uvec2(0u);
    for (uint i = 0u; i < 3u; i++) {
        uint cube_i = i == 0u ? cube.x : i == 1u ? cube.y : cube.z;
        int origin = dsn_floor_shift_int(dsn_sub64(state.position[i], uvec2(0u, cube_i << shift)), 16u);
        for (uint v = 0u; v < 3u; v++)
            origin_dot[v] = dsn_add64(origin_dot[v], dsn_multiply_signed_wide(origin, state.frame[v][i]));
    }
    for (uint k = 0u; k < count; k++) {
        uvec2 pair = dsn_position_pair(key, k);
        ivec3 inside = ivec3(int((pair.x & 0xFFFFu) << shift), int((pair.x >> 16u) << shift),
                             int((pair.y & 0xFFFFu) << shift));
        uvec2 dots[3];
        for (uint v = 0u; v < 3u; v++) {
            ivec3 f = state.frame[v];
            dots[v] = dsn_sub64(origin_dot[v],
                                dsn_add64(dsn_add64(dsn_multiply_signed_wide(inside.x, f.x),
                                                    dsn_multiply_signed_wide(inside.y, f.y)),
                                          dsn_multiply_signed_wide(inside.z, f.z)));
        }
        uint window = dsn_slab_window(dsn_floor_shift64(dots[2], 14u), shift);
        if (window != 0u)
            dsn_surface_visit(state, dsn_floor_shift64(dots[0], 14u), dsn_floor_shift64(dots[1], 14u),
                              window);
    }
}

/* Q16.16 values of the surface noise at `position` (Q32.32 per axis, as uvec2(low, high)) in the frame
   (tangent, bitangent, normal: Q2.30, DSN_FRAME_ONE is 1.0): dsn_surface_point_fixed's bits, all 0 where
   it fails (a frame component outside [-1, 1], a noise not for the continuous mode, a walk past its
   cost bound). */
ivec3 dsn_surface_point_fixed(uvec2 x, uvec2 y, uvec2 z, ivec3 tangent, ivec3 bitangent, ivec3 normal) {
    if (dsn_word(DSN_WORD_CONTINUOUS) == 0u) return ivec3(0);
    dsn_surface_state state;
    state.position[0] = x;
    state.position[1] = y;
    state.position[2] = z;
    state.frame[0] = tangent;
    state.frame[1] = bitangent;
    state.frame[2] = normal;
    ivec3 one = ivec3(DSN_FRAME_ONE);
    if (any(greaterThan(max(max(tangent, bitangent), normal), one)) ||
        any(lessThan(min(min(tangent, bitangent), normal), -one)))
        return ivec3(0); /* a component outside [-1, 1] */
    for (uint v = 0u; v < 3u; v++) state.sums[v] = uvec2(0u);
    uint shift = dsn_word(DSN_WORD_CELL_SHIFT), limit = dsn_word(DSN_WORD_SURFACE_CUBES);
    /* The walk (surface_walk.h): the reaches in units of 2^-30 texel per frame unit over 2^2. */
    uint reach[3];
    reach[0] = 4u * (dsn_word(DSN_WORD_RADIUS) + 1u);
    reach[1] = 4u * (dsn_word(DSN_WORD_RADIUS + 1u) + 1u);
    reach[2] = 3u << shift;
    uvec2 box_bound[3], first_offset_dot[3], along[9]; /* along[3 v + i] */
    uvec3 first = uvec3(0u), count = uvec3(0u);
    uint cubes = 1u;
    bool affordable = true;
    int first_offset[3];
    for (uint i = 0u; i < 3u; i++) {
        uvec2 extent = uvec2(0u, 1u);
        uint spread = 0u;
        for (uint v = 0u; v < 3u; v++) {
            extent = dsn_add64(extent, dsn_multiply_wide(reach[v], uint(abs(state.frame[v][i]))));
            spread += uint(abs(state.frame[i][v]));
        }
        uvec2 range = dsn_cube_range(state.position[i], extent, shift);
        affordable = affordable && range.y <= limit && cubes <= limit / range.y;
        cubes = affordable ? cubes * range.y : 1u;
        box_bound[i] = dsn_add64(dsn_add64(dsn_shift_left64(uvec2(reach[i], 0u), 44u),
                                           dsn_shift_left64(uvec2(spread, 0u), 15u + shift)),
                                 uvec2(0u, 1u << 14u));
        /* the offset of the first cube's centre (Q.16) */
        uvec2 middle = uvec2(shift == 0u ? 0x80000000u : 0u,
                             (range.x << shift) + (shift == 0u ? 0u : 1u << (shift - 1u)));
        first_offset[i] = dsn_floor_shift_int(dsn_sub64(state.position[i], middle), 16u);
        if (i == 0u) {
            first.x = range.x;
            count.x = range.y;
        } else if (i == 1u) {
            first.y = range.x;
            count.y = range.y;
        } else {
            first.z = range.x;
            count.z = range.y;
        }
    }
    for (uint v = 0u; v < 3u; v++) {
        first_offset_dot[v] = uvec2(0u);
        for (uint i = 0u; i < 3u; i++) {
            along[3u * v + i] = dsn_shift_left64(dsn_from_int(state.frame[v][i]), 16u + shift);
            first_offset_dot[v] = dsn_add64(first_offset_dot[v],
                                            dsn_multiply_signed_wide(first_offset[i], state.frame[v][i]));
        }
    }
    if (!affordable) return ivec3(0); /* the walk's impulses, on average, past DSN_MAX_POINT_IMPULSES */
    uint mask = 0xFFFFFFFFu >> shift;
    uvec2 plane_dot[3] = first_offset_dot;
    for (uint cz = 0u; cz < count.z; cz++) {
        uvec2 row_dot[3] = plane_dot;
        for (uint cy = 0u; cy < count.y; cy++) {
            uvec2 centre_dot[3] = row_dot;
            for (uint cx = 0u; cx < count.x; cx++) {
                if (dsn_at_most64(dsn_magnitude64(centre_dot[0]), box_bound[0]) &&
                    dsn_at_most64(dsn_magnitude64(centre_dot[1]), box_bound[1]) &&
                    dsn_at_most64(dsn_magnitude64(centre_dot[2]), box_bound[2]))
                    dsn_surface_cube(state, (first + uvec3(cx, cy, cz)) & mask, shift);
                for (uint v = 0u; v < 3u; v++) centre_dot[v] = dsn_sub64(centre_dot[v], along[3u * v]);
            }
            for (uint v = 0u; v < 3u; v++) row_dot[v] = dsn_sub64(row_dot[v], along[3u * v + 1u]);
        }
        for (uint v = 0u; v < 3u; v++) plane_dot[v] = dsn_sub64(plane_dot[v], along[3u * v + 2u]);
    }
    return dsn_normalize_q32_from(state.sums, DSN_WORD_SURFACE_OFFSET);
}

/* ---- The surface frame from float vectors (surface_frame.cpp's integers) ---- */

/* floor(sqrt(value)) of a 64-bit value, one result bit per step. */
uint dsn_integer_sqrt64(uvec2 value) {
    uvec2 root = uvec2(0u), bit = uvec2(0u, 0x40000000u);
    while (!dsn_at_most64(bit, value)) bit = dsn_shift_right64(bit, 2u);
    while ((bit.x | bit.y) != 0u) {
        uvec2 trial = dsn_add64(root, bit);
        if (dsn_at_most64(trial, value)) {
            value = dsn_sub64(value, trial);
            root = dsn_add64(dsn_shift_right64(root, 1u), bit);
        } else {
            root = dsn_shift_right64(root, 1u);
        }
        bit = dsn_shift_right64(bit, 2u);
    }
    return root.x;
}

/* a b / 2^30 rounded toward minus infinity (|a|, |b| about 2^30 at most: the quotient fits an int). */
int dsn_multiply_q30(int a, int b) { return dsn_floor_shift_int(dsn_multiply_signed_wide(a, b), 30u); }

/* |a| 2^30 / norm rounded down, with a's sign, for |a| <= norm < 2^32. */
int dsn_ratio_q30(int a, uint norm) {
    uint magnitude = a < 0 ? 0u - uint(a) : uint(a);
    uint quotient = magnitude >= norm ? 1u : 0u, rest = magnitude - quotient * norm;
    for (uint step = 0u; step < 30u; step++) {
        bool carry = (rest >> 31u) != 0u;
        rest <<= 1u;
        quotient <<= 1u;
        if (carry || rest >= norm) {
            rest -= norm;
            quotient |= 1u;
        }
    }
    return a < 0 ? -int(quotient) : int(quotient);
}

/* The direction of a vector (each component at most about 2^31 in magnitude) in Q2.30, clamped to
   [-1, 1]; false for the zero vector. */
bool dsn_unit_vector(ivec3 values, out ivec3 unit) {
    unit = ivec3(0);
    uvec3 size = uvec3(abs(values));
    uint largest = max(size.x, max(size.y, size.z));
    if (largest == 0u) return false;
    uint shift = 0u;
    while ((largest << shift) < 0x20000000u) shift++;
    ivec3 scaled = values * (1 << shift);
    uvec2 length_squared = dsn_add64(dsn_add64(dsn_multiply_signed_wide(scaled.x, scaled.x),
                                               dsn_multiply_signed_wide(scaled.y, scaled.y)),
                                     dsn_multiply_signed_wide(scaled.z, scaled.z));
    uint norm = dsn_integer_sqrt64(length_squared);
    unit = clamp(ivec3(dsn_ratio_q30(scaled.x, norm), dsn_ratio_q30(scaled.y, norm),
                       dsn_ratio_q30(scaled.z, norm)),
                 ivec3(-DSN_FRAME_ONE), ivec3(DSN_FRAME_ONE));
    return true;
}

/* A float from its bits: uvec3(mantissa, exponent, flags), value = mantissa 2^exponent (the exponent's
   two's complement bits), the mantissa shifted to 24 bits (subnormals too) unless it is 0; flags: 1 for
   a negative sign, 2 for a finite value. (No arrays or out parameters: softpipe, Mesa's reference
   rasterizer, loses array elements written through out parameters in branches that differ between
   invocations.) */
uvec3 dsn_float_parts(uint bits) {
    uint biased = (bits >> 23u) & 0xFFu, fraction = bits & 0x7FFFFFu;
    uint mantissa = biased == 0u ? fraction : (fraction | 0x800000u);
    int exponent = (biased == 0u ? 1 : int(biased)) - 150;
    if (mantissa != 0u) { /* a subnormal's mantissa shifted up to 24 bits, in five steps (no loop: */
        uint shift = mantissa < 0x100u ? 16u : 0u; /* llvmpipe's fragment compile stalls on its copies) */
        shift += (mantissa << shift) < 0x10000u ? 8u : 0u;
        shift += (mantissa << shift) < 0x100000u ? 4u : 0u;
        shift += (mantissa << shift) < 0x400000u ? 2u : 0u;
        shift += (mantissa << shift) < 0x800000u ? 1u : 0u;
        mantissa <<= shift;
        exponent -= int(shift);
    }
    return uvec3(mantissa, uint(exponent), (bits >> 31u) | (biased != 0xFFu ? 2u : 0u));
}

/* A float's value as a multiple of 2^(largest - 23): its mantissa shifted right (floored toward zero). */
int dsn_aligned_part(uvec3 parts, int largest) {
    int right = largest - int(parts.y);
    uint value = parts.x == 0u || right >= 32 ? 0u : parts.x >> uint(right);
    return (parts.z & 1u) != 0u ? -int(value) : int(value);
}

/* A float vector's direction (its IEEE bits) in Q2.30: 1, or 0 for the zero vector, -1 for a NaN or
   infinite component. The components are aligned on the largest one's exponent with 24 bits of
   mantissa. */
int dsn_float_direction(uvec3 bits, out ivec3 unit) {
    unit = ivec3(0);
    uvec3 x = dsn_float_parts(bits.x), y = dsn_float_parts(bits.y), z = dsn_float_parts(bits.z);
    if ((x.z & y.z & z.z & 2u) == 0u) return -1;
    int largest = -1000;
    if (x.x != 0u) largest = max(largest, int(x.y));
    if (y.x != 0u) largest = max(largest, int(y.y));
    if (z.x != 0u) largest = max(largest, int(z.y));
    if (largest == -1000) return 0;
    ivec3 aligned = ivec3(dsn_aligned_part(x, largest), dsn_aligned_part(y, largest),
                          dsn_aligned_part(z, largest));
    return dsn_unit_vector(aligned, unit) ? 1 : 0;
}

/* The vector's part orthogonal to the unit normal, and the square of its length. */
uvec2 dsn_remove_normal(ivec3 normal, ivec3 vector, out ivec3 orthogonal) {
    int along_normal = dsn_multiply_q30(vector.x, normal.x) + dsn_multiply_q30(vector.y, normal.y) +
              dsn_multiply_q30(vector.z, normal.z);
    orthogonal = vector - ivec3(dsn_multiply_q30(along_normal, normal.x),
                                dsn_multiply_q30(along_normal, normal.y),
                                dsn_multiply_q30(along_normal, normal.z));
    return dsn_add64(dsn_add64(dsn_multiply_signed_wide(orthogonal.x, orthogonal.x),
                               dsn_multiply_signed_wide(orthogonal.y, orthogonal.y)),
                     dsn_multiply_signed_wide(orthogonal.z, orthogonal.z));
}

/* The frame of a surface point from the IEEE bits of its normal and, when has_tangent, of a tangent
   direction: dsn_surface_frame_from_float's bits (dsn.h), or false (a zero, NaN or infinite normal, a
   NaN or infinite tangent) with a zero frame. */
bool dsn_surface_frame_from_float_bits(uvec3 normal_bits, uvec3 tangent_bits, bool has_tangent,
                                       out ivec3 tangent, out ivec3 bitangent, out ivec3 normal) {
    tangent = ivec3(0);
    bitangent = ivec3(0);
    ivec3 n, t = ivec3(0), given = ivec3(0);
    normal = ivec3(0);
    if (dsn_float_direction(normal_bits, n) != 1) return false;
    int tangent_kind = 0; /* not a call in a ?: operand: softpipe loses its out parameter there */
    if (has_tangent) tangent_kind = dsn_float_direction(tangent_bits, given);
    if (tangent_kind < 0) return false;
    bool made = false;
    if (tangent_kind == 1) {
        ivec3 orthogonal, unit;
        uvec2 length_squared = dsn_remove_normal(n, given, orthogonal);
        if ((length_squared.y >> 4u) != 0u) { /* at least 2^36 */
            dsn_unit_vector(orthogonal, unit);
            dsn_remove_normal(n, unit, orthogonal);
            made = dsn_unit_vector(orthogonal, t);
        }
    }
    if (!made) { /* the x axis made orthogonal to the normal */
        ivec3 direction;
        if (dsn_float_direction(uvec3(0u, normal_bits.y, normal_bits.z), direction) != 1) {
            t = ivec3(0, 0, n.x > 0 ? -DSN_FRAME_ONE : DSN_FRAME_ONE);
        } else {
            int cosine = direction.y, sine = direction.z;
            t = ivec3(dsn_multiply_q30(cosine, n.y) + dsn_multiply_q30(sine, n.z),
                      -dsn_multiply_q30(n.x, cosine), -dsn_multiply_q30(n.x, sine));
        }
    }
    ivec3 b = ivec3(dsn_multiply_q30(n.y, t.z) - dsn_multiply_q30(n.z, t.y),
                    dsn_multiply_q30(n.z, t.x) - dsn_multiply_q30(n.x, t.z),
                    dsn_multiply_q30(n.x, t.y) - dsn_multiply_q30(n.y, t.x));
    ivec3 one = ivec3(DSN_FRAME_ONE);
    tangent = clamp(t, -one, one);
    bitangent = clamp(b, -one, one);
    normal = clamp(n, -one, one);
    return true;
}

/* The surface noise at a float position with a float normal and optional tangent: what
   dsn_surface_point_float gives for the same values as doubles, in Q16.16 (all 0 where it fails). A
   GPU may flush subnormal inputs: pass bits to dsn_surface_frame_from_float_bits to keep them. */
ivec3 dsn_surface_point(vec3 position, vec3 normal, vec3 tangent, bool has_tangent) {
    ivec3 t, b, n;
    if (!dsn_surface_frame_from_float_bits(floatBitsToUint(normal), floatBitsToUint(tangent), has_tangent, t,
                                           b, n))
        return ivec3(0);
    return dsn_surface_point_fixed(dsn_coordinate_from_float(position.x),
                                   dsn_coordinate_from_float(position.y),
                                   dsn_coordinate_from_float(position.z), t, b, n);
}

/* ---- Output conversions (the C API edge), in integer arithmetic ---- */

/* The IEEE-754 bits of value / 65536 rounded to float (to nearest, ties to even): dsn_fixed_to_float. */
uint dsn_fixed_to_float_bits(int value) {
    if (value == 0) return 0u;
    uint sign_bit = value < 0 ? 0x80000000u : 0u;
    uint magnitude = value < 0 ? 0u - uint(value) : uint(value);
    uint top = 31u; /* the highest set bit (findMSB is not in GLSL ES 3.00) */
    while ((magnitude >> top) == 0u) top--;
    uint mantissa;
    if (top > 23u) {
        uint drop = top - 23u, rest = magnitude & ((1u << drop) - 1u), half_unit = 1u << (drop - 1u);
        mantissa = magnitude >> drop;
        if (rest > half_unit || (rest == half_unit && (mantissa & 1u) != 0u)) mantissa++;
        if (mantissa == 0x1000000u) {
            mantissa >>= 1u;
            top++;
        }
    } else {
        mantissa = magnitude << (23u - top);
    }
    /* value / 2^16 = mantissa 2^(top - 23 - 16): biased exponent top - 16 + 127 */
    return sign_bit | ((top + 111u) << 23u) | (mantissa & 0x7FFFFFu);
}

float dsn_fixed_to_float(int value) { return uintBitsToFloat(dsn_fixed_to_float_bits(value)); }

/* Clamped to [0, 1] and rounded to 0 .. 255 (half up): dsn_fixed_to_u8. */
uint dsn_fixed_to_u8(int value) {
    if (value <= 0) return 0u;
    if (value >= 65536) return 255u;
    return (uint(value) * 255u + 32768u) >> 16u;
}

/* The three channels as floats in [0, 1] (grey: the same value in all three), ready for a colour
   attachment: what dsn_lattice_point_u8 gives, divided by 255. */
vec3 dsn_color_of(ivec3 fixed_value, uint channels) {
    uvec3 u8 =
        uvec3(dsn_fixed_to_u8(fixed_value.x), dsn_fixed_to_u8(fixed_value.y), dsn_fixed_to_u8(fixed_value.z));
    if (channels != 3u) u8 = u8.xxx;
    return vec3(u8) / 255.0;
}

vec3 dsn_color(ivec3 fixed_value) { return dsn_color_of(fixed_value, dsn_word(DSN_WORD_CHANNELS)); }

/* The mix's value as colours (dsn_color for a mix). */
vec3 dsn_mix_color(ivec3 fixed_value) {
    return dsn_color_of(fixed_value, dsn_mix_word(DSN_MIX_WORD_CHANNELS));
}
