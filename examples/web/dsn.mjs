// dsn.mjs - the dsn runtime in JavaScript: loads dsn.wasm (the C runtime compiled for freestanding wasm32)
// and a .dsnt asset, and evaluates the noise with the runtime's bits: RGBA tiles for a canvas, lattice
// and continuous points, and the noise's gradient (for bump and normal mapping) per point and per tile.
// A plain ES module with no dependencies, for browsers, workers and Node.
//
//   import { loadRuntime } from './dsn.mjs';
//   const runtime = await loadRuntime(new URL('dsn.wasm', import.meta.url));
//   const texture = runtime.load(new Uint8Array(await (await fetch('demo.dsnt')).arrayBuffer()));
//   texture.configure({ seed: 7, density: 30 });             // throws DsnError on a bad setting
//   const rgba = texture.tile(0, 0, 256, 256);                // lattice tile, Uint8ClampedArray RGBA
//   const zoomed = texture.tile(10.5, -3, 256, 256, { scale: 4 }); // continuous grid, 4x magnified
//   canvas.getContext('2d').putImageData(new ImageData(rgba, 256, 256), 0, 0);
//   texture.point(12, 34);                                    // Float64Array, 1.0 = the exemplar's white
//   const { value, dx, dy } = texture.continuousGradient(12.5, 34.25); // and its derivatives per texel
//   texture.surfacePoint([x, y, z], [nx, ny, nz]);            // on any surface, no texture coordinates
//   texture.surfacePoint(p, n, null, { footprint: { x: [2, 0], y: [0, 2] } }); // filtered, 2 texels a pixel
//   const mix = runtime.mix([sand, gravel], {           // materials mixed by weights (dsn.h, "Mixing")
//       weights: { data: bytes, width: 64, height: 64, shift: 4 } }); // 2 bytes a sample, 16 texels apart
//   mix.tile(0, 0, 256, 256, { scale: 2 });                     // as Texture.tile
//
// Each texture owns a WebAssembly instance (its own memory), so textures are independent and a texture
// can be dropped by dropping the object. Errors from the runtime become DsnError exceptions carrying the
// runtime's code and message (dsn_error_message). Every argument is checked here, at the module's edge,
// before it reaches the runtime: a value of the wrong type throws TypeError, one out of its range
// RangeError, each naming the setting and its valid range (nothing is silently converted, wrapped or
// replaced by a default).

const IMPACTS_MIN_Q16 = 1 << 12; // dsn/format.h: DSN_IMPACTS_MIN_Q16 and DSN_IMPACTS_MAX_Q16
const IMPACTS_MAX_Q16 = 1024 * 65536;
const FLAG_NO_COLOR_TRANSFORM = 1;
const FLAG_ALLOW_LATTICE_CONTINUOUS = 2;
const INTERPOLATION_BILINEAR = 1; // dsn/format.h: DSN_INTERPOLATION_BILINEAR
const NOISE_BYTES = 1152;         // DSN_NOISE_BYTES
const MIX_BYTES = 4640;           // sizeof(dsn_mix): DSN_MIX_WORDS * 8
const MIX_MAX_MATERIALS = 4;      // DSN_MIX_MAX_MATERIALS
const CONTROL_BYTES = 28;         // dsn_mix_control: a pointer and six 32-bit fields
const CONFIG_BYTES = 20;          // five uint32 (wasm/web_exports.cpp checks the layouts used here)
const GRID_BYTES = 48;            // six int64
const SURFACE_BYTES = 128;        // three int64 (24), two float[3] (24), a dsn_surface_frame (36), aligned;
                                  // then a dsn_footprint (four int64 and a uint32: 40)
const FILTER_MAX_TAPS = 16;       // DSN_FILTER_MAX_TAPS
const ASSET_FIELDS = {
    channels: 8,
    bits: 12,
    interpolation: 20,
    width: 24,
    height: 28,
    defaultImpacts: 36
};
const PAGE = 65536;
const Q32_ONE = 4294967296;
const UINT32_MAX = 4294967295;
const SCALE_MIN = 1 / 65536, SCALE_MAX = 65536; // dsn-render --scale: steps of at most 2^16 texels
const MAX_TILE_PIXELS = 1 << 26;
const MAX_GRADIENT_TILE_PIXELS = 1 << 22; // three arrays of 32-bit values per channel
const POINT_FORMATS = ['number', 'fixed', 'float32'], TILE_FORMATS = ['float32', 'fixed'];

/** An error reported by the runtime: `code` is its dsn_error code, `message` its dsn_error_message. */
export class DsnError extends Error {
    constructor(code, message) {
        super(message);
        this.name = 'DsnError';
        this.code = code;
    }
}

