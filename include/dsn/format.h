/* dsn/format.h - the .dsnt asset format: its specification, its constants and the error codes.

   This comment block is the format's specification. The writer (offline/asset_writer.cpp) and the
   reader (runtime/setup/asset.cpp) both follow it and read or write every field byte by byte (their shared
   helpers are internal, runtime/setup/format_bytes.h); neither casts a struct over the bytes. Version 1.0
   comes first; version 1.1 (below it) adds sections after the 1.0 header, the first of which holds a
   pyramid of prefiltered textons.

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
                        header data, which older readers skip by header_size: see version 1.1).
      12     4  u32     header_size: offset of the texton data. >= 128; exactly 128 in files written
                        as 1.0 (a 1.0 reader ignores bytes [128, header_size) whatever they hold).
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
                        (metadata), summed over every frequency including zero as Galerne,
                        Leclaire and Moisan define it (bakers of version 1.1.0 and before left
                        the zero frequency out).
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
        (a 1.2 reader accepts flags = DSN_FLAG_HISTOGRAM in a file of minor 2 or later; a runtime
        built without the mapping answers such a file ................. DSN_ERR_UNSUPPORTED)
     9. channels, bits, shape, interpolation, width/height ........... DSN_ERR_CHANNELS, DSN_ERR_BITS,
                                                                        DSN_ERR_SHAPE,
                                                                        DSN_ERR_INTERPOLATION,
                                                                        DSN_ERR_DIMENSIONS
    10. total_size != header_size + texton bytes + 4 ................. DSN_ERR_TOTAL_SIZE
    11. scale, default_impacts, unused channel fields ................ DSN_ERR_SCALE, DSN_ERR_IMPACTS,
                                                                        DSN_ERR_RESERVED
    12. grey colour transform with non-zero unused entries ........... DSN_ERR_COLOR_TRANSFORM
    13. a texton value of -128 / -32768, or non-zero outside the disk  DSN_ERR_TEXTON
    (a 1.1 reader continues with steps 14 and 15 of version 1.1 below)
    All size arithmetic is done so that it cannot overflow (sizes are compared before they are added).
   A buffer longer than total_size is accepted (trailing bytes are ignored).

   ==================================================================================================
   .dsnt version 1.1: sections, and the texton pyramid
   ==================================================================================================

   A 1.1 file is a 1.0 file (every rule above holds, version_minor = 1) whose header continues past
   byte 128 with sections: header_size covers them, and the texton still starts at header_size. A 1.0
   reader skips to header_size and reads the texton unchanged, so old readers read new files; a 1.1
   reader reads 1.0 files (they have no sections). The CRC still covers the whole file.

   Sections (only when version_minor >= 1; a minor-0 file's bytes [128, header_size) are ignored)
   Bytes [128, header_size) are a sequence of sections that fills them exactly:
       u32 kind, u32 size (payload bytes), payload, then zero bytes up to a multiple of 4
   so every section starts 4-aligned relative to the file. A known kind appears at most once; readers
   skip kinds they do not know (forward compatibility: a later minor adds kinds, not fixed fields).
   Kinds: 1 = texton pyramid. Kind 0 and every other value are unknown to 1.1 readers.

   Section kind 1: texton pyramid (payload offsets from the start of the payload)
     off   size    type       field
       0      1    u8         level_count L: 1..8
       1      3    u8[3]      reserved, must be 0
       4     4L    records    one 4-byte record per level, level 1 first:
                                u8 width, u8 height: odd, 1..255
                                i8 exponent e_l: -24..24
                                u8 reserved, must be 0
    4+4L      n    values     the levels' values, level 1 first, each width * height * channels values
                              (i8 or i16 as the texton's `bits`, little-endian), row-major from the top
                              row, channels interleaved, in [-127, 127] / [-32767, 32767] (-128 / -32768
                              reserved, as in the texton).
   size = 4 + 4 L + sum over the levels of width_l * height_l * channels * bits / 8, exactly.

   Meaning of the pyramid
   Level 0 is the texton as the continuous mode reads it (bilinearly): with r = (width - 1) / 2,
   r' = (height - 1) / 2, hat(u, v) = max(0, 1 - |u|) max(0, 1 - |v|) the 2D tent and
   t[j] = q[j] scale[c] / 2^40 the texton values at j in [-r, r] x [-r', r'],
       t0(x) = sum_j t[j] hat(x - j).
   Level l >= 1 stands for t0 convolved with the isotropic Gaussian G_l of standard deviation
   sigma_l = 2^(l-1) texels: the prefiltered texton that a pixel filter of width about 2^l texels sees
   (filtering a spot noise filters its texton: the noise of the same impulses with t * G_l is the
   filtered noise). Its values are the samples of a bilinear texton at spacing 2^l, centred on the
   impulse (level-l value (i, j) sits at offset (2^l (i - r_l), 2^l (j - r'_l)) in level-0 texels,
   r_l = (width_l - 1) / 2, r'_l = (height_l - 1) / 2; no half-texel shift between levels):
       t_l(x) = sum_(i,j) s_l[i, j] hat(x / 2^l - (i - r_l, j - r'_l)),
       s_l = q_l scale[c] 2^e_l / 2^40
   with q_l the stored integers and e_l the level's exponent (one per level, shared by the channels).
   A writer chooses s_l as the L2 projection of t0 * G_l onto the span of those tents (least squares):
   by Campbell's theorem that minimizes the expected squared error of the filtered noise, lambda times
   the integral of (t_l - t0 * G_l)^2, so it is the best prefilter of that form. Level windows keep the
   spill of the blurred texton beyond the original support (discarding it would make the mean drift).
   dsn-bake makes L = floor(log2(max(r, r'))) + 1 levels (none for a 1 x 1 texton) with
   r_l = ceil((r + 1 + 3 sigma_l) / 2^l) per axis; readers accept any level sizes within the rules
   above. The mean of a level follows from its stored values alone: the noise of t_l has expectation
   lambda * integral t_l = lambda 4^l sum s_l, so a reader computes each level's exact offset from the
   integer sums of q_l (nothing of it is stored).

   Validation order, continued (after step 13; only when version_minor >= 1)
    14. section framing: a section header or payload (with its padding) overruns header_size, a
        non-zero padding byte, a known kind that appears twice ..... DSN_ERR_SECTION
    15. pyramid contents: level_count 0 or above 8, reserved bytes non-zero, a payload too short for
        its records, a width or height even or 0, an exponent outside -24..24, a size that differs from
        the formula above, a value of -128 / -32768 ................. DSN_ERR_PYRAMID
   A runtime built without the filtered evaluation (DSN_FILTERING 0 in dsn.h, the small build) skips
   steps 14 and 15: it reads every 1.1 file as a 1.0 file, and so accepts files whose sections a full
   build rejects.

   ==================================================================================================
   .dsnt version 1.2: the histogram-preserving output
   ==================================================================================================

   A 1.2 file may map the Gaussian noise through an inverse histogram (Heitz and Neyret, "High-
   Performance By-Example Noise using a Histogram-Preserving Blending Operator", HPG 2018): the baker
   decorrelates the exemplar's colours (PCA), Gaussianizes each decorrelated channel through its
   empirical CDF and bakes the texton of that Gaussianized exemplar; the runtime evaluates the Gaussian
   noise as in 1.0 (out_c above, here "Gaussian-space" values) and then maps each channel back through
   a lookup table and the colour rotation. Such a file sets bit 0 of `flags` (DSN_FLAG_HISTOGRAM) and
   holds exactly one section of kind 2; version_minor is 2. A 1.0 or 1.1 reader rejects it
   (DSN_ERR_RESERVED: flags must be 0 there), so no older reader shows Gaussian-space values as colours.
   Files without the flag are written with the lowest minor that holds their sections (0 or 1).
   Kind 2 is a known kind from minor 2 on: in a file of minor 1 a 1.2 reader skips it, as a 1.1 reader
   does, and flags must be 0 there (step 8).

   Section kind 2: histogram mapping (payload offsets from the start of the payload)
     off   size     type      field
       0      2     u16       entry_count N: 2..1024 (dsn-bake writes 129)
       2      1     u8        level_count M: 1..9: tables for levels 0 .. M - 1 (dsn-bake writes
                              1 + the pyramid's level count)
       3      1     u8        step_shift s: 0..16: table entry i stands for the Gaussian-space value
                              input_low + i 2^-s
       4      4     i32       input_low, Q16.16
       8     36     i32[9]    rotation P, Q8.24, row-major: output c = centre[c] + sum_k P[c*3+k] v_k.
                              Grey: only P[0] is used, the other eight entries must be 0.
      44     12     i32[3]    centre[c], Q8.24 (0 for unused channels)
      56     12     i32[3]    expected[k], Q16.16: the value v_k the filtered evaluation fades to beyond
                              its coarsest level, within the tables' range [-32767 2^4, 32767 2^4]
                              (0 for unused channels)
      68  2MNC     i16        table values T[l][k][i], Q3.12 (value = raw / 4096), level-major, then
                              channel, then entry: (l, k, i) at index (l C + k) N + i, C = channels;
                              in [-32767, 32767] (-32768 reserved)
   size = 68 + 2 M N C exactly.

   Meaning of the mapping
   Let d = 16 - s. For Gaussian-space value g_k (Q16.16, the 1.0 output of channel k), with
   u = clamp(g_k - input_low, 0, (N - 1) 2^d) (in 64-bit arithmetic), i = floor(u / 2^d),
   f = u - i 2^d and j = min(i + 1, N - 1), the level-l table gives (Q16.16, linear interpolation,
   exact integer arithmetic, one rounding half up):
       v_k = round((T[l][k][i] 2^d + (T[l][k][j] - T[l][k][i]) f) 2^4 / 2^d)
   and the output is (Q16.16, rounding half up, saturated to int32)
       out_c = round((centre[c] 2^16 + sum_k P[c*3+k] v_k) / 2^24).
   (|v_k| <= 32767 2^4 < 2^19, so the sum stays below 2^47 + 3 2^31 2^19 < 2^52 and |out_c| < 2^28:
   64-bit integers hold every step and the saturation never acts.)
   The unfiltered evaluations (lattice and continuous; point, tile and batch) use level 0. Level l >= 1
   is level 0's table prefiltered for pyramid level l: T_l(y) = E[T_0(y + rho_l Z)], Z standard
   normal, rho_l^2 = var_0 - var_l the variance of channel k that the level's filter removed (Deliot and
   Heitz, "Procedural Stochastic Textures by Tiling and Blending", GPU Zen 2, prefilter the table per
   mip level), so that a filtered pixel still averages to the exemplar's mean colour. The filtered
   evaluation, blending levels l and l + 1 with weight w, maps its blended Gaussian-space value g by
   (1 - w) T_l(g) + w T_(l+1)(g), with T_l = expected for every l >= M (the fade beyond the coarsest
   table). Exactly, with w = b / 256 (b = 0..255 the fraction of the level of detail, dsn.h), g_k the
   Q16.16 value the filtered evaluation returns without the mapping and X_l = (T[l][k][i] 2^d +
   (T[l][k][j] - T[l][k][i]) f) 2^4 for l < M, X_l = expected[k] 2^d for l >= M (i, j, f from g_k
   as above):
       v_k = round(((256 - b) X_l + b X_(l+1)) / 2^(d + 8))     (one rounding, half up)
   which is the level-0 formula above when l = 0 and b = 0, and v_k = expected[k] once l >= M; out_c
   follows from v_k as above.

   Validation order, continued (only when version_minor >= 2, after step 15)
    16. histogram: the flag without a kind-2 section or a kind-2 section without the flag, N, M or s
        out of range, M above 1 + the pyramid's level count, a size that differs from the formula, a
        grey rotation with non-zero unused entries, a non-zero unused centre or expected, an expected
        value outside [-32767 2^4, 32767 2^4], a table value of -32768 .. DSN_ERR_HISTOGRAM
   A runtime built without the mapping (DSN_HISTOGRAM 0 in dsn.h, the default of the small build)
   rejects any file with the flag (DSN_ERR_UNSUPPORTED, at step 8) and skips step 16. A runtime built
   with the mapping but without the filtered evaluation still runs steps 14 and 15 (it reads the
   sections to find the mapping).

   ==================================================================================================
   .dsnt version 1.3: the lattice texton of a bilinear asset
   ==================================================================================================

   A texton baked for bilinear reads (interpolation 1) is compensated for the smoothing of the bilinear
   read: the continuous noise sampled on the lattice has the texton's spectrum times
       B(xi) = (2/3 + cos(2 pi xi1)/3) (2/3 + cos(2 pi xi2)/3),
   so the bake divides the target spectrum by B. Read as it is on the lattice, the same texton has its
   spectrum without that factor: up to 1/B = 9 times the exemplar's power at the highest frequencies. A
   1.3 bilinear file therefore also carries the texton that the lattice evaluators read, in a section of
   kind 3, so that every evaluator gives the exemplar's statistics. That texton is the texton convolved
   with k (x) k, k the two-tap filter [a, b] at offsets 0 and +1 with
       a = (1 + 1/sqrt(3)) / 2,   b = (1 - 1/sqrt(3)) / 2,
   whose power spectrum a^2 + b^2 + 2ab cos(2 pi xi) = 2/3 + cos(2 pi xi)/3 is B's factor along one axis:
   the lattice noise of (t * k * k) has exactly the covariance of the continuous noise at integer lags.
   The writer rounds it to the texton's own scale and bits, one row and column larger on each side than
   the texton (the filter spreads it by one texel towards +x and +y; the first row and column are zero),
   and makes its integer sum per channel equal to the texton's (largest remainders get the rounding
   difference), so both reads share the same expected sum and the same normalization. Kind 3 is a known
   kind from minor 3 on; files with it are written as minor 3 (or later).

   Section kind 3: lattice texton (payload offsets from the start of the payload)
     off   size    type       field
       0      1    u8         width: odd, 1..255
       1      1    u8         height: odd, 1..255
       2      2    u8[2]      reserved, must be 0
       4      n    values     width * height * channels values (i8 or i16 as the texton's `bits`,
                              little-endian), row-major from the top row, channels interleaved, in
                              [-127, 127] / [-32767, 32767] (-128 / -32768 reserved), centred on the
                              impulse as the texton is; value q of channel c stands for q scale[c] / 2^40.
   size = 4 + width * height * channels * bits / 8, exactly.

   Validation order, continued (only when version_minor >= 3, after step 16)
    17. lattice texton: a kind-3 section in a lattice-baked file, reserved bytes non-zero, a width or
        height even or 0, a size that differs from the formula, a value of -128 / -32768, or a channel
        whose values do not sum to the texton's .................... DSN_ERR_LATTICE_TEXTON
   Every runtime build reads kind 3 (the small build included: it is the lattice evaluators' texton).
   A 1.2 reader skips the section and reads the bilinear texton on the lattice, as before 1.3.

   ================================================================================================== */
