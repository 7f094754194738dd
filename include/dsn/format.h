/* dsn/format.h - the .dsnt asset format: specification, constants and byte helpers.

   This comment block is the format's specification. The writer (offline/asset_writer.cpp) and the
   reader (runtime/asset.cpp) both include this file; neither casts a struct over the bytes.

   ==================================================================================================
   .dsnt version 1.0
   ==================================================================================================

   A .dsnt file holds one synthesis-oriented texton (SOT) and what the runtime needs to turn it into
   discrete spot noise: per-channel scale and mean, a 3x3 colour transform and a default density.

   Conventions
   - Every multi-byte field is little-endian, whatever the host. Readers assemble values byte by byte.
   - u8/u16/u32 are unsigned, i32 is two's complement.
   - Fixed-point "Qa.b" means a signed or unsigned integer whose value is raw / 2^b.

   Layout (offsets in bytes from the start of the file)

     off  size  type    field
     ---  ----  ------  ------------------------------------------------------------------------------
       0     8  u8[8]   magic: 0x89 'D' 'S' 'N' 0x0D 0x0A 0x1A 0x0A  ("\x89DSN\r\n\x1a\n")
       8     2  u16     version_major: 1. Any other major version is rejected.
      10     2  u16     version_minor: 0. Readers of 1.x accept any minor (later minors only append
                        header fields, which older readers skip by header_size).
      12     4  u32     header_size: offset of the texton data. >= 128; exactly 128 in 1.0 files.
      16     4  u32     total_size: length of the whole file, CRC included.
                        Must equal header_size + texton bytes + 4.
      20     4  u32     flags: reserved, must be 0.
      24     1  u8      channels: 1 (grey) or 3 (RGB).
      25     1  u8      bits: 8 or 16, the width of one quantized texton value.
      26     1  u8      shape: 0 = rectangle (the support is the whole width x height window),
                               1 = disk (points with dx^2 + dy^2 <= r^2, r = (width-1)/2; needs
                               width == height). Values outside the support must be 0.
      27     1  u8      interpolation the texton was baked for: 0 = lattice, 1 = bilinear.
      28     2  u16     width: odd, 1..255.  The texton covers dx in [-(width-1)/2, (width-1)/2].
      30     2  u16     height: odd, 1..255. The texton covers dy in [-(height-1)/2, (height-1)/2].
      32     4  u32     default_impacts: impacts per pixel, Q16.16. 0 = none given (runtime uses 30).
                        Otherwise within [DSN_IMPACTS_MIN_Q16, DSN_IMPACTS_MAX_Q16].
      36    12  u32[3]  scale[c]: texton value of channel c is q * scale[c] / 2^40 (q the stored
                        integer). Must be > 0 for c < channels and 0 for the unused channels.
      48    12  i32[3]  mean[c]: per-channel mean, Q8.24. 0 for the unused channels.
      60    36  i32[9]  color_transform: K, row-major (K[row*3+col]), Q8.24. Output channel c is
                        mean[c] + sum_k K[c*3+k] * noise_k. For channels == 1 only K[0] is used and
                        the other eight entries must be 0.
      96     4  u32     bake_iterations: alternating-projection iterations run (metadata).
     100     4  u32     bake_seed: seed of the random-phase start (metadata).
     104     4  u32     bake_rme: relative model error of the stored (quantized) texton, Q8.24
                        (metadata).
     108     2  u16     exemplar_width  (metadata, 0 if unknown).
     110     2  u16     exemplar_height (metadata, 0 if unknown).
     112    16  u8[16]  reserved, must be 0.
     128     n  texton: width * height * channels values, each i8 (bits 8) or i16 (bits 16), row-major
                        from the top row (dy = -(height-1)/2) and, in a row, from dx = -(width-1)/2;
                        channels interleaved. Values lie in [-127, 127] or [-32767, 32767] (the most
                        negative value is reserved so that negation is always defined).
     128+n   4  u32     crc32 of bytes [0, total_size - 4): the CRC-32 of zlib, PNG and Ethernet
                        (reflected polynomial 0xEDB88320, initial value and final xor 0xFFFFFFFF).

   Meaning
   The texton t_c(dx, dy) = q_c(dx, dy) * scale[c] / 2^40 is the spot of a discrete spot noise. With
   lambda = impacts / |S| (|S| the number of support points) the runtime outputs
       out_c(x) = mean[c] + sum_k K[c][k] (F_k(x) - lambda sum_y t_k(y)) / sqrt(lambda),
   F_k(x) = sum_i t_k(x - x_i) over a Poisson point process of intensity lambda.

   Validation order (a reader reports the first failure, each with its own code)
     1. buffer shorter than 8 bytes ................................. DSN_ERR_TRUNCATED
     2. magic differs ............................................... DSN_ERR_BAD_MAGIC
        (when only the CR, LF or SUB bytes differ ...................... DSN_ERR_TEXT_MODE)
     3. buffer shorter than the 1.0 header + CRC (132 bytes) ......... DSN_ERR_TRUNCATED
     4. version_major != 1 ........................................... DSN_ERR_VERSION
     5. header_size < 128 or > total_size - 4 ....................... DSN_ERR_HEADER_SIZE
     6. total_size larger than the buffer ............................ DSN_ERR_TRUNCATED
     7. CRC mismatch ................................................. DSN_ERR_CRC
        (skipped when built with FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION)
     8. flags or reserved bytes non-zero ............................. DSN_ERR_RESERVED
     9. channels, bits, shape, interpolation, width/height ........... DSN_ERR_CHANNELS, DSN_ERR_BITS,
                                                                        DSN_ERR_SHAPE,
                                                                        DSN_ERR_INTERPOLATION,
                                                                        DSN_ERR_DIMENSIONS
    10. total_size != header_size + texton bytes + 4 ................. DSN_ERR_TOTAL_SIZE
    11. scale, default_impacts, unused channel fields ................ DSN_ERR_SCALE, DSN_ERR_IMPACTS,
                                                                        DSN_ERR_RESERVED
    12. grey colour transform with non-zero unused entries ........... DSN_ERR_COLOR_TRANSFORM
    13. a texton value of -128 / -32768, or non-zero outside the disk  DSN_ERR_TEXTON
    All size arithmetic is done so that it cannot overflow (sizes are compared before they are added).
   A buffer longer than total_size is accepted (trailing bytes are ignored).

   ================================================================================================== */