/**
   Compiles dsn.wasm once. `source`: a URL (or string) to fetch, the file's bytes, or a
    WebAssembly.Module (one can be sent to a worker with postMessage).
 */
export async function loadRuntime(source) {
    return new Runtime(await compileModule(source));
}

/** A WebAssembly.Module from a URL (or string) to fetch, the file's bytes, or a module as it is. */
export async function compileModule(source) {
    if (source instanceof WebAssembly.Module) return source;
    if (source instanceof ArrayBuffer || ArrayBuffer.isView(source)) return WebAssembly.compile(source);
    const response = await fetch(source);
    if (!response.ok) throw new Error(`dsn: cannot fetch ${source}: HTTP ${response.status}`);
    return WebAssembly.compile(await response.arrayBuffer());
}

export class Runtime {
    constructor(module) {
        this.module = module;
        const probe = new WebAssembly.Instance(module, {}).exports;
        this.version = readString(probe.memory, probe.dsn_version());
    }

    /**
       Validates `bytes` (Uint8Array or ArrayBuffer: a .dsnt file) and returns a Texture configured with
        the defaults (seed 0, the asset's density). Throws DsnError with the loader's message.
     */
    load(bytes, settings = {}) {
        const texture = new Texture(new WebAssembly.Instance(this.module, {}).exports, toBytes(bytes));
        texture.configure(settings);
        return texture;
    }

    /**
       A mix of materials (dsn.h, "Mixing"): `assets`, 1 to 4 .dsnt files (Uint8Array or ArrayBuffer),
        the first leading (its seed, density and cells make the impulses of them all); each impulse
        carries one material, drawn from the weights at its position. settings: those of
        Texture.configure (seed, density, period, colorTransform; every material is configured with
        them), and weights (see Mix.setWeights). Throws as Texture.configure does, and DsnError where
        the runtime refuses the mix (a material with a histogram mapping: DSN_ERR_UNSUPPORTED).
     */
    mix(assets, settings = {}) {
        if (!Array.isArray(assets) || assets.length < 1 || assets.length > MIX_MAX_MATERIALS)
            throw new RangeError(`dsn: a mix takes an array of 1 to ${MIX_MAX_MATERIALS} assets`);
        const { weights, ...noiseSettings } = settings;
        return new Mix(new WebAssembly.Instance(this.module, {}).exports, assets.map(toBytes), noiseSettings,
                       weights);
    }
}

export class Texture {
    constructor(exports, bytes) {
        this.exports = exports;
        const memory = exports.memory;
        // Fixed blocks at the heap's start, then the asset's bytes (the asset keeps pointers into them),
        // then one work area (scratch, output) that grows as needed.
        let at = align(exports.__heap_base.value >>> 0, 16);
        const reserve = (size) => {
            const start = at;
            at = align(at + size, 16);
            return start;
        };
        this.assetAt = reserve(exports.dsn_web_asset_bytes() >>> 0);
        this.noiseAt = reserve(NOISE_BYTES);
        this.configAt = reserve(CONFIG_BYTES);
        this.gridAt = reserve(GRID_BYTES);
        this.valuesAt = reserve(16);
        this.gradientAt = reserve(3 * 16); // a point's value, dx and dy: three blocks of 16 bytes
        this.surfaceAt = reserve(SURFACE_BYTES); // a surface point: its position, normal, tangent, frame
        this.bytesAt = reserve(bytes.length);
        this.workAt = at;
        this.ensure(at);
        new Uint8Array(memory.buffer, this.bytesAt, bytes.length).set(bytes);
        check(exports, exports.dsn_asset_load(this.assetAt, this.bytesAt, bytes.length));
        const field = (offset) => new DataView(memory.buffer).getUint32(this.assetAt + offset, true);
        /** 1 (grey) or 3 (RGB). */
        this.channels = field(ASSET_FIELDS.channels);
        this.bits = field(ASSET_FIELDS.bits);
        /** 'lattice' or 'bilinear': how the texton was baked (bilinear suits the continuous mode). */
        this.interpolation =
            field(ASSET_FIELDS.interpolation) === INTERPOLATION_BILINEAR ? 'bilinear' : 'lattice';
        this.textonWidth = field(ASSET_FIELDS.width);
        this.textonHeight = field(ASSET_FIELDS.height);
        /** Impacts per pixel the asset asks for (30 when it names none). */
        this.defaultDensity = (field(ASSET_FIELDS.defaultImpacts) || 30 * 65536) / 65536;
        this.settings = null;
    }

