// texton_noise_baseline.h - the Texton Noise algorithm (B. Galerne, A. Leclaire, L. Moisan, "Texton
// Noise", Computer Graphics Forum 36(8), 2017) on the CPU, written from the paper, as the nearest
// published system to the runtime's continuous mode: the benchmarks time it on the same asset, density
// and points. Float arithmetic throughout, as on the GPU:
//   - the plane is cut into square cells of side r / 1.6 (r the texton's side), so that the texton's
//     r x r square around a point meets at most 3 x 3 cells;
//   - each cell seeds its own generator: a Wang hash of the cell's index, then xorshift32 steps;
//   - a cell's impulse count is Poisson approximated by a Gaussian, floor(m + 1/2 + sqrt(m) N) with N from
//     Box-Muller (two uniforms, a log, a square root, a cosine), m = lambda r^2 / 1.6^2;
//   - each impulse is uniform in its cell (two uniforms) and adds the texton read with bilinear
//     interpolation (the GPU's linear texture filtering), zero outside the texton's square;
//   - the sum, less its mean lambda * sum(texton), is scaled by 1/sqrt(lambda), then the asset's colour
//     transform and mean are applied.
#ifndef DSN_BENCH_TEXTON_NOISE_BASELINE_H
#define DSN_BENCH_TEXTON_NOISE_BASELINE_H

#include <cmath>
#include <cstdint>
#include <vector>

#include "dsn/dsn.h"

namespace texton_noise {

// Thomas Wang's 32-bit integer hash: the cell's seed to the generator's first state.
inline uint32_t wang_hash(uint32_t seed) {
    seed = (seed ^ 61u) ^ (seed >> 16);
    seed *= 9u;
    seed ^= seed >> 4;
    seed *= 0x27D4EB2Du;
    seed ^= seed >> 15;
    return seed;
}

// G. Marsaglia's xorshift32 (a zero state would stay zero: the seeds avoid it).
inline uint32_t xorshift32(uint32_t &state) {
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return state;
}

inline float uniform01(uint32_t &state) { return float(xorshift32(state)) * (1.0f / 4294967295.0f); }

class Baseline {
  public:
    // The asset's texton, density (impacts per pixel over the support, as dsn_config) and normalization.
    Baseline(const dsn_asset &asset, double impacts, uint32_t offset)
        : side_(asset.width), channels_(asset.channels), padded_(asset.width + 2), offset_(offset) {
        // The texton as floats with a border of zeros, so that the bilinear reads need no bounds test.
        texels_.assign(size_t(padded_) * padded_ * 4, 0.0f);
        float sums[3] = {0, 0, 0};
        for (uint32_t row = 0; row < asset.height; row++)
            for (uint32_t column = 0; column < asset.width; column++)
                for (uint32_t c = 0; c < channels_; c++) {
                    const float value = float(dsn_asset_texton_value(&asset, row, column, c)) *
                                        float(double(asset.scale[c]) / 1099511627776.0); // 2^40
                    texels_[(size_t(row + 1) * padded_ + column + 1) * 4 + c] = value;
                    sums[c] += value;
                }
        const double lambda = impacts / double(asset.support_size);
        cell_side_ = float(double(side_) / 1.6);
        cells_per_texel_ = 1.0f / cell_side_;
        cell_mean_ = float(lambda * double(cell_side_) * double(cell_side_));
        cell_deviation_ = std::sqrt(cell_mean_);
        const float inverse_root = float(1.0 / std::sqrt(lambda));
        for (uint32_t c = 0; c < channels_; c++) {
            expected_[c] = float(lambda) * sums[c];
            mean_[c] = float(double(asset.mean[c]) / DSN_Q24_ONE);
            for (uint32_t k = 0; k < 3; k++)
                transform_[c * 3 + k] =
                    channels_ == 3
                        ? float(double(asset.color_transform[c * 3 + k]) / DSN_Q24_ONE) * inverse_root
                        : (k == 0 ? inverse_root : 0.0f);
        }
    }