#ifndef DSN_FORMAT_H
#define DSN_FORMAT_H

#include <stddef.h>
#include <stdint.h>

/* The inline helpers below are C; C++ code built with -Wold-style-cast (the runtime) includes them too. */
#if defined(__cplusplus) && defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
#endif

#define DSN_FORMAT_MAGIC "\211DSN\r\n\032\n" /* 0x89 'D' 'S' 'N' CR LF SUB LF */
#define DSN_FORMAT_MAGIC_SIZE 8u
#define DSN_FORMAT_VERSION_MAJOR 1u
#define DSN_FORMAT_VERSION_MINOR 0u
#define DSN_FORMAT_HEADER_SIZE 128u
#define DSN_FORMAT_CRC_SIZE 4u
#define DSN_FORMAT_MAX_SIDE 255u

/* Field offsets. */
#define DSN_OFFSET_VERSION_MAJOR 8u
#define DSN_OFFSET_VERSION_MINOR 10u
#define DSN_OFFSET_HEADER_SIZE 12u
#define DSN_OFFSET_TOTAL_SIZE 16u
#define DSN_OFFSET_FLAGS 20u
#define DSN_OFFSET_CHANNELS 24u
#define DSN_OFFSET_BITS 25u
#define DSN_OFFSET_SHAPE 26u
#define DSN_OFFSET_INTERPOLATION 27u
#define DSN_OFFSET_WIDTH 28u
#define DSN_OFFSET_HEIGHT 30u
#define DSN_OFFSET_DEFAULT_IMPACTS 32u
#define DSN_OFFSET_SCALE 36u
#define DSN_OFFSET_MEAN 48u
#define DSN_OFFSET_COLOR_TRANSFORM 60u
#define DSN_OFFSET_BAKE_ITERATIONS 96u
#define DSN_OFFSET_BAKE_SEED 100u
#define DSN_OFFSET_BAKE_RME 104u
#define DSN_OFFSET_EXEMPLAR_WIDTH 108u
#define DSN_OFFSET_EXEMPLAR_HEIGHT 110u
#define DSN_OFFSET_RESERVED 112u
#define DSN_RESERVED_SIZE 16u