    /**
       Sets seed (an integer 0 .. 2^32 - 1), density (impacts per pixel, 1/16 .. 1024; 0 or absent: the
        asset's), period ([px, py], integers 0 .. 2^32 - 1, 0 = not periodic on that axis) and
        colorTransform (a boolean; false: the identity). The continuous mode is allowed on lattice-baked
        assets too. Throws TypeError or RangeError for a setting the module refuses (an unknown name
        included), DsnError when the runtime refuses.
     */
    configure(settings = {}) {
        const { seed, impacts, period, colorTransform } = writeConfig(this.exports, this.configAt, settings);
        const err = this.exports.dsn_noise_init(this.noiseAt, this.assetAt, this.configAt);
        if (err !== 0) this.settings = null;
        check(this.exports, err);
        this.settings = {
            seed,
            density: impacts ? impacts / 65536 : this.defaultDensity,
            period: [period[0], period[1]],
            colorTransform
        };
        return this;
    }

    get seed() { return this.settings.seed; }
    get density() { return this.settings.density; }
    get period() { return this.settings.period; }

    /**
       The values at lattice point (x, y) (integers, taken modulo 2^32 as the runtime's int32 lattice
        wraps): Float64Array of `channels` values, exactly the runtime's Q16.16 fixed point / 65536
        (1.0 = the exemplar's white).
     */
    point(x, y) {
        this.checkConfigured();
        checkLattice('x', x);
        checkLattice('y', y);
        this.exports.dsn_lattice_point_fixed(this.noiseAt, x | 0, y | 0, this.valuesAt);
        return fromFixed(new Int32Array(this.exports.memory.buffer, this.valuesAt, this.channels));
    }

    /**
       The values at the continuous point (x, y) in texels (any finite number; the runtime converts it
        with dsn_coordinate_from_double): Float64Array as for point().
     */
    continuousPoint(x, y) {
        this.checkConfigured();
        checkFinite('x', x);
        checkFinite('y', y);
        const e = this.exports;
        check(e, e.dsn_continuous_point_fixed(this.noiseAt, e.dsn_coordinate_from_double(x),
                                              e.dsn_coordinate_from_double(y), this.valuesAt));
        return fromFixed(new Int32Array(e.memory.buffer, this.valuesAt, this.channels));
    }

    /**
       The surface noise (dsn.h, "Surface noise") at `position`, [x, y, z] in texels (finite numbers, each
        converted by dsn_coordinate_from_double), on the surface whose normal there is `normal`, [nx, ny,
        nz] (finite, not all zero; its direction counts), with an optional `tangent` [tx, ty, tz] (null:
        the frame from the normal alone); the vectors are rounded to float32, as the C function takes
        them. Returns a Float64Array as continuousPoint() (options.format 'fixed': the Q16.16 integers;
        'float32': dsn_surface_point_float's values). With options.footprint, { x: [u, v], y: [u, v],
        maxTaps } (the texels per pixel step along the screen's x and y, each [along the tangent, along
        the bitangent], finite; maxTaps 1 .. 16, a power of two or not, default 1: isotropic), the
        surface noise filtered by that footprint (dsn_surface_filtered_point_fixed; the asset needs its
        pyramid). Throws DsnError for a normal, or an asset, the runtime refuses.
     */
    surfacePoint(position, normal, tangent = null, options = {}) {
        this.checkConfigured();
        const vector = (name, value) => {
            if (!Array.isArray(value) || value.length !== 3)
                throw new TypeError(`dsn: ${name} must be an array of three numbers`);
            value.forEach((component, i) => checkFinite(`${name}[${i}]`, component));
        };
        vector('position', position);
        vector('normal', normal);
        if (tangent !== null) vector('tangent', tangent);
        const format = checkFormat(options, POINT_FORMATS, ['footprint']);
        const footprint = options.footprint === undefined ? null : checkFootprint(options.footprint);
        const e = this.exports, buffer = e.memory.buffer;
        const positionAt = this.surfaceAt, normalAt = positionAt + 24, tangentAt = normalAt + 12;
        const frameAt = tangentAt + 12, footprintAt = positionAt + 88;
        new Float32Array(buffer, normalAt, 3).set(normal);
        if (tangent !== null) new Float32Array(buffer, tangentAt, 3).set(tangent);
        if (footprint !== null)
            check(e, e.dsn_footprint_from_float(footprintAt, footprint.x[0], footprint.x[1], footprint.y[0],
                                                footprint.y[1], footprint.maxTaps));
        if (format === 'float32') {
            new Float64Array(buffer, positionAt, 3).set(position);
            const tangentArgument = tangent === null ? 0 : tangentAt;
            const noise = this.noiseAt, out = this.valuesAt;
            check(e, footprint === null
                         ? e.dsn_surface_point_float(noise, positionAt, normalAt, tangentArgument, out)
                         : e.dsn_surface_filtered_point_float(noise, positionAt, normalAt, tangentArgument,
                                                              footprintAt, out));
            return new Float32Array(e.memory.buffer, this.valuesAt, this.channels).slice();
        }
        check(e, e.dsn_surface_frame_from_float(normalAt, tangent === null ? 0 : tangentAt, frameAt));
        new BigInt64Array(buffer, positionAt, 3).set(position.map((value) => e.dsn_coordinate_from_double(value)));
        check(e, footprint === null
                     ? e.dsn_surface_point_fixed(this.noiseAt, positionAt, frameAt, this.valuesAt)
                     : e.dsn_surface_filtered_point_fixed(this.noiseAt, positionAt, frameAt, footprintAt,
                                                          this.valuesAt));
        const fixed = new Int32Array(e.memory.buffer, this.valuesAt, this.channels);
        return format === 'fixed' ? fixed.slice() : fromFixed(fixed);
    }

