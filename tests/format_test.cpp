// format_test.cpp - the byte helpers of the .dsnt format (runtime/setup/format_bytes.h): CRC-32 and
// little-endian fields.
#include <doctest/doctest.h>

#include <cstring>

#include "runtime/setup/format_bytes.h"

TEST_CASE("crc32 matches the zlib/PNG check value and continues across chunks") {
    const char *check = "123456789";
    CHECK(dsn_crc32(0, check, 9) == 0xCBF43926u);
    CHECK(dsn_crc32(dsn_crc32(0, check, 4), check + 4, 5) == 0xCBF43926u);
    CHECK(dsn_crc32(0, check, 0) == 0u);
}

TEST_CASE("little-endian fields round-trip at their extremes, whatever the host") {
    unsigned char bytes[4];
    const int32_t values[] = {0, 1, -1, 2147483647, -2147483647 - 1, 123456789, -98765};
    for (int32_t value : values) {
        dsn_write_i32le(bytes, value);
        CHECK(dsn_read_i32le(bytes) == value);
    }
    dsn_write_u32le(bytes, 0x11223344u);
    CHECK(bytes[0] == 0x44);
    CHECK(bytes[3] == 0x11);
    dsn_write_u16le(bytes, 0xBEEFu);
    CHECK(dsn_read_u16le(bytes) == 0xBEEFu);
    const unsigned char minus_two[2] = {0xFE, 0xFF};
    CHECK(dsn_read_i16le(minus_two) == -2);
    const unsigned char minus_128 = 0x80;
    CHECK(dsn_read_i8(&minus_128) == -128);
}

TEST_CASE("support size counts the disk exactly") {
    CHECK(dsn_support_size(DSN_SHAPE_RECTANGLE, 31, 29) == 31u * 29u);
    CHECK(dsn_support_size(DSN_SHAPE_DISK, 1, 1) == 1u);
    CHECK(dsn_support_size(DSN_SHAPE_DISK, 3, 3) == 5u); // the centre and its 4 neighbours
    CHECK(dsn_support_size(DSN_SHAPE_DISK, 5, 5) == 13u);
    uint32_t disk_31 = 0;
    for (int y = -15; y <= 15; y++)
        for (int x = -15; x <= 15; x++) disk_31 += (x * x + y * y <= 225) ? 1u : 0u;
    CHECK(dsn_support_size(DSN_SHAPE_DISK, 31, 31) == disk_31);
    CHECK(std::memcmp(DSN_FORMAT_MAGIC,
                      "\x89"
                      "DSN\r\n\x1a\n",
                      DSN_FORMAT_MAGIC_SIZE) == 0);
}
