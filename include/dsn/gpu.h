/* dsn/gpu.h - the configured noise as a buffer of 32-bit words, for the GLSL evaluator dsn/dsn.glsl.

   What it does
     dsn_gpu_pack copies everything the evaluation reads (the configuration dsn_noise_init computed and
     the asset's texton) into an array of uint32_t that a shader reads through a function it defines,
     `uint dsn_word(uint index)`: from a shader storage buffer, a uniform buffer or an R32UI texture.
     dsn/dsn.glsl then evaluates the lattice and the continuous mode per point with exactly the bits of
     dsn_lattice_point_fixed and dsn_continuous_point_fixed, and the surface noise per point with those of
     dsn_surface_point_fixed (integer arithmetic only, in 32-bit words).
     dsn_gpu_mix_pack does the same for a mix of materials and its control (below), for dsn.glsl's
     dsn_mix_lattice_point_fixed and dsn_mix_continuous_point_fixed.

   How to call it
       uint32_t words[...];                                  // dsn_gpu_word_count(&noise) of them
       size_t count = dsn_gpu_word_count(&noise);            // 0: not a configured noise
       int err = dsn_gpu_pack(&noise, words, count);         // DSN_OK or an error (below)
       glBufferData(GL_SHADER_STORAGE_BUFFER, count * 4, words, GL_STATIC_DRAW);   // for example
   Upload the words as they are: the values are host integers (a GL buffer holds them in the host's byte
   order, which is what the shader reads).

   Layout, version 4 (DSN_GPU_LAYOUT_VERSION; version 3 had word 47 zero and no quads; version 2 had no
   words 208 .. 215, its texton started at word 208; version 1 also had words 42 .. 46 zero and no
   lattice texton).
   Word i of the buffer:
       0            DSN_GPU_MAGIC ("DSNG" as a little-endian word)
       1            DSN_GPU_LAYOUT_VERSION
       2            total number of words (dsn_gpu_word_count)
       3            channels (1 or 3)
       4            bits of the asset's texton values (8 or 16; informative: the values below are whole)
       5, 6         texton width, height (odd)
       7, 8         radius along x, y: (width - 1) / 2, (height - 1) / 2
       9            cell_shift: cells are 2^cell_shift lattice points wide
       10, 11       period along x, y (0: not periodic)
       12, 13       the seed's column and row hashes (mixed into every cell key)
       14           gain_shift: fraction bits of gain and offset
       15           poisson_parts: a cell's count is the sum of this many draws
       16           poisson_size: entries used in the Poisson table
       17           1 when the continuous mode may be used with this noise (dsn_continuous_check), else 0
       18 .. 35     gain[9], row-major (output channel c, input channel k at 3 c + k): int64 as two words,
                    low word first (two's complement)
       36 .. 41     offset[3]: int64 as two words, low word first
       42, 43       the lattice evaluators' texton width, height (odd): the asset's lattice texton
                    (format 1.3) where it has one, else the texton's (words 5, 6)
       44, 45       its radius along x, y
       46           the word where its values start: 216 + width * height * channels after the texton, or
                    216 (the texton itself)
       47           the word where the texton's quads start (below)
       48 .. 143    the Poisson table: 96 inverse-CDF thresholds (entries from poisson_size on are
                    0xFFFFFFFF)
       144 .. 207   the Poisson guide: the first candidate count for each top-6-bit bucket of a uniform
       208 .. 213   the surface noise's offset[3] (dsn.h, "Surface noise": the offset less 3/32 of the
                    expected sum): int64 as two words, low word first
       214          the most cubes one surface point's walk may visit: a walk over more fails with
                    DSN_ERR_COST (its impulses, on average, would pass DSN_MAX_POINT_IMPULSES)
       215          0 (reserved); words 208 .. 215 are all 0 in a runtime built without DSN_SURFACE
       216 ..       the texton: width * height * channels values, row-major from the top row, channels
                    interleaved, each sign-extended to a whole word (two's complement int32); then, where
                    the asset has one, the lattice texton in the same form; then the texton's
                    quads: (height + 1) * (width + 1) * channels pairs of words, quad (r, q) of channel c
                    at word (word 47) + 2 ((r (width + 1) + q) channels + c): the texels (r - 1, q - 1) and
                    (r - 1, q) of channel c in the low and high 16 bits of its first word, (r, q - 1) and
                    (r, q) in its second (two's complement; 0 outside the texton): a bilinear read's
                    2 x 2 texels in two words, where the values take four
   A later layout changes DSN_GPU_LAYOUT_VERSION, and dsn.glsl checks nothing at run time: use the
   dsn.glsl installed with this header. The words are a copy: repack after dsn_noise_init. */