    /**
       The value at lattice point (x, y) (integers, as for point()) with its gradient, the forward
        differences dx = F(x + 1, y) - F(x, y) and dy = F(x, y + 1) - F(x, y) of the noise before its
        rounding (dsn_lattice_gradient_fixed; on a periodic axis too): { value, dx, dy }, each of
        `channels` values. options.format: 'number' (the default: Float64Array, exactly the runtime's
        Q16.16 / 65536; `value` is what point() gives), 'fixed' (Int32Array: the Q16.16 integers) or
        'float32' (Float32Array: dsn_lattice_gradient_float, each fixed value rounded to float).
     */
    gradient(x, y, options = {}) {
        this.checkConfigured();
        checkLattice('x', x);
        checkLattice('y', y);
        const format = checkFormat(options, POINT_FORMATS);
        const e = this.exports, [out, dx, dy] = this.gradientSlots();
        const call = format === 'float32' ? e.dsn_lattice_gradient_float : e.dsn_lattice_gradient_fixed;
        check(e, call(this.noiseAt, x | 0, y | 0, out, dx, dy));
        return this.readGradient(format, out, dx, dy, this.channels);
    }

    /**
       The value at the continuous point (x, y) in texels (finite numbers, as for continuousPoint()) with
        its exact derivatives per texel along x and y (dsn_continuous_gradient_fixed: the bilinear noise
        is piecewise linear, and on a texel edge of some impulse the slope given is that toward +x or
        +y): { value, dx, dy }, each of `channels` values. options.format as for gradient() ('float32':
        dsn_continuous_gradient_float, from the same coordinates).
     */
    continuousGradient(x, y, options = {}) {
        this.checkConfigured();
        checkFinite('x', x);
        checkFinite('y', y);
        const format = checkFormat(options, POINT_FORMATS);
        const e = this.exports, [out, dx, dy] = this.gradientSlots();
        if (format === 'float32')
            check(e, e.dsn_continuous_gradient_float(this.noiseAt, x, y, out, dx, dy));
        else
            check(e, e.dsn_continuous_gradient_fixed(this.noiseAt, e.dsn_coordinate_from_double(x),
                                                     e.dsn_coordinate_from_double(y), out, dx, dy));
        return this.readGradient(format, out, dx, dy, this.channels);
    }

    /**
       The values and gradients of a width x height tile, exactly the per-point results:
        { value, dx, dy }, each of width x height x `channels` values (row by row, channels
        interleaved). The window as for tile(): without `view` the lattice tile at the integer point
        (x, y) (gradient()'s forward differences), with view = { scale, rotate } the continuous grid
        (continuousGradient()'s derivatives, per texel of the noise, not per pixel of the grid).
        width x height at most 2^22. options.format: 'float32' (the default: Float32Array, the runtime's
        float tiles) or 'fixed' (Int32Array: the Q16.16 integers).
     */
    gradientTile(x, y, width, height, view = null, options = {}) {
        this.checkConfigured();
        const e = this.exports;
        checkTile(x, y, width, height, view, MAX_GRADIENT_TILE_PIXELS, 'a gradient tile');
        const format = checkFormat(options, TILE_FORMATS), float = format === 'float32';
        const count = width * height * this.channels, stride = align(4 * count, 16);
        const out = this.workAt, dx = out + stride, dy = dx + stride;
        this.ensure(dy + stride);
        let err;
        if (view === null) {
            const call = float ? e.dsn_lattice_tile_gradient_float : e.dsn_lattice_tile_gradient_fixed;
            err = call(this.noiseAt, x | 0, y | 0, width, height, out, dx, dy);
        } else {
            this.writeGrid(x, y, view);
            const call = float ? e.dsn_continuous_tile_gradient_float : e.dsn_continuous_tile_gradient_fixed;
            err = call(this.noiseAt, this.gridAt, width, height, out, dx, dy);
        }
        check(e, err);
        return this.readGradient(format, out, dx, dy, count);
    }