#ifndef DSN_FORMAT_H
#define DSN_FORMAT_H

#include <stddef.h>
#include <stdint.h>

#define DSN_FORMAT_MAGIC "\211DSN\r\n\032\n" /* 0x89 'D' 'S' 'N' CR LF SUB LF */
#define DSN_FORMAT_MAGIC_SIZE 8u
#define DSN_FORMAT_VERSION_MAJOR 1u
#define DSN_FORMAT_VERSION_MINOR                                                                             \
    3u /* the newest minor this header describes; files without sections are                                 \
           written as minor 0 (DSN_FORMAT_VERSION_MINOR_PLAIN) */
#define DSN_FORMAT_VERSION_MINOR_PLAIN 0u
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

/* Sections (version 1.1). */
#define DSN_FORMAT_SECTIONS_MINOR 1u /* sections are read from files of this minor version on */
#define DSN_SECTION_HEADER_SIZE 8u   /* u32 kind, u32 size */
#define DSN_SECTION_ALIGNMENT 4u
#define DSN_SECTION_PYRAMID 1u
#define DSN_PYRAMID_HEADER_SIZE 4u /* u8 level_count, u8[3] reserved */
#define DSN_PYRAMID_RECORD_SIZE 4u /* u8 width, u8 height, i8 exponent, u8 reserved */
#define DSN_PYRAMID_MAX_LEVELS 8u
#define DSN_PYRAMID_EXPONENT_MIN (-24)
#define DSN_PYRAMID_EXPONENT_MAX 24
#define DSN_SECTION_HISTOGRAM 2u      /* version 1.2 */
#define DSN_FORMAT_HISTOGRAM_MINOR 2u /* files with the histogram mapping are written as this minor */
#define DSN_FLAG_HISTOGRAM 1u         /* flags bit 0: the output goes through the kind-2 section */
#define DSN_HISTOGRAM_HEADER_SIZE 68u /* payload bytes before the table values */
#define DSN_HISTOGRAM_MAX_ENTRIES 1024u
#define DSN_HISTOGRAM_MAX_LEVELS 9u
#define DSN_HISTOGRAM_MAX_STEP_SHIFT 16u
#define DSN_HISTOGRAM_VALUE_FRACTION_BITS 12      /* table values: Q3.12 */
#define DSN_HISTOGRAM_VALUE_LIMIT 32767           /* |table value| <= this; -32768 is reserved */
#define DSN_HISTOGRAM_EXPECTED_LIMIT (32767 << 4) /* |expected[k]| <= this (Q16.16) */
#define DSN_SECTION_LATTICE_TEXTON 3u             /* version 1.3 */
#define DSN_FORMAT_LATTICE_TEXTON_MINOR 3u        /* files with a lattice texton are written as this minor */
#define DSN_LATTICE_TEXTON_HEADER_SIZE 4u         /* u8 width, u8 height, u8[2] reserved */

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