/* Field values. */
#define DSN_SHAPE_RECTANGLE 0u
#define DSN_SHAPE_DISK 1u
#define DSN_INTERPOLATION_LATTICE 0u
#define DSN_INTERPOLATION_BILINEAR 1u

/* Fixed-point scales of the fields. */
#define DSN_SCALE_FRACTION_BITS 40 /* scale[c]: value = raw / 2^40 */
#define DSN_Q24_ONE (1L << 24)     /* mean, color_transform, bake_rme: Q8.24 */
#define DSN_IMPACTS_ONE (1L << 16) /* default_impacts: Q16.16 */
#define DSN_IMPACTS_DEFAULT_Q16 (30u << 16)
#define DSN_IMPACTS_MIN_Q16 (1u << 12)    /* 1/16 impact per pixel */
#define DSN_IMPACTS_MAX_Q16 (1024u << 16) /* 1024 impacts per pixel */

/* Error codes shared by the loader, the runtime and the tools. 0 is success; every failure is distinct
   and negative. dsn_error_message() (dsn.h) gives a static one-line message for each. */
enum dsn_error {
    DSN_OK = 0,
    DSN_ERR_NULL = -1,                 /* a required pointer argument is null */
    DSN_ERR_TRUNCATED = -2,            /* the buffer ends before the asset does */
    DSN_ERR_BAD_MAGIC = -3,            /* not a .dsnt asset */
    DSN_ERR_TEXT_MODE = -4,            /* magic damaged by a text-mode (CR/LF) transfer */
    DSN_ERR_VERSION = -5,              /* unsupported major version */
    DSN_ERR_HEADER_SIZE = -6,          /* header_size out of range */
    DSN_ERR_TOTAL_SIZE = -7,           /* total_size inconsistent with the header fields */
    DSN_ERR_CRC = -8,                  /* checksum mismatch: the file is damaged */
    DSN_ERR_RESERVED = -9,             /* a reserved bit, byte or unused-channel field is not 0 */
    DSN_ERR_CHANNELS = -10,            /* channels is not 1 or 3 */
    DSN_ERR_BITS = -11,                /* bits is not 8 or 16 */
    DSN_ERR_SHAPE = -12,               /* unknown support shape, or a disk that is not square */
    DSN_ERR_INTERPOLATION = -13,       /* unknown interpolation */
    DSN_ERR_DIMENSIONS = -14,          /* texton width/height zero, even or above 255 */
    DSN_ERR_SCALE = -15,               /* a used channel has scale 0 */
    DSN_ERR_IMPACTS = -16,             /* impacts per pixel out of range (asset default or config) */
    DSN_ERR_COLOR_TRANSFORM = -17,     /* grey asset with non-zero unused transform entries */
    DSN_ERR_TEXTON = -18,              /* reserved texton value, or non-zero value outside the support */
    DSN_ERR_PERIOD = -19,              /* reserved: every period 1 .. 2^32 - 1 is valid */
    DSN_ERR_CONTINUOUS_MISMATCH = -20, /* continuous mode on a lattice-baked asset not allowed */
    DSN_ERR_SCRATCH = -21,             /* scratch buffer missing or too small */
    DSN_ERR_TILE_SIZE = -22,           /* tile width or height is 0 or too large */
    DSN_ERR_ARGUMENT = -23             /* another argument out of its documented range */
};