    // The three output blocks of a point's gradient.
    gradientSlots() { return [this.gradientAt, this.gradientAt + 16, this.gradientAt + 32]; }

    // { value, dx, dy } read from the three arrays of `count` values at out, dx, dy, as copies.
    readGradient(format, out, dx, dy, count) {
        const buffer = this.exports.memory.buffer;
        const read = (at) => {
            if (format === 'float32') return new Float32Array(buffer, at, count).slice();
            const fixed = new Int32Array(buffer, at, count);
            return format === 'fixed' ? fixed.slice() : fromFixed(fixed);
        };
        return { value: read(out), dx: read(dx), dy: read(dy) };
    }

    /**
       A width x height tile as RGBA bytes (alpha 255, grey repeated in R, G, B), ready for ImageData.
        Without `view`: the lattice tile whose top-left pixel is the point (x, y) (integers, as for
        point()). With view = { scale, rotate }: the continuous grid from (x, y) in texels (finite
        numbers) where one pixel steps 1/scale texels (scale within [1/65536, 65536], as dsn-render
        --scale), rotated by `rotate` degrees counterclockwise (finite; as dsn-render --mode continuous).
        width and height: integers of at least 1, width x height at most 2^26.
     */
    tile(x, y, width, height, view = null) {
        this.checkConfigured();
        const e = this.exports;
        checkTile(x, y, width, height, view);
        const count = width * height * this.channels;
        let scratchSize, call;
        if (view === null) {
            scratchSize = e.dsn_lattice_tile_scratch_size(this.noiseAt, width, height) >>> 0;
            call = (out, scratch) =>
                e.dsn_lattice_tile_u8(this.noiseAt, x | 0, y | 0, width, height, out, scratch, scratchSize);
        } else {
            this.writeGrid(x, y, view);
            scratchSize = e.dsn_continuous_tile_scratch_size(this.noiseAt, this.gridAt, width, height) >>> 0;
            call = (out, scratch) =>
                e.dsn_continuous_tile_u8(this.noiseAt, this.gridAt, width, height, out, scratch, scratchSize);
        }
        const out = this.workAt, scratch = align(out + count, 16);
        this.ensure(scratch + scratchSize);
        check(e, call(out, scratch));
        return toRGBA(new Uint8Array(e.memory.buffer, out, count), this.channels, width * height);
    }

    writeGrid(x, y, view) { writeGrid(this.exports, this.gridAt, x, y, view); }

    // After a failed dsn_noise_init the noise is zeroed and per-point calls would write nothing.
    checkConfigured() {
        if (this.settings === null) throw new Error('dsn: the texture has no valid settings (configure failed)');
    }

    ensure(end) {
        const memory = this.exports.memory;
        if (end > memory.buffer.byteLength) memory.grow(Math.ceil((end - memory.buffer.byteLength) / PAGE));
    }
}

/**
   A mix of materials in one WebAssembly instance: the materials' assets and noises, the configured mix,
    and its weights, each kept at a fixed place of the instance's memory; then one work area.
 */
export class Mix {
    constructor(exports, assets, settings, weights) {
        this.exports = exports;
        let at = align(exports.__heap_base.value >>> 0, 16);
        const reserve = (size) => {
            const start = at;
            at = align(at + size, 16);
            return start;
        };
        const assetBytes = exports.dsn_web_asset_bytes() >>> 0;
        this.materials = assets.map((bytes) => ({
            assetAt: reserve(assetBytes), noiseAt: reserve(NOISE_BYTES), bytesAt: reserve(bytes.length), bytes
        }));
        this.listAt = reserve(4 * MIX_MAX_MATERIALS); // the noises' pointers
        this.mixAt = reserve(MIX_BYTES);
        this.controlAt = reserve(CONTROL_BYTES);
        this.configAt = reserve(CONFIG_BYTES);
        this.gridAt = reserve(GRID_BYTES);
        this.valuesAt = reserve(16);
        this.weightsAt = at;
        this.workAt = at;
        this.ensure(at);
        for (const material of this.materials) {
            new Uint8Array(exports.memory.buffer, material.bytesAt, material.bytes.length).set(material.bytes);
            check(exports, exports.dsn_asset_load(material.assetAt, material.bytesAt, material.bytes.length));
        }
        this.configure(settings);
        this.setWeights(weights);
    }

