// png_output.h - encode_png: 8-bit pixels -> the bytes of a PNG file (stb_image_write); encode_png_16:
// 16-bit pixels -> the bytes of a PNG file. For the tools, which then write them with
// write_file_atomically (file_output.h). Part of libdsn_tools.a.
#ifndef DSN_TOOLS_PNG_OUTPUT_H
#define DSN_TOOLS_PNG_OUTPUT_H

#include <cstdint>
#include <vector>

namespace dsn {

// The bytes of a PNG file of 8-bit pixels (rows from the top, channels interleaved, 1 to 4 channels).
// Throws std::invalid_argument for an impossible size, std::runtime_error if encoding fails.
std::vector<unsigned char> encode_png(int width, int height, int channels, const unsigned char *pixels);

// The same for 16-bit samples (stb_image_write writes only 8 bits). The image data is stored, not
// compressed: the tools write noise, which deflate hardly shrinks. Same errors as encode_png.
std::vector<unsigned char> encode_png_16(int width, int height, int channels, const uint16_t *samples);

} // namespace dsn

#endif // DSN_TOOLS_PNG_OUTPUT_H
