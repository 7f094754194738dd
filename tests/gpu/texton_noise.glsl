/* texton_noise.glsl - the Texton Noise algorithm of B. Galerne, A. Leclaire and L. Moisan, "Texton
   Noise", Computer Graphics Forum 36(8), 2017, as the anchor that dsn-gpu-bench times dsn.glsl against.
   Written from the paper exactly as tests/bench/texton_noise_baseline.h writes it on the CPU (the same
   cells, generator, counts and normalization, in float), but with the texton read by the GPU's own
   bilinear filtering, as the paper's shader does:
     - square cells of side r / 1.6 (r the texton's side), so that the texton's r x r square around a
       point meets at most 3 x 3 cells;
     - each cell seeds its own generator: a Wang hash of the cell's index, then xorshift32 steps;
     - a cell's impulse count is Poisson approximated by a Gaussian, floor(m + 1/2 + sqrt(m) N), N by
       Box-Muller, m = lambda (r / 1.6)^2;
     - each impulse is uniform in its cell and adds the texton read through a sampler2D with GL_LINEAR
       filtering from an RGBA float texture whose one-texel border is zero (no bounds test per tap);
     - the sum, less its mean, is scaled by 1/sqrt(lambda) (folded into the transform), then the colour
       transform and the mean are applied.
   The including shader calls texton_noise_evaluate(point), point in texels. */

uniform highp sampler2D texton_noise_texton; /* (r + 2) x (r + 2), the texton in the middle */
uniform float texton_noise_side;             /* r, in texels */
uniform float texton_noise_cell_side;        /* r / 1.6 */
uniform float texton_noise_cells_per_texel;  /* its inverse, rounded as the CPU baseline rounds it */
uniform float texton_noise_cell_mean;        /* m: the mean count of impulses per cell */
uniform float texton_noise_cell_deviation;   /* sqrt(m) */
uniform uint texton_noise_seed_offset;
uniform vec3 texton_noise_expected; /* lambda times the texton's sum: the mean of the sums */
uniform vec3 texton_noise_mean;
uniform mat3 texton_noise_transform; /* the colour transform over sqrt(lambda) */

/* Thomas Wang's 32-bit integer hash: the cell's seed to the generator's first state. */
uint texton_noise_wang_hash(uint seed) {
    seed = (seed ^ 61u) ^ (seed >> 16u);
    seed *= 9u;
    seed ^= seed >> 4u;
    seed *= 0x27D4EB2Du;
    seed ^= seed >> 15u;
    return seed;
}

/* G. Marsaglia's xorshift32: never zero from a non-zero state. */
uint texton_noise_xorshift32(inout uint state) {
    state ^= state << 13u;
    state ^= state >> 17u;
    state ^= state << 5u;
    return state;
}

float texton_noise_uniform01(inout uint state) {
    return float(texton_noise_xorshift32(state)) * (1.0 / 4294967295.0);
}

/* The published seeding: the cell's index on a 1024 x 1024 torus of cells, times 1024, plus an offset;
   zero would leave xorshift32 stuck at zero. */
uint texton_noise_cell_seed(int cell_x, int cell_y) {
    const uint period = 1024u;
    uint seed = ((uint(cell_y) % period) * period + uint(cell_x) % period) * period + texton_noise_seed_offset;
    return seed == 0u ? 1u : seed;
}

/* floor(m + 1/2 + sqrt(m) N) with N standard normal by Box-Muller; negative draws count as none. */
uint texton_noise_poisson(inout uint state) {
    float u = texton_noise_uniform01(state), v = texton_noise_uniform01(state);
    float normal = sqrt(-2.0 * log(u)) * cos(6.28318530717958648 * v);
    float count = floor(texton_noise_cell_mean + 0.5 + texton_noise_cell_deviation * normal);
    return count > 0.0 ? uint(count) : 0u;
}

/* The noise at `point` (texels): the colour, in the asset's units (1.0 the exemplar's white). */
vec3 texton_noise_evaluate(vec2 point) {
    float half_side = 0.5 * texton_noise_side;
    ivec2 first = ivec2(floor((point - half_side) * texton_noise_cells_per_texel));
    ivec2 last = ivec2(floor((point + half_side) * texton_noise_cells_per_texel));
    /* Texture coordinates: texton coordinate u in [0, r] is padded texel u + 1/2 + 1/2 (the border, less
       half a texel to the centres), over the padded side r + 2. */
    float padded_texels = 1.0 / (texton_noise_side + 2.0);
    vec4 sums = vec4(0.0);
    for (int cell_y = first.y; cell_y <= last.y; cell_y++) {
        for (int cell_x = first.x; cell_x <= last.x; cell_x++) {
            uint state = texton_noise_wang_hash(texton_noise_cell_seed(cell_x, cell_y));
            uint count = texton_noise_poisson(state);
            for (uint i = 0u; i < count; i++) {
                float impulse_x = (float(cell_x) + texton_noise_uniform01(state)) * texton_noise_cell_side;
                float impulse_y = (float(cell_y) + texton_noise_uniform01(state)) * texton_noise_cell_side;
                vec2 uv = point - vec2(impulse_x, impulse_y) + half_side;
                if (uv.x >= 0.0 && uv.x <= texton_noise_side && uv.y >= 0.0 && uv.y <= texton_noise_side)
                    sums += textureLod(texton_noise_texton, (uv + 1.0) * padded_texels, 0.0);
            }
        }
    }
    return texton_noise_mean + texton_noise_transform * (sums.rgb - texton_noise_expected);
}
