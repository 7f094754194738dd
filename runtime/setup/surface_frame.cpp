/* runtime/setup/surface_frame.cpp - a surface point's frame (tangent, bitangent, normal in Q2.30) from float
   vectors, with integer operations only: each vector read from its bits and normalized with an integer
   square root, the tangent made orthogonal to the normal, or, without one, the x axis made orthogonal to
   it (dsn.h, "Surface noise"). */
#include "core/float_bits.h"
#include "dsn/dsn.h"
#include "setup/wide_arithmetic.h"

#if DSN_SURFACE

namespace {

const int64_t frame_one = DSN_FRAME_ONE;

/* A float as sign, mantissa and exponent (value = mantissa 2^exponent), the mantissa shifted to 24 bits
   (subnormals too) unless it is 0; false for NaN and infinities. */
bool float_parts(float value, bool *negative, uint32_t *mantissa, int32_t *exponent) {
    const uint32_t bits = bits_of<uint32_t>(value);
    const uint32_t biased = (bits >> 23) & 0xFFu, fraction = bits & 0x7FFFFFu;
    if (biased == 0xFFu) return false;
    *negative = (bits >> 31) != 0;
    *mantissa = biased == 0 ? fraction : (fraction | (1u << 23));
    *exponent = (biased == 0 ? 1 : static_cast<int32_t>(biased)) - 150;
    for (; *mantissa != 0 && *mantissa < (1u << 23); *mantissa <<= 1) --*exponent;
    return true;
}

/* a * b / 2^30 rounded toward minus infinity, for |a|, |b| <= 2^31 (the product is below 2^62). */
int64_t multiply_q30(int64_t a, int64_t b) {
    const uint64_t bias = static_cast<uint64_t>(1) << 62;
    return static_cast<int64_t>((static_cast<uint64_t>(a * b) + bias) >> 30) -
           (static_cast<int64_t>(1) << 32);
}

/* |a| / |b| 2^30 rounded down, with a's sign, for |a| <= |b| (b non-zero): no compiler division helper. */
int64_t ratio_q30(int64_t a, uint64_t b) {
    const uint64_t magnitude = a < 0 ? 0u - static_cast<uint64_t>(a) : static_cast<uint64_t>(a);
    const int64_t quotient = static_cast<int64_t>(dsn_divide(magnitude << 30, b));
    return a < 0 ? -quotient : quotient;
}

/* The direction of three values below 2^31 in magnitude, in Q2.30: the values shifted up until the
   largest has 30 bits (so the integer square root of the squared length keeps 30 significant bits), each
   divided by the length, clamped to [-1, 1]. False for the zero vector. */
bool unit_vector(const int64_t *values, int64_t *unit) {
    uint64_t largest = 0;
    for (int i = 0; i < 3; i++) {
        const uint64_t size =
            values[i] < 0 ? 0u - static_cast<uint64_t>(values[i]) : static_cast<uint64_t>(values[i]);
        largest = size > largest ? size : largest;
    }
    if (largest == 0) return false;
    uint32_t shift = 0;
    while ((largest << shift) < (static_cast<uint64_t>(1) << 29)) shift++;
    int64_t scaled[3];
    uint64_t length_squared = 0;
    for (int i = 0; i < 3; i++) {
        scaled[i] = values[i] * (static_cast<int64_t>(1) << shift);
        length_squared += static_cast<uint64_t>(scaled[i] * scaled[i]); /* below 3 2^62 */
    }
    const uint64_t length = dsn_integer_sqrt(length_squared);
    for (int i = 0; i < 3; i++) {
        const int64_t component = ratio_q30(scaled[i], length);
        unit[i] = component > frame_one ? frame_one : component < -frame_one ? -frame_one : component;
    }
    return true;
}

/* A float vector's direction in Q2.30: the components aligned on the largest one's exponent with 24
   bits of mantissa (the smaller ones floored toward zero), then unit_vector. 0 for the zero vector,
   -1 for a NaN or infinite component. */
int float_direction(const float *vector, int64_t *unit) {
    bool negative[3];
    uint32_t mantissa[3];
    int32_t exponent[3], largest = -1000;
    for (int i = 0; i < 3; i++) {
        if (!float_parts(vector[i], &negative[i], &mantissa[i], &exponent[i])) return -1;
        if (mantissa[i] != 0 && exponent[i] > largest) largest = exponent[i];
    }
    if (largest == -1000) return 0;
    int64_t aligned[3];
    for (int i = 0; i < 3; i++) {
        /* mantissa 2^exponent as a multiple of 2^(largest - 23) fits 24 bits; far smaller values give 0. */
        const int32_t right = largest - exponent[i];
        const uint32_t value = mantissa[i] == 0 || right >= 32 ? 0u : mantissa[i] >> right;
        aligned[i] = negative[i] ? -static_cast<int64_t>(value) : static_cast<int64_t>(value);
    }
    return unit_vector(aligned, unit) ? 1 : 0;
}

/* The tangent from the normal alone (dsn.h): the x axis made orthogonal to the normal. With (c, s) the
   direction of (n_y, n_z) and rho = c n_y + s n_z its length, that is (rho, -n_x c, -n_x s), well
   conditioned next to the axis, where the frame turns as fast as (c, s) does: so (c, s) comes from the
   float normal's n_y and n_z at their own precision, which the normal's 30 bits would not hold there. */
void tangent_from_normal(const float *vector, const int64_t *normal, int64_t *tangent) {
    const float across[3] = {0, vector[1], vector[2]};
    int64_t direction[3];
    if (float_direction(across, direction) != 1) { /* the normal is the x axis: (0, 0, -1) or (0, 0, 1) */
        tangent[0] = tangent[1] = 0;
        tangent[2] = normal[0] > 0 ? -frame_one : frame_one;
        return;
    }
    const int64_t cosine = direction[1], sine = direction[2];
    tangent[0] = multiply_q30(cosine, normal[1]) + multiply_q30(sine, normal[2]);
    tangent[1] = -multiply_q30(normal[0], cosine);
    tangent[2] = -multiply_q30(normal[0], sine);
}

/* The vector's part orthogonal to the unit normal, and the square of its length. */
uint64_t remove_normal(const int64_t *normal, const int64_t *vector, int64_t *orthogonal) {
    const int64_t dot = multiply_q30(vector[0], normal[0]) + multiply_q30(vector[1], normal[1]) +
                        multiply_q30(vector[2], normal[2]);
    uint64_t length_squared = 0;
    for (int i = 0; i < 3; i++) {
        orthogonal[i] = vector[i] - multiply_q30(dot, normal[i]);
        length_squared += static_cast<uint64_t>(orthogonal[i] * orthogonal[i]);
    }
    return length_squared;
}

/* The tangent's part orthogonal to the normal, normalized, then orthogonalized and normalized once more
   (the first pass leaves an error of 2^-30 over the part's length); false when the part is under 2^-12 of
   the tangent's length (a tangent along the normal). */
bool orthogonal_tangent(const int64_t *normal, const int64_t *tangent, int64_t *out) {
    int64_t orthogonal[3], first[3];
    if (remove_normal(normal, tangent, orthogonal) < static_cast<uint64_t>(1) << 36) return false;
    unit_vector(orthogonal, first);
    remove_normal(normal, first, orthogonal);
    return unit_vector(orthogonal, out);
}

/* A vector's components, clamped to [-1, 1] (the floors of a product of unit values may leave one past it).
 */
void store(const int64_t *values, int32_t *out) {
    for (int i = 0; i < 3; i++)
        out[i] = static_cast<int32_t>(values[i] > frame_one    ? frame_one
                                      : values[i] < -frame_one ? -frame_one
                                                               : values[i]);
}

} // namespace

extern "C" int dsn_surface_frame_from_float(const float *normal, const float *tangent,
                                            dsn_surface_frame *frame) {
    if (frame == 0) return DSN_ERR_NULL;
    const dsn_surface_frame zero = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    *frame = zero;
    if (normal == 0) return DSN_ERR_NULL;
    int64_t n[3], t[3], given[3];
    if (float_direction(normal, n) != 1) return DSN_ERR_ARGUMENT;
    const int tangent_kind = tangent == 0 ? 0 : float_direction(tangent, given);
    if (tangent_kind < 0) return DSN_ERR_ARGUMENT;
    if (tangent_kind == 0 || !orthogonal_tangent(n, given, t)) tangent_from_normal(normal, n, t);
    const int64_t b[3] = {multiply_q30(n[1], t[2]) - multiply_q30(n[2], t[1]),
                          multiply_q30(n[2], t[0]) - multiply_q30(n[0], t[2]),
                          multiply_q30(n[0], t[1]) - multiply_q30(n[1], t[0])};
    store(t, frame->tangent);
    store(b, frame->bitangent);
    store(n, frame->normal);
    return DSN_OK;
}

#endif /* DSN_SURFACE */
