/* runtime/setup/format_bytes.h - the byte-level helpers of the .dsnt format (dsn/format.h): little-endian
   reads and writes, the CRC-32 and the support of a texton. Shared by the loader (runtime/setup/asset.cpp),
   the evaluators that read texton values, and the offline writer (offline/asset_writer.cpp), which
   includes it as "runtime/setup/format_bytes.h" (the build gives offline code -I.). Internal: not installed,
   not part of dsn.h. Values are assembled byte by byte, whatever the host's endianness; no struct is ever
   cast over the bytes. */
#ifndef DSN_FORMAT_BYTES_H
#define DSN_FORMAT_BYTES_H

#include <stddef.h>
#include <stdint.h>

#include "dsn/format.h"

inline uint16_t dsn_read_u16le(const unsigned char *p) {
    return static_cast<uint16_t>(static_cast<unsigned>(p[0]) | (static_cast<unsigned>(p[1]) << 8));
}

inline uint32_t dsn_read_u32le(const unsigned char *p) {
    return static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) |
           (static_cast<uint32_t>(p[2]) << 16) | (static_cast<uint32_t>(p[3]) << 24);
}

/* Two's-complement decodes without implementation-defined conversions. */
inline int32_t dsn_read_i32le(const unsigned char *p) {
    const uint32_t u = dsn_read_u32le(p);
    return (u & 0x80000000u) ? -static_cast<int32_t>(~u) - 1 : static_cast<int32_t>(u);
}

inline int32_t dsn_read_i16le(const unsigned char *p) {
    const int32_t u = dsn_read_u16le(p);
    return (u & 0x8000) ? u - 65536 : u;
}

inline int32_t dsn_read_i8(const unsigned char *p) {
    const int32_t u = p[0];
    return (u & 0x80) ? u - 256 : u;
}

inline void dsn_write_u16le(unsigned char *p, uint16_t v) {
    p[0] = static_cast<unsigned char>(v & 0xFFu);
    p[1] = static_cast<unsigned char>(v >> 8);
}

inline void dsn_write_u32le(unsigned char *p, uint32_t v) {
    p[0] = static_cast<unsigned char>(v & 0xFFu);
    p[1] = static_cast<unsigned char>((v >> 8) & 0xFFu);
    p[2] = static_cast<unsigned char>((v >> 16) & 0xFFu);
    p[3] = static_cast<unsigned char>(v >> 24);
}

inline void dsn_write_i32le(unsigned char *p, int32_t v) { dsn_write_u32le(p, static_cast<uint32_t>(v)); }

/* CRC-32 (zlib/PNG), bitwise with a 16-entry nibble table: small enough for microcontrollers. Pass 0 as
   crc for the first chunk; feed the result back to continue over further chunks. */
inline uint32_t dsn_crc32(uint32_t crc, const void *data, size_t size) {
    static const uint32_t nibble_table[16] = {0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu,
                                              0x76DC4190u, 0x6B6B51F4u, 0x4DB26158u, 0x5005713Cu,
                                              0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
                                              0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu};
    const unsigned char *bytes = static_cast<const unsigned char *>(data);
    crc = ~crc;
    for (size_t i = 0; i < size; i++) {
        crc ^= bytes[i];
        crc = (crc >> 4) ^ nibble_table[crc & 15u];
        crc = (crc >> 4) ^ nibble_table[crc & 15u];
    }
    return ~crc;
}

/* Number of points of the support: the whole window, or the disk dx^2 + dy^2 <= r^2. */
inline uint32_t dsn_support_size(uint32_t shape, uint32_t width, uint32_t height) {
    if (shape != DSN_SHAPE_DISK) return width * height;
    const uint32_t r = (width - 1u) / 2u;
    uint32_t count = 0;
    for (uint32_t dy = 0; dy < width; dy++)
        for (uint32_t dx = 0; dx < width; dx++) {
            const uint32_t ax = dx > r ? dx - r : r - dx, ay = dy > r ? dy - r : r - dy;
            count += (ax * ax + ay * ay <= r * r) ? 1u : 0u;
        }
    return count;
}

/* Whether texton (row, column) lies in the support (always, for a rectangle). */
inline int dsn_in_support(uint32_t shape, uint32_t width, uint32_t row, uint32_t column) {
    const uint32_t r = (width - 1u) / 2u;
    const uint32_t ax = column > r ? column - r : r - column, ay = row > r ? row - r : r - row;
    return shape != DSN_SHAPE_DISK || ax * ax + ay * ay <= r * r;
}

#endif /* DSN_FORMAT_BYTES_H */