#ifndef DSN_GPU_H
#define DSN_GPU_H

#include <stddef.h>
#include <stdint.h>

#include "dsn/dsn.h"

#ifdef __cplusplus
extern "C" {
#endif

#define DSN_GPU_MAGIC 0x474E5344u /* 'D' 'S' 'N' 'G' in the low to high bytes */
#define DSN_GPU_LAYOUT_VERSION 4u
#define DSN_GPU_HEADER_WORDS 216u /* the texton starts at this word */
#define DSN_GPU_MAX_WORDS (DSN_GPU_HEADER_WORDS + 2u * 255u * 255u * 3u + 2u * 256u * 256u * 3u)

/* The number of words dsn_gpu_pack writes for `noise`: DSN_GPU_HEADER_WORDS + the textons' values + the
   texton's quads, at most DSN_GPU_MAX_WORDS; 0 for a null noise or one that dsn_noise_init did not
   fill. */
size_t dsn_gpu_word_count(const dsn_noise *noise);

/* Writes the dsn_gpu_word_count(noise) words of the layout above to `words`. Returns DSN_OK;
   DSN_ERR_NULL for a null `noise` or `words`; DSN_ERR_ARGUMENT for a noise that dsn_noise_init did not
   fill, or a `capacity` (in words) below the count; DSN_ERR_UNSUPPORTED for a noise with a histogram
   mapping (format 1.2: dsn.glsl does not apply it; a noise configured with DSN_FLAG_NO_HISTOGRAM packs,
   and the shader then gives its Gaussian-space values). On an error nothing is written. Freestanding like the
   rest of the runtime: no allocation, integer arithmetic only. */
int dsn_gpu_pack(const dsn_noise *noise, uint32_t *words, size_t capacity);

#if DSN_MIXING
/* ---- Mixing (dsn.h, "Mixing") ----
   dsn_gpu_mix_pack copies a configured mix and a control into words for dsn.glsl's dsn_mix_* functions:
   a header, each material as the layout above (each a whole pack, its words relative to its own start),
   then the control. Word i of the buffer:
       0            DSN_GPU_MIX_MAGIC ("DSNM" as a little-endian word)
       1            DSN_GPU_LAYOUT_VERSION
       2            total number of words (dsn_gpu_mix_word_count)
       3            materials (1 .. DSN_MIX_MAX_MATERIALS)
       4            channels of the mix (1 or 3)
       5, 6         the continuous walk's reach along x, y (the largest texton radius)
       7, 8         the lattice walk's reach along x, y (the largest lattice texton radius)
       9 .. 12      the word where material m's pack starts (0 past the materials)
       13           the word where the control starts (C)
       14, 15       0 (reserved)
       16 ..        the materials' packs, one after the other (material 0's holds the impulse process)
       C .. C + 5   the control's width, height, spacing_shift, origin_x, origin_y (two's complement),
                    flags
       C + 6 ..     its weights: byte i of dsn_mix_control.weights in bits 8 (i % 4) .. 8 (i % 4) + 7 of
                    word C + 6 + i / 4 (the last word's unused bytes 0)
   The control is last, so a renderer that changes only the weights (not the grid's size) rewrites
   words C .. of the buffer. */
#define DSN_GPU_MIX_MAGIC 0x4D4E5344u /* 'D' 'S' 'N' 'M' */
#define DSN_GPU_MIX_HEADER_WORDS 16u
#define DSN_GPU_MIX_CONTROL_WORDS 6u /* before the weights */

/* The number of words dsn_gpu_mix_pack writes for `mix` and `control`; 0 for a null or unconfigured mix,
   or a control that the mix functions refuse. */
size_t dsn_gpu_mix_word_count(const dsn_mix *mix, const dsn_mix_control *control);

/* Writes the dsn_gpu_mix_word_count(mix, control) words of the layout above to `words`. Returns DSN_OK;
   DSN_ERR_NULL for a null mix, control, weights or words, or a mix not configured; DSN_ERR_ARGUMENT for a
   control out of its ranges (dsn_mix_control) or a `capacity` (in words) below the count. On an error
   nothing is written. */
int dsn_gpu_mix_pack(const dsn_mix *mix, const dsn_mix_control *control, uint32_t *words, size_t capacity);
#endif

#ifdef __cplusplus
}
#endif

#endif /* DSN_GPU_H */
