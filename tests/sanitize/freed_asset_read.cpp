// freed_asset_read.cpp - a continuous point read through asset bytes freed after init (a broken contract:
// the bytes must outlive the noise). Not a test of the runtime but of the sanitizer run: `make sanitize`
// builds it against the runtime without its x86 kernel copies and requires AddressSanitizer to report a
// heap-use-after-free. The AVX2 copy reads the texton with vector gathers, whose loads ASan does not see,
// so a build that runs them can miss such a read; this program exits 0 only when nothing stopped it.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "dsn/asset_writer.h"
#include "dsn/dsn.h"

int main() {
    // The usual kind of asset: a 31 x 31 8-bit RGB texton at 30 impacts, read bilinearly.
    dsn::AssetFields fields;
    fields.channels = 3;
    fields.interpolation = DSN_INTERPOLATION_BILINEAR;
    fields.width = fields.height = 31;
    fields.default_impacts_q16 = DSN_IMPACTS_DEFAULT_Q16;
    for (int c = 0; c < 3; c++) fields.scale[c] = 1u << 30;
    fields.texton.resize(31 * 31 * 3);
    for (size_t i = 0; i < fields.texton.size(); i++) fields.texton[i] = int32_t(i * 37 % 255) - 127;
    const std::vector<unsigned char> encoded = dsn::encode_asset(fields);
    unsigned char *bytes = static_cast<unsigned char *>(std::malloc(encoded.size()));
    if (bytes == nullptr) return 2;
    std::memcpy(bytes, encoded.data(), encoded.size());
    dsn_noise noise;
    if (dsn_noise_load(&noise, bytes, encoded.size(), 7) != DSN_OK) return 2;
    std::free(bytes); // the contract broken: the noise still points into these bytes
    int32_t sum = 0, value[DSN_MAX_CHANNELS];
    for (int64_t i = 0; i < 64; i++) {
        dsn_continuous_point_fixed(&noise, i * 0x5A5A5A5A5LL, i * 0x3C3C3C3C3LL, value);
        sum += value[0];
    }
    std::printf("freed_asset_read: 64 continuous points read freed bytes unreported (sum %d)\n", int(sum));
    return 0;
}
