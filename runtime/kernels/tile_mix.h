/* runtime/kernels/tile_mix.h - a lattice tile of two mixed materials whose weights are the same over the
   whole tile (mix_tile.cpp's bands, dsn.h "Mixing"), on the strip path: each rectangle's impulses listed
   per material (those whose hash draws it, kernels.h's dsn_impulse_filter), each material's strips summed
   from its own texton, each normalized in lanes with its own gains and weighted offset, and the two
   materials' lanes added before they are stored. The bits are those of the mix's points: each material's
   lanes are its dsn_normalize values (tile_normalize.h), and the sum needs no saturation where the
   materials' bounds (value_bound) cannot add past int32. Internal to tile_render.h. */
#ifndef DSN_TILE_MIX_H
#define DSN_TILE_MIX_H

#if DSN_TILE_BLOCKS && DSN_MIXING

namespace {

const uint32_t mix_tile_materials = 2;

/* What a mixed tile prepares once per material: its noise (its lattice view, with its weighted offset),
   the impulses it keeps, and its strip path's texton and normalization. */
typedef struct mix_tile_material {
    const dsn_noise_state *noise;
    keep_material keep;
    strip_setup setup;
} mix_tile_material;

/* The largest magnitude of a noise's normalized lanes over its channels, |P_q| + 2^(46 - s)
   (tile_normalize.h), or 2^31 where they are not split into lanes. */
int64_t value_bound(const dsn_noise_state *noise) {
    split_normalization split;
    const int64_t none = int64_t(1) << 31;
    if (!make_split_normalization(noise, &split)) return none;
    int64_t most = 0;
    for (uint32_t c = 0; c < noise->asset.channels; c++) {
        const int64_t bound = (split.p_q[c] < 0 ? -int64_t(split.p_q[c]) : int64_t(split.p_q[c])) +
                              (int64_t(1) << (46u - noise->gain_shift));
        most = bound > most ? bound : most;
    }
    return most;
}

/* Which of the two materials an impulse draws, as a bit each (both filters tested on one hash). */
struct keep_either {
    keep_material first, second;
    uint32_t operator()(uint32_t key, uint32_t k) const {
        const uint64_t hash = dsn_material_hash(key, k);
        return uint32_t(hash - first.low < first.span) | uint32_t(hash - second.low < second.span) << 1;
    }
};

/* The impulses of one walk into each material's list: every impulse stored in both, counted in the list
   of the material it draws (keep_either's bits). */
struct either_list {
    impulse_list *lists;
    void operator()(uint32_t end_x, uint32_t end_y, uint32_t drawn) {
        lists[0](end_x, end_y, drawn & 1u);
        lists[1](end_x, end_y, drawn >> 1);
    }
};

/* One rectangle: 0 where a material's impulses do not fit the strips (the caller then renders the tile
   otherwise). Materials whose textons have one size are listed from one walk (their impulses reach the
   same pixels; every material has the mix's cells), others from a walk each. */
template <uint32_t Channels, typename Value>
int mix_rectangle(mix_tile_material *materials, const tile_run *walk_x, const tile_run *walk_y,
                  const tile_target *target) {
    impulse_list lists[mix_tile_materials];
    strip_entries entries[mix_tile_materials];
    for (uint32_t m = 0; m < mix_tile_materials; m++) lists[m].clear(walk_x->length, walk_y->length);
    const dsn_asset *asset_0 = &materials[0].noise->asset, *asset_1 = &materials[1].noise->asset;
    if (asset_0->width == asset_1->width && asset_0->height == asset_1->height) {
        either_list either = {lists};
        const keep_either keep = {materials[0].keep, materials[1].keep};
        for_each_nearby_impulse(materials[0].noise, walk_x, walk_y, either, keep);
    } else {
        for (uint32_t m = 0; m < mix_tile_materials; m++)
            for_each_nearby_impulse(materials[m].noise, walk_x, walk_y, lists[m], materials[m].keep);
    }
    for (uint32_t m = 0; m < mix_tile_materials; m++) {
        const strip_texton *texton = &materials[m].setup.texton;
        if (!lists[m].prepare(texton->width, texton->height)) return 0;
        file_strip_entries(&lists[m], texton, walk_x->length, walk_y->length, &entries[m]);
    }
    for (uint32_t y = 0; y < walk_y->length; y += strip_rows) {
        simd_vector sums[mix_tile_materials][strip_count][3 * strip_rows];
        for (uint32_t m = 0; m < mix_tile_materials; m++) {
            const strip_texton *texton = &materials[m].setup.texton;
            const strip_texel *row_zero = texton->values + (strip_rows - 1) * texton->stride;
            const uint32_t last_key_end = y + strip_rows - 1 + texton->height;
            for (uint32_t s = 0; s * lane < walk_x->length; s++) {
                const uint32_t first = entries[m].key_start[s][y],
                               end = entries[m].key_start[s][last_key_end];
                add_strip_rows<Channels>(row_zero + y * texton->stride, entries[m].base + first, end - first,
                                         texton->plane, texton->stride, sums[m][s]);
            }
        }
        for (uint32_t r = 0; r < strip_rows && y + r < walk_y->length; r++) {
            Value *out = static_cast<Value *>(target->out) +
                         size_t(walk_y->offset + y + r) * target->row_values + walk_x->offset * Channels;
            for (uint32_t s = 0; s * lane < walk_x->length; s++) {
                const uint32_t pixels = walk_x->length - s * lane < lane ? walk_x->length - s * lane : lane;
                simd_vector lanes[2][3], second[2][3];
                normalized_lanes<Channels>(&materials[0].setup.split, sums[0][s] + 3 * r, lanes);
                normalized_lanes<Channels>(&materials[1].setup.split, sums[1][s] + 3 * r, second);
                for (uint32_t h = 0; h < 2; h++)
                    for (uint32_t c = 0; c < Channels; c++) lanes[h][c] = add_32(lanes[h][c], second[h][c]);
                store_lanes<Channels>(lanes, pixels, out + s * lane * Channels);
            }
        }
    }
    return 1;
}

/* The whole tile in rectangles that suit both materials; 0 where a rectangle does not fit (having
   written part of the tile). */
template <uint32_t Channels, typename Value>
int mix_tile_rectangles(mix_tile_material *materials, rectangle_size rectangle, const tile_run *run_x,
                        const tile_run *run_y, const tile_target *target) {
    for (uint32_t y = 0; y < run_y->length; y += rectangle.height) {
        const tile_run walk_y = {run_y->start + y, run_y->offset + y,
                                 run_y->length - y < rectangle.height ? run_y->length - y : rectangle.height};
        for (uint32_t x = 0; x < run_x->length; x += rectangle.width) {
            const tile_run walk_x = {run_x->start + x, run_x->offset + x,
                                     run_x->length - x < rectangle.width ? run_x->length - x
                                                                         : rectangle.width};
            if (!mix_rectangle<Channels, Value>(materials, &walk_x, &walk_y, target)) return 0;
        }
    }
    return 1;
}

/* The mixed lattice tile entry (kernels.h's lattice_mix_tile). (Inline: a file that includes tile_render.h
   for its other functions need not use it.) */
inline int render_mix_tile(const dsn_noise_state *const *noises, const dsn_impulse_filter *filters,
                           uint32_t count, uint32_t x0, uint32_t y0, uint32_t width, uint32_t height,
                           void *out, dsn_output_kind kind) {
    if (count != mix_tile_materials) return 0;
    const uint32_t channels = noises[0]->asset.channels;
    rectangle_size rectangle = {rectangle_width, rectangle_height};
    int64_t bound = 0;
    for (uint32_t m = 0; m < count; m++) {
        const dsn_noise_state *noise = noises[m];
        if (noise->asset.channels != channels || noise->asset.histogram_table != 0 ||
            !lattice_strips_take(noise))
            return 0;
        const rectangle_size own = choose_rectangle(noise);
        if (own.width == 0) return 0;
        rectangle.width = own.width < rectangle.width ? own.width : rectangle.width;
        rectangle.height = own.height < rectangle.height ? own.height : rectangle.height;
        bound += value_bound(noise);
    }
    if (bound > INT32_MAX) return 0;
    tile_run runs_x[2], runs_y[2];
    if (split_runs(x0, width, noises[0]->period[0], runs_x) != 1 ||
        split_runs(y0, height, noises[0]->period[1], runs_y) != 1)
        return 0;
    mix_tile_material materials[mix_tile_materials];
    const uint64_t pixels = uint64_t(width) * height;
    for (uint32_t m = 0; m < count; m++) {
        materials[m].noise = noises[m];
        materials[m].keep.low = filters[m].low;
        materials[m].keep.span = filters[m].high - filters[m].low;
        make_strip_setup(noises[m], rectangle, pixels, 4, &materials[m].setup);
        if (!materials[m].setup.split_ok) return 0;
    }
    const tile_target target = {out, kind, 0, width * channels, 0};
    if (kind == dsn_output_float)
        return channels == 3 ? mix_tile_rectangles<3, float>(materials, rectangle, runs_x, runs_y, &target)
                             : mix_tile_rectangles<1, float>(materials, rectangle, runs_x, runs_y, &target);
    if (kind == dsn_output_u8)
        return channels == 3 ? mix_tile_rectangles<3, uint8_t>(materials, rectangle, runs_x, runs_y, &target)
                             : mix_tile_rectangles<1, uint8_t>(materials, rectangle, runs_x, runs_y, &target);
    return channels == 3 ? mix_tile_rectangles<3, int32_t>(materials, rectangle, runs_x, runs_y, &target)
                         : mix_tile_rectangles<1, int32_t>(materials, rectangle, runs_x, runs_y, &target);
}

} // namespace

#define DSN_LATTICE_MIX_TILE_ENTRY render_mix_tile
#else
#define DSN_LATTICE_MIX_TILE_ENTRY 0
#endif /* DSN_TILE_BLOCKS && DSN_MIXING */

#endif /* DSN_TILE_MIX_H */
