// asset_file.cpp - reads and validates the tools' asset files, with one-line reasons (asset_file.h).
#include "asset_file.h"

#include "offline/file_input.h"

#include <cstring>
#include <stdexcept>

namespace dsn {
namespace {

size_t section_bytes(size_t payload) {
    return DSN_SECTION_HEADER_SIZE +
           (payload + DSN_SECTION_ALIGNMENT - 1) / DSN_SECTION_ALIGNMENT * DSN_SECTION_ALIGNMENT;
}

// An image's first bytes, as stb_image (dsn-bake's reader) tells the formats apart.
bool looks_like_image(const std::vector<unsigned char> &bytes) {
    auto starts = [&bytes](const char *signature, size_t size) {
        return bytes.size() >= size && std::memcmp(bytes.data(), signature, size) == 0;
    };
    const bool pnm = bytes.size() >= 3 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '7' &&
                     (bytes[2] == '\n' || bytes[2] == ' ' || bytes[2] == '\r' || bytes[2] == '\t');
    return starts("\x89PNG\r\n\x1a\n", 8) || starts("\xff\xd8\xff", 3) || starts("GIF8", 4) ||
           starts("BM", 2) || starts("8BPS", 4) || starts("#?RADIANCE", 10) || starts("#?RGBE", 6) || pnm;
}

// "folder/wood.png" -> "folder/wood.dsnt".
std::string asset_name_for(const std::string &image_path) {
    const size_t slash = image_path.find_last_of('/');
    const size_t dot = image_path.find_last_of('.');
    const bool has_extension = dot != std::string::npos && (slash == std::string::npos || dot > slash + 1);
    return (has_extension ? image_path.substr(0, dot) : image_path) + ".dsnt";
}

} // namespace

size_t largest_asset_bytes() {
    const size_t texton = size_t(DSN_FORMAT_MAX_SIDE) * DSN_FORMAT_MAX_SIDE * DSN_MAX_CHANNELS * 2;
    const size_t pyramid =
        section_bytes(DSN_PYRAMID_HEADER_SIZE + DSN_PYRAMID_MAX_LEVELS * (DSN_PYRAMID_RECORD_SIZE + texton));
    const size_t histogram =
        section_bytes(DSN_HISTOGRAM_HEADER_SIZE +
                      size_t(2) * DSN_HISTOGRAM_MAX_LEVELS * DSN_HISTOGRAM_MAX_ENTRIES * DSN_MAX_CHANNELS);
    const size_t lattice_texton = section_bytes(DSN_LATTICE_TEXTON_HEADER_SIZE + texton);
    return DSN_FORMAT_HEADER_SIZE + pyramid + histogram + lattice_texton + texton + DSN_FORMAT_CRC_SIZE;
}

std::vector<unsigned char> read_asset_file(const std::string &path) {
    return read_input_file(path, largest_asset_bytes(), "a dsn asset");
}

std::string asset_problem(const std::string &path, const std::vector<unsigned char> &bytes, int error) {
    if (looks_like_image(bytes))
        return path + " is an image, not a dsn asset: bake it first: dsn-bake " + path + " -o " +
               asset_name_for(path);
    return path + " is not a dsn asset: " + dsn_error_message(error);
}

std::vector<unsigned char> load_asset_file(const std::string &path, dsn_asset &asset) {
    std::vector<unsigned char> bytes = read_asset_file(path);
    const int error = dsn_asset_load(&asset, bytes.data(), bytes.size());
    if (error != DSN_OK) throw std::runtime_error(asset_problem(path, bytes, error));
    return bytes;
}

} // namespace dsn