/* Error codes shared by the loader, the runtime and the tools: 0 is success, every failure is distinct
   and negative, and a code keeps its value in every version. One table, X(name, value, message), makes
   both the enum below and the messages of dsn_error_message() (dsn.h); include it with your own X to
   build, say, a table of names. -19 belongs to no error (it is retired, never
   returned) so that every other code keeps its value. */
#define DSN_LIST_ERRORS(X)                                                                                   \
    X(DSN_OK, 0, "success")                                                                                  \
    X(DSN_ERR_NULL, -1, "a required pointer argument is null")                                               \
    X(DSN_ERR_TRUNCATED, -2, "the buffer ends before the asset does (truncated file)")                       \
    X(DSN_ERR_BAD_MAGIC, -3, "not a .dsnt asset (bad magic)")                                                \
    X(DSN_ERR_TEXT_MODE, -4, "the asset's magic was damaged by a text-mode (CR/LF) transfer")                \
    X(DSN_ERR_VERSION, -5, "unsupported .dsnt major version")                                                \
    X(DSN_ERR_HEADER_SIZE, -6, "header size out of range")                                                   \
    X(DSN_ERR_TOTAL_SIZE, -7, "total size inconsistent with the header fields")                              \
    X(DSN_ERR_CRC, -8, "checksum mismatch: the asset is damaged")                                            \
    X(DSN_ERR_RESERVED, -9, "a reserved bit, byte or unused-channel field is not 0")                         \
    X(DSN_ERR_CHANNELS, -10, "channel count is not 1 or 3")                                                  \
    X(DSN_ERR_BITS, -11, "quantization bits is not 8 or 16")                                                 \
    X(DSN_ERR_SHAPE, -12, "unknown support shape, or a disk that is not square")                             \
    X(DSN_ERR_INTERPOLATION, -13, "unknown interpolation")                                                   \
    X(DSN_ERR_DIMENSIONS, -14, "texton width/height is zero, even or above 255")                             \
    X(DSN_ERR_SCALE, -15, "a used channel has scale 0")                                                      \
    X(DSN_ERR_IMPACTS, -16, "impacts per pixel out of range")                                                \
    X(DSN_ERR_COLOR_TRANSFORM, -17, "grey asset with non-zero unused colour transform entries")              \
    X(DSN_ERR_TEXTON, -18, "reserved texton value, or non-zero value outside the support")                   \
    X(DSN_ERR_CONTINUOUS_MISMATCH, -20, "continuous mode on a lattice-baked asset is not allowed")           \
    X(DSN_ERR_SCRATCH, -21, "scratch buffer missing or too small")                                           \
    X(DSN_ERR_TILE_SIZE, -22, "tile width or height is 0 or too large")                                      \
    X(DSN_ERR_ARGUMENT, -23, "an argument is out of its documented range")                                   \
    X(DSN_ERR_SECTION, -24, "a header section overruns the header, is badly padded or repeated")             \
    X(DSN_ERR_PYRAMID, -25, "invalid texton pyramid: level count, sizes, exponent or reserved field")        \
    X(DSN_ERR_HISTOGRAM, -26, "invalid histogram mapping: flag and section disagree, or a bad field")        \
    X(DSN_ERR_UNSUPPORTED, -27, "the asset needs the histogram mapping, which this build leaves out")        \
    X(DSN_ERR_LATTICE_TEXTON, -28, "invalid lattice texton: size, reserved field, value or sum")             \
    X(DSN_ERR_COST, -29, "one point would examine more impulses than the runtime allows (dense, wide reach)")

/* clang-format off */
#define DSN_ERROR_ENUM_ENTRY(name, value, message) name = value,
enum dsn_error {
    DSN_LIST_ERRORS(DSN_ERROR_ENUM_ENTRY)
    DSN_ERR_LOWEST = DSN_ERR_COST /* the most negative code: every code lies in [DSN_ERR_LOWEST, 0] */
};
/* clang-format on */
#undef DSN_ERROR_ENUM_ENTRY

#endif /* DSN_FORMAT_H */
