/* golden_kernel.glsl - what one shader invocation of the GPU golden program computes: one point of a
   lattice tile, one point of a continuous grid, or one listed query (a point of any mode, a coordinate
   conversion), of a noise or of a mix, with the output converted as the C API converts it; for a
   gradient, the value and its two derivatives. The including shader defines golden_query() (where the
   queries are) and calls golden_evaluate(index, value, dx, dy) (dx and dy are 0 but for a gradient). */

/* The task of this draw or dispatch. */
uniform uint task_kind;         /* 0: listed queries, 1: a lattice tile, 2: a continuous grid */
uniform uint task_output;       /* tiles: 0 fixed Q16.16, 1 float32 bits, 2 u8 */
uniform uint task_gradient;     /* tiles: 1 for the value with its gradient, else 0 */
uniform uint task_mix;          /* tiles: 1 when the words are a mix's (dsn_gpu_mix_pack), else 0 */
uniform uint task_width;        /* tiles: pixels per row */
uniform uvec4 task_origin;      /* lattice: (x, -, y, -); grid: (x low, x high, y low, y high) */
uniform uvec4 task_column_step; /* grid: the step to the next pixel of a row, Q32.32 x then y */
uniform uvec4 task_row_step;    /* grid: the step to the next row */

/* Query `index` as four uvec4 (parts 0 to 3): (mode, x low, x high, y low), (y high, ...). Modes: bits
   0-7 the point (0 lattice (x, y) int32, 1 continuous (x, y) Q32.32, 2 continuous from the IEEE bits of
   two doubles, 3 coordinate from a double's bits (x), 4 coordinate from a float's bits (x low), 5 a
   surface point (x, y, z Q32.32, then the frame's tangent, bitangent and normal), 6 a surface point from
   the IEEE bits of three doubles and of a float normal and tangent (then 1 when there is a tangent), 7 a
   surface frame from the float bits of a normal (words 1-3) and a tangent (4-6) with the tangent's flag
   (word 7): its tangent, bitangent and normal as value, dx and dy, value.w 1 when it is made), bits 8-15
   the output conversion as task_output, bit 16 the gradient (points of modes 0 to 2), bit 17 a mix's
   point (modes 0 and 1). */
uvec4 golden_query(uint index, uint part);

uvec4 golden_convert(ivec3 value, uint conversion) {
    if (conversion == 1u)
        return uvec4(dsn_fixed_to_float_bits(value.x), dsn_fixed_to_float_bits(value.y),
                     dsn_fixed_to_float_bits(value.z), 0u);
    if (conversion == 2u)
        return uvec4(dsn_fixed_to_u8(value.x), dsn_fixed_to_u8(value.y), dsn_fixed_to_u8(value.z), 0u);
    return uvec4(uvec3(value), 0u);
}

/* The lattice point p, or the continuous point (x, y): its value alone or with its gradient, or a mix's
   value. */
void golden_point(bool lattice, ivec2 p, uvec2 x, uvec2 y, bool gradient, bool mix, uint conversion,
                  out uvec4 value, out uvec4 dx, out uvec4 dy) {
    ivec3 v = ivec3(0), gx = ivec3(0), gy = ivec3(0);
    if (mix) {
#if GOLDEN_CPU_MIXES /* dsn-gpu-golden --cpu-mixes: no mix code in the shader (the C runtime answers) */
        v = ivec3(0);
#else
        v = lattice ? dsn_mix_lattice_point_fixed(p) : dsn_mix_continuous_point_fixed(x, y);
#endif
    } else if (gradient) {
        if (lattice)
            dsn_lattice_gradient_fixed(p, v, gx, gy);
        else
            dsn_continuous_gradient_fixed(x, y, v, gx, gy);
    } else {
        v = lattice ? dsn_lattice_point_fixed(p) : dsn_continuous_point_fixed(x, y);
    }
    value = golden_convert(v, conversion);
    dx = golden_convert(gx, conversion);
    dy = golden_convert(gy, conversion);
}