    /** As Texture.configure, for every material; the mix is made again. */
    configure(settings = {}) {
        const { seed, impacts, period, colorTransform } = writeConfig(this.exports, this.configAt, settings);
        const e = this.exports, list = new Uint32Array(e.memory.buffer, this.listAt, MIX_MAX_MATERIALS);
        this.settings = null;
        this.materials.forEach((material, m) => {
            check(e, e.dsn_noise_init(material.noiseAt, material.assetAt, this.configAt));
            list[m] = material.noiseAt;
        });
        check(e, e.dsn_mix_init(this.mixAt, this.listAt, this.materials.length));
        /** 3 when any material has 3 channels, else 1. */
        this.channels = e.dsn_mix_channels(this.mixAt);
        this.settings = { seed, density: impacts ? impacts / 65536 : null, period: [period[0], period[1]], colorTransform };
        return this;
    }

    /**
       The weights: { data, width, height, shift, origin, periodic }. data: a Uint8Array of width x height
        samples (row by row, top row first), each one byte per material in the mix's order (any scale:
        they are normalized where read; where all are 0, the first material); width and height: integers
        1 .. 65535, their product at most 2^24; shift: samples 2^shift texels apart, 0 .. 16 (default 0);
        origin: [x, y], the texel of sample (0, 0), integers (default [0, 0]); periodic: [px, py], whether
        the grid repeats along x and y (default [false, false]; else its edges extend it).
     */
    setWeights(weights) {
        checkNames('weights', weights, ['data', 'width', 'height', 'shift', 'origin', 'periodic']);
        const { data, width, height, shift = 0, origin = [0, 0], periodic = [false, false] } = weights;
        checkInteger('weights.width', width, 1, 65535);
        checkInteger('weights.height', height, 1, 65535);
        if (width * height > 1 << 24)
            throw new RangeError(`dsn: weights of at most 2^24 samples, not ${width}x${height}`);
        checkInteger('weights.shift', shift, 0, 16);
        if (!(data instanceof Uint8Array) || data.length !== width * height * this.materials.length)
            throw new TypeError(`dsn: weights.data must be a Uint8Array of ${width} x ${height} x ` +
                                `${this.materials.length} bytes`);
        if (!Array.isArray(origin) || origin.length !== 2)
            throw new TypeError(`dsn: weights.origin must be an array [x, y], not ${describe(origin)}`);
        checkInteger('weights.origin[0]', origin[0], -2147483648, 2147483647);
        checkInteger('weights.origin[1]', origin[1], -2147483648, 2147483647);
        if (!Array.isArray(periodic) || periodic.length !== 2 || periodic.some((p) => typeof p !== 'boolean'))
            throw new TypeError('dsn: weights.periodic must be an array of two booleans');
        this.workAt = align(this.weightsAt + data.length, 16);
        this.ensure(this.workAt);
        const e = this.exports;
        new Uint8Array(e.memory.buffer, this.weightsAt, data.length).set(data);
        const words = new DataView(e.memory.buffer, this.controlAt, CONTROL_BYTES);
        words.setUint32(0, this.weightsAt, true);
        words.setUint32(4, width, true);
        words.setUint32(8, height, true);
        words.setUint32(12, shift, true);
        words.setInt32(16, origin[0], true);
        words.setInt32(20, origin[1], true);
        words.setUint32(24, (periodic[0] ? 1 : 0) | (periodic[1] ? 2 : 0), true);
        return this;
    }

    /** The values at lattice point (x, y): Float64Array of `channels` values, as Texture.point. */
    point(x, y) {
        checkLattice('x', x);
        checkLattice('y', y);
        const e = this.exports;
        check(e, e.dsn_mix_lattice_point_fixed(this.mixAt, this.controlAt, x | 0, y | 0, this.valuesAt));
        return fromFixed(new Int32Array(e.memory.buffer, this.valuesAt, this.channels));
    }

    /** The values at the continuous point (x, y) in texels, as Texture.continuousPoint. */
    continuousPoint(x, y) {
        checkFinite('x', x);
        checkFinite('y', y);
        const e = this.exports;
        check(e, e.dsn_mix_continuous_point_fixed(this.mixAt, this.controlAt, e.dsn_coordinate_from_double(x),
                                                  e.dsn_coordinate_from_double(y), this.valuesAt));
        return fromFixed(new Int32Array(e.memory.buffer, this.valuesAt, this.channels));
    }

