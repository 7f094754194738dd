// json_output.cpp - json_string: any bytes (a file name) as a valid JSON string (json_output.h).
#include "json_output.h"

#include <cstdio>

namespace dsn {
namespace {

// The length of the valid UTF-8 sequence at text[at] (1 to 4), or 0 when the bytes there are not one
// (a stray continuation byte, an overlong form, a surrogate, beyond U+10FFFF, cut short).
size_t utf8_sequence_length(const std::string &text, size_t at) {
    const auto byte = [&text](size_t i) { return i < text.size() ? (unsigned char)text[i] : 0u; };
    const unsigned lead = byte(at);
    if (lead < 0x80) return 1;
    const size_t length = lead >= 0xC2 && lead <= 0xDF   ? 2
                          : lead >= 0xE0 && lead <= 0xEF ? 3
                          : lead >= 0xF0 && lead <= 0xF4 ? 4
                                                         : 0;
    if (length == 0) return 0;
    for (size_t i = 1; i < length; i++)
        if ((byte(at + i) & 0xC0u) != 0x80u) return 0;
    const unsigned second = byte(at + 1);
    if ((lead == 0xE0 && second < 0xA0) || (lead == 0xED && second > 0x9F) ||
        (lead == 0xF0 && second < 0x90) || (lead == 0xF4 && second > 0x8F))
        return 0;
    return length;
}

// A JSON string; bytes that are not UTF-8 (a file name is any bytes) become U+FFFD, so the report stays
// valid JSON.
} // namespace

std::string json_string(const std::string &text) {
    std::string quoted = "\"";
    for (size_t at = 0; at < text.size();) {
        const size_t length = utf8_sequence_length(text, at);
        if (length == 0) {
            quoted += "\\ufffd";
            at++;
            continue;
        }
        if (length > 1) {
            quoted += text.substr(at, length);
            at += length;
            continue;
        }
        const unsigned char character = (unsigned char)text[at++];
        if (character == '"' || character == '\\') {
            quoted += '\\';
            quoted += char(character);
        } else if (character < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", character);
            quoted += escaped;
        } else {
            quoted += char(character);
        }
    }
    return quoted + "\"";
}

} // namespace dsn