/* ---- Byte helpers (both halves use these; never cast a struct over the bytes) ---- */

static inline uint16_t dsn_read_u16le(const unsigned char *p) {
    return (uint16_t)((unsigned)p[0] | ((unsigned)p[1] << 8));
}

static inline uint32_t dsn_read_u32le(const unsigned char *p) {
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

/* Two's-complement decode without implementation-defined conversions. */
static inline int32_t dsn_read_i32le(const unsigned char *p) {
    uint32_t u = dsn_read_u32le(p);
    return (u & 0x80000000u) ? (int32_t)(-(int32_t)(~u) - 1) : (int32_t)u;
}

static inline int32_t dsn_read_i16le(const unsigned char *p) {
    uint32_t u = dsn_read_u16le(p);
    return (u & 0x8000u) ? (int32_t)u - 65536 : (int32_t)u;
}

static inline int32_t dsn_read_i8(const unsigned char *p) {
    return (p[0] & 0x80u) ? (int32_t)p[0] - 256 : (int32_t)p[0];
}

static inline void dsn_write_u16le(unsigned char *p, uint16_t v) {
    p[0] = (unsigned char)(v & 0xFFu);
    p[1] = (unsigned char)(v >> 8);
}

static inline void dsn_write_u32le(unsigned char *p, uint32_t v) {
    p[0] = (unsigned char)(v & 0xFFu);
    p[1] = (unsigned char)((v >> 8) & 0xFFu);
    p[2] = (unsigned char)((v >> 16) & 0xFFu);
    p[3] = (unsigned char)(v >> 24);
}

static inline void dsn_write_i32le(unsigned char *p, int32_t v) { dsn_write_u32le(p, (uint32_t)v); }

/* CRC-32 (zlib/PNG), bitwise with a 16-entry nibble table: small enough for microcontrollers. Pass 0 as
   crc for the first chunk; feed the result back to continue over further chunks. */
static inline uint32_t dsn_crc32(uint32_t crc, const void *data, size_t size) {
    static const uint32_t nibble_table[16] = {0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu,
                                              0x76DC4190u, 0x6B6B51F4u, 0x4DB26158u, 0x5005713Cu,
                                              0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
                                              0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu};
    const unsigned char *bytes = (const unsigned char *)data;
    size_t i;
    crc = ~crc;
    for (i = 0; i < size; i++) {
        crc ^= bytes[i];
        crc = (crc >> 4) ^ nibble_table[crc & 15u];
        crc = (crc >> 4) ^ nibble_table[crc & 15u];
    }
    return ~crc;
}

/* Number of points of the support: the whole window, or the disk dx^2 + dy^2 <= r^2. */
static inline uint32_t dsn_support_size(uint32_t shape, uint32_t width, uint32_t height) {
    uint32_t r, count = 0, dy, dx;
    if (shape != DSN_SHAPE_DISK) return width * height;
    r = (width - 1u) / 2u;
    for (dy = 0; dy < width; dy++)
        for (dx = 0; dx < width; dx++) {
            uint32_t ax = dx > r ? dx - r : r - dx, ay = dy > r ? dy - r : r - dy;
            count += (ax * ax + ay * ay <= r * r) ? 1u : 0u;
        }
    return count;
}

static inline int dsn_in_support(uint32_t shape, uint32_t width, uint32_t row, uint32_t column) {
    uint32_t r = (width - 1u) / 2u;
    uint32_t ax = column > r ? column - r : r - column, ay = row > r ? row - r : r - row;
    return shape != DSN_SHAPE_DISK || ax * ax + ay * ay <= r * r;
}

#if defined(__cplusplus) && defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#endif /* DSN_FORMAT_H */