    /** A width x height tile as RGBA bytes, the window as for Texture.tile (lattice, or a view). */
    tile(x, y, width, height, view = null) {
        const e = this.exports;
        checkTile(x, y, width, height, view);
        const count = width * height * this.channels;
        let scratchSize, call;
        if (view === null) {
            scratchSize = e.dsn_mix_lattice_tile_scratch_size(this.mixAt, width, height) >>> 0;
            call = (out, scratch) => e.dsn_mix_lattice_tile_u8(this.mixAt, this.controlAt, x | 0, y | 0, width,
                                                               height, out, scratch, scratchSize);
        } else {
            writeGrid(e, this.gridAt, x, y, view);
            scratchSize = e.dsn_mix_continuous_tile_scratch_size(this.mixAt, this.gridAt, width, height) >>> 0;
            call = (out, scratch) => e.dsn_mix_continuous_tile_u8(this.mixAt, this.controlAt, this.gridAt, width,
                                                                  height, out, scratch, scratchSize);
        }
        const out = this.workAt, scratch = align(out + count, 16);
        this.ensure(scratch + scratchSize);
        check(e, call(out, scratch));
        return toRGBA(new Uint8Array(e.memory.buffer, out, count), this.channels, width * height);
    }

    ensure(end) {
        const memory = this.exports.memory;
        if (end > memory.buffer.byteLength) memory.grow(Math.ceil((end - memory.buffer.byteLength) / PAGE));
    }
}

// The settings of Texture.configure checked and written as a dsn_config at configAt (five uint32); returns
// them, the density as impacts_q16 (0: the asset's).
function writeConfig(exports, configAt, settings) {
    checkNames('settings', settings, ['seed', 'density', 'period', 'colorTransform']);
    const { seed = 0, density = 0, period = [0, 0], colorTransform = true } = settings;
    checkInteger('seed', seed, 0, UINT32_MAX);
    checkNumber('density', density);
    const impacts = Math.round(density * 65536);
    if (density !== 0 && !(density >= 1 / 16 && density <= 1024 && impacts >= IMPACTS_MIN_Q16 &&
                           impacts <= IMPACTS_MAX_Q16))
        throw new RangeError('dsn: density must be 0 (the asset\'s) or within [1/16, 1024] impacts per ' +
                             `pixel, not ${density}`);
    if (!Array.isArray(period) || period.length !== 2)
        throw new TypeError(`dsn: period must be an array [px, py], not ${describe(period)}`);
    checkInteger('period[0]', period[0], 0, UINT32_MAX);
    checkInteger('period[1]', period[1], 0, UINT32_MAX);
    if (typeof colorTransform !== 'boolean')
        throw new TypeError(`dsn: colorTransform must be true or false, not ${describe(colorTransform)}`);
    const words = new Uint32Array(exports.memory.buffer, configAt, CONFIG_BYTES / 4);
    words[0] = seed;
    words[1] = impacts;
    words[2] = period[0];
    words[3] = period[1];
    words[4] = FLAG_ALLOW_LATTICE_CONTINUOUS | (colorTransform ? 0 : FLAG_NO_COLOR_TRANSFORM);
    return { seed, impacts, period, colorTransform };
}

// A tile's window: width and height integers of at least 1, at most `most` pixels in all (`what` names
// the tile); (x, y) a lattice point without a view, finite texels with one.
function checkTile(x, y, width, height, view, most = MAX_TILE_PIXELS, what = 'a tile') {
    checkInteger('width', width, 1, most);
    checkInteger('height', height, 1, most);
    if (width * height > most) throw new RangeError(`dsn: ${what} is at most ${most} pixels, not ${width}x${height}`);
    if (view === null) {
        checkLattice('x', x);
        checkLattice('y', y);
    } else {
        checkFinite('x', x);
        checkFinite('y', y);
        checkView(view);
    }
}

// The grid of a tile's view at gridAt: Q32.32 coordinates computed as dsn-render computes them (origin by
// the runtime's conversion, steps rounded to the nearest 2^-32 texel).
function writeGrid(exports, gridAt, x, y, { scale = 1, rotate = 0 }) {
    const radians = rotate * Math.PI / 180;
    const cosine = Math.cos(radians) / scale, sine = Math.sin(radians) / scale;
    const step = (texels) => BigInt(Math.round(texels * Q32_ONE));
    const grid = new BigInt64Array(exports.memory.buffer, gridAt, GRID_BYTES / 8);
    grid[0] = exports.dsn_coordinate_from_double(x);
    grid[1] = exports.dsn_coordinate_from_double(y);
    grid[2] = step(cosine);
    grid[3] = step(sine);
    grid[4] = step(-sine);
    grid[5] = step(cosine);
}

// The checks of the module's edge: TypeError for a value of the wrong type, RangeError for one out of range.
function describe(value) {
    if (typeof value === 'string') return JSON.stringify(value);
    return Array.isArray(value) ? 'an array' : String(value);
}