/* A surface query (modes 5 to 7) of the words w[0 .. 15]. */
void golden_surface(uint point, uint conversion, uvec4 w0, uvec4 w1, uvec4 w2, uvec4 w3, out uvec4 value,
                    out uvec4 dx, out uvec4 dy) {
    value = uvec4(0u);
    dx = uvec4(0u);
    dy = uvec4(0u);
#if !GOLDEN_CPU_SURFACES /* dsn-gpu-golden --cpu-surfaces: no surface code in the shader */
    if (point == 7u) {
        ivec3 t, b, n;
        bool made = dsn_surface_frame_from_float_bits(w0.yzw, w1.xyz, w1.w != 0u, t, b, n);
        value = uvec4(uvec3(t), made ? 1u : 0u);
        dx = uvec4(uvec3(b), 0u);
        dy = uvec4(uvec3(n), 0u);
        return;
    }
    ivec3 v = ivec3(0);
    if (point == 5u) {
        v = dsn_surface_point_fixed(w0.yz, uvec2(w0.w, w1.x), w1.yz, ivec3(uvec3(w1.w, w2.xy)),
                                    ivec3(uvec3(w2.zw, w3.x)), ivec3(w3.yzw));
    } else {
        ivec3 t, b, n;
        if (dsn_surface_frame_from_float_bits(uvec3(w1.w, w2.xy), uvec3(w2.zw, w3.x), w3.y != 0u, t, b, n))
            v = dsn_surface_point_fixed(dsn_coordinate_from_double_bits(w0.yz),
                                        dsn_coordinate_from_double_bits(uvec2(w0.w, w1.x)),
                                        dsn_coordinate_from_double_bits(w1.yz), t, b, n);
    }
    value = golden_convert(v, conversion);
#endif
}

/* One call of each evaluator in the shader (each is inlined where it is called). */
void golden_evaluate(uint index, out uvec4 value, out uvec4 dx, out uvec4 dy) {
    uint i = index % task_width, j = index / task_width;
    bool lattice = task_kind == 1u, gradient = task_gradient != 0u, mix = task_mix != 0u;
    uint conversion = task_output;
    ivec2 p = ivec2(int(task_origin.x + i), int(task_origin.z + j));
    uvec2 x = uvec2(0u), y = uvec2(0u);
    if (task_kind == 2u) {
        /* origin + i column_step + j row_step, modulo 2^64 */
        x = dsn_add64(task_origin.xy, dsn_add64(dsn_multiply64(uvec2(i, 0u), task_column_step.xy),
                                                dsn_multiply64(uvec2(j, 0u), task_row_step.xy)));
        y = dsn_add64(task_origin.zw, dsn_add64(dsn_multiply64(uvec2(i, 0u), task_column_step.zw),
                                                dsn_multiply64(uvec2(j, 0u), task_row_step.zw)));
    } else if (task_kind == 0u) {
        uvec4 first = golden_query(index, 0u), second = golden_query(index, 1u);
        uint point = first.x & 0xFFu;
        if (point >= 5u) {
            golden_surface(point, (first.x >> 8u) & 0xFFu, first, second, golden_query(index, 2u),
                           golden_query(index, 3u), value, dx, dy);
            return;
        }
        x = first.yz;
        y = uvec2(first.w, second.x);
        if (point > 2u) {
            dx = uvec4(0u);
            dy = uvec4(0u);
            value = point == 3u ? uvec4(dsn_coordinate_from_double_bits(x), 0u, 0u)
                                : uvec4(dsn_coordinate_from_float_bits(x.x), 0u, 0u);
            return;
        }
        lattice = point == 0u;
        gradient = ((first.x >> 16u) & 1u) != 0u;
        mix = ((first.x >> 17u) & 1u) != 0u;
        conversion = (first.x >> 8u) & 0xFFu;
        p = ivec2(int(x.x), int(y.x));
        if (point == 2u) {
            x = dsn_coordinate_from_double_bits(x);
            y = dsn_coordinate_from_double_bits(y);
        }
    }
    golden_point(lattice, p, x, y, gradient, mix, conversion, value, dx, dy);
}