    // out[channels]: the noise at the point (x, y), in texels.
    void evaluate(float x, float y, float *out) const {
        const float half = 0.5f * float(side_);
        const int first_x = int(std::floor((x - half) * cells_per_texel_)),
                  last_x = int(std::floor((x + half) * cells_per_texel_));
        const int first_y = int(std::floor((y - half) * cells_per_texel_)),
                  last_y = int(std::floor((y + half) * cells_per_texel_));
        float sums[4] = {0, 0, 0, 0};
        for (int cell_y = first_y; cell_y <= last_y; cell_y++)
            for (int cell_x = first_x; cell_x <= last_x; cell_x++) {
                uint32_t state = wang_hash(cell_seed(cell_x, cell_y));
                const uint32_t count = poisson(state);
                for (uint32_t i = 0; i < count; i++) {
                    const float impulse_x = (float(cell_x) + uniform01(state)) * cell_side_;
                    const float impulse_y = (float(cell_y) + uniform01(state)) * cell_side_;
                    // Texton coordinates in [0, r] cover the square; texel i's centre is at i + 1/2.
                    const float u = x - impulse_x + half, v = y - impulse_y + half;
                    if (u >= 0.0f && u <= float(side_) && v >= 0.0f && v <= float(side_))
                        add_bilinear(u + 0.5f, v + 0.5f, sums); // + 1 for the border, - 1/2 for the centres
                }
            }
        for (uint32_t c = 0; c < channels_; c++) {
            float value = mean_[c];
            for (uint32_t k = 0; k < channels_; k++)
                value += transform_[c * 3 + k] * (sums[k] - expected_[k]);
            out[c] = value;
        }
    }

  private:
    // The published seeding: the cell's index on a 1024 x 1024 torus of cells, times 1024, plus an offset.
    uint32_t cell_seed(int cell_x, int cell_y) const {
        const uint32_t period = 1024u;
        uint32_t seed = ((uint32_t(cell_y) % period) * period + uint32_t(cell_x) % period) * period + offset_;
        return seed == 0 ? 1u : seed;
    }

    // floor(m + 1/2 + sqrt(m) N), N standard normal by Box-Muller; negative draws count as none.
    uint32_t poisson(uint32_t &state) const {
        const float u = uniform01(state), v = uniform01(state);
        const float normal = std::sqrt(-2.0f * std::log(u)) * std::cos(6.28318530717958648f * v);
        const float count = std::floor(cell_mean_ + 0.5f + cell_deviation_ * normal);
        return count > 0.0f ? uint32_t(count) : 0u; // u = 0 gives +inf: clamped below
    }

    // The padded texton read bilinearly at (u, v) in padded texel units (texel centres on integers).
    void add_bilinear(float u, float v, float *sums) const {
        const float floor_u = std::floor(u), floor_v = std::floor(v);
        const float wu = u - floor_u, wv = v - floor_v;
        const uint32_t column = uint32_t(floor_u), row = uint32_t(floor_v);
        const float *top = &texels_[(size_t(row) * padded_ + column) * 4],
                    *bottom = top + size_t(padded_) * 4;
        const float w00 = (1 - wu) * (1 - wv), w01 = wu * (1 - wv), w10 = (1 - wu) * wv, w11 = wu * wv;
        for (uint32_t c = 0; c < 4; c++) // four lanes (RGB and a zero): one vector operation each
            sums[c] += w00 * top[c] + w01 * top[4 + c] + w10 * bottom[c] + w11 * bottom[4 + c];
    }

    uint32_t side_, channels_, padded_, offset_;
    float cell_side_ = 0, cells_per_texel_ = 0, cell_mean_ = 0, cell_deviation_ = 0;
    float expected_[3] = {0, 0, 0}, mean_[3] = {0, 0, 0}, transform_[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    std::vector<float> texels_;
};

} // namespace texton_noise

#endif // DSN_BENCH_TEXTON_NOISE_BASELINE_H