function checkNumber(name, value) {
    if (typeof value !== 'number')
        throw new TypeError(`dsn: ${name} must be a number, not ${describe(value)}`);
}

function checkFinite(name, value) {
    checkNumber(name, value);
    if (!Number.isFinite(value)) throw new RangeError(`dsn: ${name} must be a finite number, not ${value}`);
}

// A footprint in the tangent plane (Texture.surfacePoint): { x: [u, v], y: [u, v], maxTaps }, checked.
function checkFootprint(footprint) {
    checkNames('options.footprint', footprint, ['x', 'y', 'maxTaps']);
    for (const axis of ['x', 'y']) {
        const step = footprint[axis];
        if (!Array.isArray(step) || step.length !== 2)
            throw new TypeError(`dsn: options.footprint.${axis} must be an array of two numbers`);
        step.forEach((value, i) => checkFinite(`options.footprint.${axis}[${i}]`, value));
    }
    const { maxTaps = 1 } = footprint;
    checkInteger('options.footprint.maxTaps', maxTaps, 1, FILTER_MAX_TAPS);
    return { x: footprint.x, y: footprint.y, maxTaps };
}

function checkInteger(name, value, minimum, maximum) {
    checkNumber(name, value);
    if (!(Number.isInteger(value) && value >= minimum && value <= maximum))
        throw new RangeError(`dsn: ${name} must be an integer within [${minimum}, ${maximum}], not ${value}`);
}

// A lattice coordinate: any integer JavaScript holds exactly, taken modulo 2^32 by `| 0`.
function checkLattice(name, value) {
    checkNumber(name, value);
    if (!Number.isSafeInteger(value))
        throw new RangeError(`dsn: ${name} must be an integer (a lattice point), not ${value}`);
}

function checkNames(what, object, names) {
    if (object === null || typeof object !== 'object' || Array.isArray(object))
        throw new TypeError(`dsn: ${what} must be an object, not ${describe(object)}`);
    for (const name of Object.keys(object))
        if (!names.includes(name))
            throw new TypeError(`dsn: unknown ${what === 'settings' ? 'setting' : what.replace(/s$/, '')} ` +
                                `'${name}' (known: ${names.join(', ')})`);
}

// options = { format, and otherNames }: format one of `formats` (the first by default).
function checkFormat(options, formats, otherNames = []) {
    checkNames('options', options, ['format', ...otherNames]);
    const { format = formats[0] } = options;
    if (typeof format !== 'string')
        throw new TypeError(`dsn: options.format must be a string, not ${describe(format)}`);
    if (!formats.includes(format))
        throw new RangeError(`dsn: options.format must be one of ` +
                             `${formats.map((f) => `'${f}'`).join(', ')}, not ${describe(format)}`);
    return format;
}

function checkView(view) {
    checkNames('view', view, ['scale', 'rotate']);
    const { scale = 1, rotate = 0 } = view;
    checkNumber('view.scale', scale);
    if (!(scale >= SCALE_MIN && scale <= SCALE_MAX))
        throw new RangeError(`dsn: view.scale must be within [1/65536, 65536], not ${scale}`);
    checkFinite('view.rotate', rotate);
}

function check(exports, code) {
    if (code !== 0) throw new DsnError(code, readString(exports.memory, exports.dsn_error_message(code)));
}

function readString(memory, pointer) {
    const bytes = new Uint8Array(memory.buffer, pointer >>> 0); // wasm32 pointers arrive signed
    return new TextDecoder().decode(bytes.subarray(0, bytes.indexOf(0)));
}

function toBytes(bytes) {
    if (bytes instanceof ArrayBuffer) return new Uint8Array(bytes);
    if (ArrayBuffer.isView(bytes)) return new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    throw new TypeError('dsn: an asset is a Uint8Array or an ArrayBuffer');
}

function fromFixed(values) { return Float64Array.from(values, (value) => value / 65536); }

function toRGBA(values, channels, pixels) {
    const rgba = new Uint8ClampedArray(pixels * 4);
    if (channels === 3) {
        for (let p = 0, q = 0; p < pixels; p++, q += 3) {
            rgba[4 * p] = values[q];
            rgba[4 * p + 1] = values[q + 1];
            rgba[4 * p + 2] = values[q + 2];
            rgba[4 * p + 3] = 255;
        }
    } else {
        for (let p = 0; p < pixels; p++) {
            const v = values[p];
            rgba[4 * p] = v;
            rgba[4 * p + 1] = v;
            rgba[4 * p + 2] = v;
            rgba[4 * p + 3] = 255;
        }
    }
    return rgba;
}

function align(value, to) { return Math.ceil(value / to) * to; }
