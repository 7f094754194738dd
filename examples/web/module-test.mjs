// module-test.mjs - checks of the JavaScript module (dsn.mjs) under Node against the native runtime, as
// dsn-render writes it: lattice and continuous tiles (with a rotation, a period, a density and the largest
// seed), lattice and continuous points, gradients and surface points (against dsn-web-gradient-native,
// which must lie beside dsn-render), mixes (against dsn-render --mix, with dsn-example-asset beside it), and the loader's errors. Run by examples/web/web-test.
// With the baker (dsn-bake.wasm and an exemplar image), also bake.mjs: a bake that loads, refusals.
// Usage: node module-test.mjs dsn.wasm ASSET.dsnt DSN-RENDER OUT-FOLDER [dsn-bake.wasm EXEMPLAR]
import {execFileSync} from 'node:child_process';
import {createHash} from 'node:crypto';
import {readFileSync, writeFileSync} from 'node:fs';
import {dirname, join} from 'node:path';

import {BakeError, loadBaker} from './bake.mjs';
import {DsnError, loadRuntime} from './dsn.mjs';

const [wasmPath, assetPath, renderPath, outFolder, bakerPath, exemplarPath] = process.argv.slice(2);
if (!outFolder) {
    console.error('usage: node module-test.mjs dsn.wasm ASSET.dsnt DSN-RENDER OUT-FOLDER');
    process.exit(2);
}
let failures = 0;
const check = (name, ok, detail = '') => {
    console.log(`module-test: ${name}: ${ok ? 'passed' : `FAILED ${detail}`}`);
    if (!ok) failures++;
};

// dsn-render's output for a window: RGB hash of its PNG, or its float32 values.
const render = (name, args) => {
    const file = join(outFolder, name);
    execFileSync(renderPath, [assetPath, '-o', file, '--quiet', ...args]);
    return file;
};
const pngHash = (file) =>
    execFileSync(process.execPath, [new URL('png-hash.mjs', import.meta.url).pathname, file])
        .toString()
        .trim();
const rgbHash = (rgba) => {
    const rgb = new Uint8Array((rgba.length / 4) * 3);
    for (let p = 0, q = 0; p < rgba.length; p += 4, q += 3) rgb.set(rgba.subarray(p, p + 3), q);
    return createHash('sha256').update(rgb).digest('hex');
};
const floats = (file) => {
    const bytes = readFileSync(file);
    return new Float32Array(bytes.buffer, bytes.byteOffset, bytes.length / 4);
};

const runtime = await loadRuntime(readFileSync(wasmPath));
const bytes = readFileSync(assetPath);
const texture = runtime.load(bytes);
check('version', /^\d+\.\d+\.\d+$/.test(runtime.version), runtime.version);
check('asset fields',
      (texture.channels === 1 || texture.channels === 3) && texture.textonWidth % 2 === 1 &&
          texture.defaultDensity > 0,
      JSON.stringify(texture));

// Tiles against dsn-render, over several settings.
const cases = [
    {
        name: 'lattice tile',
        settings: { seed: 3 },
        window: [-70, 41, 100, 60],
        view: null,
        args: ['--seed', '3', '--mode', 'tile', '--origin', '-70,41', '--size', '100x60']
    },
    {
        name: 'lattice tile, largest seed, density 10, period 16x8',
        settings: { seed: 0xffffffff, density: 10, period: [16, 8] },
        window: [2147483600, -5, 90, 40],
        view: null,
        args: [
            '--seed', '4294967295', '--mode', 'tile', '--impacts', '10', '--period', '16x8', '--origin',
            '2147483600,-5', '--size', '90x40'
        ]
    },
    {
        name: 'continuous tile, zoom 1.5, rotated 30 degrees',
        settings: { seed: 11 },
        window: [-12.25, 7.5, 96, 64],
        view: { scale: 1.5, rotate: 30 },
        args: [
            '--seed', '11', '--mode', 'continuous', '--scale', '1.5', '--rotate', '30', '--origin',
            '-12.25,7.5', '--size', '96x64'
        ]
    },
    {
        name: 'continuous tile, zoom 1/4, no colour transform',
        settings: { seed: 5, colorTransform: false },
        window: [1000, -1000, 64, 64],
        view: { scale: 0.25 },
        args: [
            '--seed', '5', '--no-color-transform', '--mode', 'continuous', '--filter', 'none', '--scale',
            '0.25', '--origin', '1000,-1000', '--size', '64x64'
        ]
    },
];
for (const [index, test] of cases.entries()) {
    texture.configure(test.settings);
    const [x, y, width, height] = test.window;
    const page = rgbHash(texture.tile(x, y, width, height, test.view));
    const native = pngHash(render(`module-${index}.png`, test.args));
    check(`${test.name} = dsn-render`, page === native, `${page} != ${native}`);
}

// The period holds in the module's own output, and density changes the texture.
texture.configure({ seed: 9, period: [16, 0] });
const periodic = texture.tile(-8, 3, 48, 4);
let periodHolds = true;
for (let j = 0; j < 4; j++)
    for (let i = 0; i + 16 < 48; i++)
        for (let c = 0; c < 4; c++)
            if (periodic[(j * 48 + i) * 4 + c] !== periodic[(j * 48 + i + 16) * 4 + c]) periodHolds = false;
check('period 16: pixel x + 16 = pixel x', periodHolds);
texture.configure({ seed: 9, density: 5 });
const sparse = rgbHash(texture.tile(0, 0, 32, 32));
texture.configure({ seed: 9, density: 60 });
check('density changes the tile', sparse !== rgbHash(texture.tile(0, 0, 32, 32)));
check('settings read back', texture.seed === 9 && texture.density === 60 && texture.period[0] === 0);

// Points: exactly the fixed-point values, so their float32 rounding is dsn-render's .f32 output.
texture.configure({ seed: 21 });
const latticeValues =
    floats(render('points.f32', ['--seed', '21', '--mode', 'point', '--origin', '-3,-2', '--size', '7x5']));
const continuousValues =
    floats(render('continuous-points.f32',
                  ['--seed', '21', '--mode', 'continuous', '--origin', '0.5,-1.75', '--size', '7x5']));
let latticeSame = true, continuousSame = true;
for (let j = 0; j < 5; j++)
    for (let i = 0; i < 7; i++) {
        const lattice = texture.point(-3 + i, -2 + j),
              continuous = texture.continuousPoint(0.5 + i, -1.75 + j);
        for (let c = 0; c < texture.channels; c++) {
            const at = (j * 7 + i) * texture.channels + c;
            if (Math.fround(lattice[c]) !== latticeValues[at]) latticeSame = false;
            if (Math.fround(continuous[c]) !== continuousValues[at]) continuousSame = false;
        }
    }
check('lattice points = dsn-render --mode point', latticeSame);
check('continuous points = dsn-render --mode continuous', continuousSame);

// Gradients: the native runtime's bits per point (lattice, also across the int32 wrap of a periodic
// axis, and continuous), the value equal to point()'s and continuousPoint()'s, the float32 format the
// fixed values rounded, the tiles equal to the points, the lattice differences within one unit of the
// rounded values' differences.
const gradientNative = join(dirname(renderPath), 'dsn-web-gradient-native');
const nativeGradients = (settings, mode, points) =>
    execFileSync(gradientNative, [
        assetPath, String(settings.seed), String(settings.period?.[0] ?? 0),
        String(settings.period?.[1] ?? 0), mode, ...points.flat().map(String)
    ])
        .toString()
        .trim()
        .split('\n')
        .map((line) => line.split(' ').map(Number));
const sameValues = (a, b) => a.length === b.length && a.every((value, i) => Object.is(value, b[i]));
const gradientCases = [
    { name: 'lattice', settings: { seed: 21 }, mode: 'lattice',
      points: [[-3, -2], [0, 0], [5, 7], [-1, 2147483647], [2147483647, -2147483648]] },
    { name: 'lattice, period 16x8 (across the int32 wrap)', settings: { seed: 21, period: [16, 8] },
      mode: 'lattice', points: [[2147483647, 2147483647], [-2147483648, 2147483647], [15, 7], [-1, -1]] },
    { name: 'continuous', settings: { seed: 21 }, mode: 'continuous',
      points: [[0.5, -1.75], [3.125, 2], [-7.3, 11.9], [1e6 + 0.25, -2.5e5], [0, 0]] },
    { name: 'continuous, period 16x8', settings: { seed: 4, period: [16, 8] }, mode: 'continuous',
      points: [[15.75, 7.5], [-0.25, 3], [2147483647.5, -2147483648.25]] },
];
for (const test of gradientCases) {
    texture.configure(test.settings);
    const lattice = test.mode === 'lattice';
    const native = nativeGradients(test.settings, test.mode, test.points);
    let bits = true, values = true, floats = true, differences = true;
    for (const [k, [x, y]] of test.points.entries()) {
        const gradient = lattice ? (p, q, o) => texture.gradient(p, q, o)
                                 : (p, q, o) => texture.continuousGradient(p, q, o);
        const fixed = gradient(x, y, { format: 'fixed' });
        const n = texture.channels;
        if (!sameValues([...fixed.value, ...fixed.dx, ...fixed.dy], native[k])) bits = false;
        const number = gradient(x, y);
        const point = lattice ? texture.point(x, y) : texture.continuousPoint(x, y);
        if (!sameValues(number.value, point) ||
            !sameValues(number.dx, Float64Array.from(fixed.dx, (v) => v / 65536)))
            values = false;
        const float = gradient(x, y, { format: 'float32' });
        for (const part of ['value', 'dx', 'dy'])
            if (!sameValues(float[part], Float32Array.from(fixed[part], (v) => v / 65536))) floats = false;
        if (lattice) {
            const east = texture.point(x + 1, y), south = texture.point(x, y + 1);
            for (let c = 0; c < n; c++)
                if (Math.abs(fixed.dx[c] - (east[c] - point[c]) * 65536) > 1 ||
                    Math.abs(fixed.dy[c] - (south[c] - point[c]) * 65536) > 1)
                    differences = false;
        }
    }
    check(`gradient, ${test.name}: the native runtime's bits`, bits);
    check(`gradient, ${test.name}: value = the value function, numbers = fixed / 65536`, values);
    check(`gradient, ${test.name}: float32 = dsn_*_gradient_float`, floats);
    if (lattice)
        check(`gradient, ${test.name}: dx, dy within one unit of the values' differences`, differences);
}
{
    texture.configure({ seed: 21 });
    const n = texture.channels, width = 7, height = 5;
    // A lattice tile and a continuous one (steps of half a texel, exact in doubles) against the points.
    const latticeTile = texture.gradientTile(-3, -2, width, height, null, { format: 'fixed' });
    const continuousTile = texture.gradientTile(0.5, -1.75, width, height, { scale: 2 }, { format: 'fixed' });
    const floatTile = texture.gradientTile(0.5, -1.75, width, height, { scale: 2 });
    let latticeSame = true, continuousSame = true, floatSame = true;
    for (let j = 0; j < height; j++)
        for (let i = 0; i < width; i++) {
            const at = (j * width + i) * n;
            const a = texture.gradient(-3 + i, -2 + j, { format: 'fixed' });
            const b = texture.continuousGradient(0.5 + i / 2, -1.75 + j / 2, { format: 'fixed' });
            for (const part of ['value', 'dx', 'dy']) {
                if (!sameValues(latticeTile[part].subarray(at, at + n), a[part])) latticeSame = false;
                if (!sameValues(continuousTile[part].subarray(at, at + n), b[part])) continuousSame = false;
                const rounded = Float32Array.from(b[part], (v) => v / 65536);
                if (!sameValues(floatTile[part].subarray(at, at + n), rounded)) floatSame = false;
            }
        }
    check('gradient tile, lattice = its points', latticeSame);
    check('gradient tile, continuous (scale 2) = its points', continuousSame);
    check('gradient tile, float32 = the fixed points rounded', floatSame);
    // The continuous tile's values are those the RGBA tile shows (dsn_fixed_to_u8 of the same values).
    const rgba = texture.tile(0.5, -1.75, width, height, { scale: 2 });
    const u8 = (v) => (v <= 0 ? 0 : v >= 65536 ? 255 : Math.floor((v * 255 + 32768) / 65536));
    let shown = true;
    for (let p = 0; p < width * height; p++)
        for (let c = 0; c < 3; c++)
            if (rgba[4 * p + c] !== u8(continuousTile.value[p * n + (n === 3 ? c : 0)])) shown = false;
    check('gradient tile values = the RGBA tile', shown);
}

// Surface noise: the native runtime's bits at points of a sphere, the tilted plane and the x axis (where the
// frame from the normal alone turns around), the float32 format the fixed values rounded, and the errors.
{
    const settings = { seed: 13 };
    texture.configure(settings);
    const points = [[40, 0, 0, 1, 0, 0], [0, -40, 0, 0, -1, 0], [3.5, 7.25, -11, 0.3, -0.5, 0.8],
                    [1e6 + 0.5, -2.5e5, 17.75, -1, 2, 0.5], [0.125, 0.25, 0.375, 0, 0, -2]];
    const native = nativeGradients(settings, 'surface', points);
    let bits = true, floats = true;
    for (const [k, point] of points.entries()) {
        const position = point.slice(0, 3), normal = point.slice(3);
        const fixed = texture.surfacePoint(position, normal, null, { format: 'fixed' });
        if (!sameValues([...fixed], native[k])) bits = false;
        const float = texture.surfacePoint(position, normal, null, { format: 'float32' });
        if (!sameValues(float, Float32Array.from(fixed, (v) => v / 65536))) floats = false;
    }
    check('surface point: the native runtime\'s bits', bits);
    check('surface point: float32 = dsn_surface_point_float', floats);
    const refused = (call, kind) => {
        try { call(); } catch (error) { return error instanceof kind; }
        return false;
    };
    check('surface point: a zero normal is refused (DsnError)',
          refused(() => texture.surfacePoint([0, 0, 0], [0, 0, 0]), DsnError));
    check('surface point: a NaN coordinate is refused (RangeError)',
          refused(() => texture.surfacePoint([0, NaN, 0], [0, 0, 1]), RangeError));
    check('surface point: a normal of two numbers is refused (TypeError)',
          refused(() => texture.surfacePoint([0, 0, 0], [0, 1]), TypeError));
}

// Filtered surface noise: the native runtime's bits under footprints in the tangent plane (isotropic,
// anisotropic with taps, under a texel), the float32 format, a texel's footprint giving the point, and the
// footprint's checks.
{
    const settings = { seed: 13 };
    texture.configure(settings);
    const points = [[3.5, 7.25, -11, 0.3, -0.5, 0.8, 2, 0, 0, 2, 1], [40, 0, 0, 1, 0, 0, 1.5, 0.5, -0.5, 6, 8],
                    [0.125, 0.25, 0.375, 0, 0, -2, 0.5, 0, 0, 0.75, 1],
                    [1e6 + 0.5, -2.5e5, 17.75, -1, 2, 0.5, 9, 1, -2, 3, 4]];
    const native = nativeGradients(settings, 'filtered-surface', points);
    let bits = true, floats = true, filtered = false;
    for (const [k, point] of points.entries()) {
        const position = point.slice(0, 3), normal = point.slice(3, 6);
        const footprint = { x: point.slice(6, 8), y: point.slice(8, 10), maxTaps: point[10] };
        const fixed = texture.surfacePoint(position, normal, null, { format: 'fixed', footprint });
        if (!sameValues([...fixed], native[k])) bits = false;
        const float = texture.surfacePoint(position, normal, null, { format: 'float32', footprint });
        if (!sameValues(float, Float32Array.from(fixed, (v) => v / 65536))) floats = false;
        const unfiltered = texture.surfacePoint(position, normal, null, { format: 'fixed' });
        if (!sameValues(fixed, unfiltered)) filtered = true;
    }
    check('filtered surface point: the native runtime\'s bits', bits);
    check('filtered surface point: float32 = dsn_surface_filtered_point_float', floats);
    check('filtered surface point: footprints over a texel filter', filtered);
    const position = [3.5, 7.25, -11], normal = [0.3, -0.5, 0.8];
    check('filtered surface point: a texel\'s footprint gives the point',
          sameValues(texture.surfacePoint(position, normal, null,
                                          { format: 'fixed', footprint: { x: [1, 0], y: [0, 1] } }),
                     texture.surfacePoint(position, normal, null, { format: 'fixed' })));
    const refused = (footprint, kind) => {
        try {
            texture.surfacePoint(position, normal, null, { footprint });
        } catch (error) {
            return error instanceof kind;
        }
        return false;
    };
    check('filtered surface point: a footprint step of one number is refused (TypeError)',
          refused({ x: [1], y: [0, 1] }, TypeError));
    check('filtered surface point: a NaN step is refused (RangeError)', refused({ x: [NaN, 0], y: [0, 1] }, RangeError));
    check('filtered surface point: maxTaps 0 and 17 are refused (RangeError)',
          refused({ x: [1, 0], y: [0, 1], maxTaps: 0 }, RangeError) &&
              refused({ x: [1, 0], y: [0, 1], maxTaps: 17 }, RangeError));
    check('filtered surface point: an unknown footprint setting is refused (TypeError)',
          refused({ x: [1, 0], y: [0, 1], z: [0, 0] }, TypeError));
}

// Mixing: against dsn-render --mix (PNG hashes of a lattice and a continuous window, the weights from a
// grey PGM, 8 texels a pixel), where the weights are the first material's alone the first's own tile, and
// the module's checks of the weights.
{
    const second = join(outFolder, 'second.dsnt');
    execFileSync(join(dirname(renderPath), 'dsn-example-asset'), ['--channels', '1', second]);
    const ramp = [0, 40, 200, 255, 128, 0];
    const pgm = join(outFolder, 'weights.pgm');
    writeFileSync(pgm, Buffer.concat([Buffer.from('P5\n3 2\n255\n'), Buffer.from(ramp)]));
    const data = new Uint8Array(ramp.length * 2);
    ramp.forEach((grey, i) => { data[2 * i] = 255 - grey; data[2 * i + 1] = grey; });
    const weights = { data, width: 3, height: 2, shift: 3 };
    const mix = runtime.mix([bytes, readFileSync(second)], { seed: 6, weights });
    const mixArgs = ['--mix', second, '--weights', pgm, '--weights-shift', '3', '--seed', '6'];
    const lattice = pngHash(render('mix-lattice.png', [...mixArgs, '--size', '40x24', '--origin', '-5,-3',
                                                        '--mode', 'tile']));
    check('mix lattice tile = dsn-render --mix', rgbHash(mix.tile(-5, -3, 40, 24)) === lattice);
    const continuous = pngHash(render('mix-continuous.png', [...mixArgs, '--size', '40x24', '--origin',
                                                             '-5.5,2.25', '--scale', '1.5', '--rotate', '30']));
    check('mix continuous tile = dsn-render --mix',
          rgbHash(mix.tile(-5.5, 2.25, 40, 24, { scale: 1.5, rotate: 30 })) === continuous);
    const one = new Uint8Array(ramp.length * 2);
    for (let i = 0; i < ramp.length; i++) one[2 * i] = 9;
    mix.setWeights({ data: one, width: 3, height: 2, shift: 3, periodic: [true, false] });
    texture.configure({ seed: 6 });
    check('mix with the first material alone = its own tile',
          rgbHash(mix.tile(3, 4, 20, 10, { scale: 0.75 })) === rgbHash(texture.tile(3, 4, 20, 10, { scale: 0.75 })));
    check('mix point = the first material\'s point',
          sameValues(mix.continuousPoint(3.25, -8.5), texture.continuousPoint(3.25, -8.5)) &&
              sameValues(mix.point(-17, 2), texture.point(-17, 2)));
    check('mix channels', mix.channels === Math.max(texture.channels, 1), String(mix.channels));
    const thrown = (f) => {
        try {
            f();
            return null;
        } catch (error) {
            return error;
        }
    };
    check('mix weights: wrong data size -> TypeError',
          thrown(() => mix.setWeights({ data: new Uint8Array(3), width: 3, height: 2 })) instanceof TypeError);
    check('mix weights: shift 17 -> RangeError',
          thrown(() => mix.setWeights({ data: one, width: 3, height: 2, shift: 17 })) instanceof RangeError);
    check('mix weights: unknown name -> TypeError',
          thrown(() => mix.setWeights({ data: one, width: 3, height: 2, spacing: 1 })) instanceof TypeError);
    check('mix of no assets -> RangeError', thrown(() => runtime.mix([], { weights })) instanceof RangeError);
    check('mix without weights -> TypeError', thrown(() => runtime.mix([bytes])) instanceof TypeError);
}

// The loader's errors: codes and messages from the runtime.
const refused = (data) => {
    try {
        runtime.load(data);
        return null;
    } catch (error) {
        return error;
    }
};
const damaged = Uint8Array.from(bytes);
damaged[damaged.length - 1] ^= 0xff; // the checksum itself
const crc = refused(damaged);
check('damaged asset: DsnError CRC',
      crc instanceof DsnError && crc.code === -8 && /checksum/.test(crc.message), String(crc));
const truncated = refused(bytes.subarray(0, 100));
check('truncated asset: DsnError',
      truncated instanceof DsnError && truncated.code === -2 && truncated.message.length > 0,
      String(truncated));
const notAnAsset = refused(new TextEncoder().encode('<html>not an asset</html>'));
check('not an asset: DsnError', notAnAsset instanceof DsnError && notAnAsset.code === -3, String(notAnAsset));
let rangeError = null;
try {
    texture.configure({ density: 5000 });
} catch (error) {
    rangeError = error;
}
check('density out of range refused', rangeError instanceof RangeError);

// Every setting is checked at the module's edge: the wrong type is a TypeError, a value out of range a
// RangeError, each naming the setting (a scale of 0 threw an internal RangeError converting Infinity to
// BigInt, a scale of 1e-12 wrapped its step modulo 2^64, a density of 1e-9 became the asset's 30), and
// the texture keeps its settings.
const refusals = [
    ['scale 0', RangeError, /view\.scale.*\[1\/65536, 65536\]/, () => texture.tile(0, 0, 8, 8, { scale: 0 })],
    ['scale 1e-12', RangeError, /view\.scale/, () => texture.tile(0, 0, 8, 8, { scale: 1e-12 })],
    ['scale -1', RangeError, /view\.scale/, () => texture.tile(0, 0, 8, 8, { scale: -1 })],
    ['scale NaN', RangeError, /view\.scale/, () => texture.tile(0, 0, 8, 8, { scale: NaN })],
    ['scale "2"', TypeError, /view\.scale must be a number/, () => texture.tile(0, 0, 8, 8, { scale: '2' })],
    ['rotate Infinity', RangeError, /view\.rotate/, () => texture.tile(0, 0, 8, 8, { rotate: Infinity })],
    ['view zoom', TypeError, /unknown view 'zoom'/, () => texture.tile(0, 0, 8, 8, { zoom: 2 })],
    ['continuous x NaN', RangeError, /\bx must be a finite number/,
     () => texture.tile(NaN, 0, 8, 8, { scale: 1 })],
    ['lattice x 1.5', RangeError, /\bx must be an integer/, () => texture.tile(1.5, 0, 8, 8)],
    ['tile width 0', RangeError, /width must be an integer within \[1, /, () => texture.tile(0, 0, 0, 8)],
    ['tile 2^14 x 2^13', RangeError, /at most 67108864 pixels/, () => texture.tile(0, 0, 1 << 14, 1 << 13)],
    ['point y "3"', TypeError, /\by must be a number/, () => texture.point(0, '3')],
    ['continuous point Infinity', RangeError, /\bx must be a finite/,
     () => texture.continuousPoint(Infinity, 0)],
    ['density 1e-9', RangeError, /density must be 0 \(the asset's\) or within \[1\/16, 1024\]/,
     () => texture.configure({ density: 1e-9 })],
    ['density -5', RangeError, /density/, () => texture.configure({ density: -5 })],
    ['density NaN', RangeError, /density/, () => texture.configure({ density: NaN })],
    ['seed -1', RangeError, /seed must be an integer within \[0, 4294967295\]/,
     () => texture.configure({ seed: -1 })],
    ['seed 2^32', RangeError, /seed/, () => texture.configure({ seed: 2 ** 32 })],
    ['seed 1.5', RangeError, /seed/, () => texture.configure({ seed: 1.5 })],
    ['seed "7"', TypeError, /seed must be a number/, () => texture.configure({ seed: '7' })],
    ['period [1.5, 0]', RangeError, /period\[0\]/, () => texture.configure({ period: [1.5, 0] })],
    ['period 16', TypeError, /period must be an array/, () => texture.configure({ period: 16 })],
    ['colorTransform "no"', TypeError, /colorTransform must be true or false/,
     () => texture.configure({ colorTransform: 'no' })],
    ['setting seeds', TypeError, /unknown setting 'seeds'/, () => texture.configure({ seeds: 3 })],
    ['settings null', TypeError, /settings must be an object/, () => texture.configure(null)],
    ['gradient x 1.5', RangeError, /\bx must be an integer/, () => texture.gradient(1.5, 0)],
    ['gradient y "1"', TypeError, /\by must be a number/, () => texture.gradient(0, '1')],
    ['continuous gradient NaN', RangeError, /\by must be a finite number/,
     () => texture.continuousGradient(0, NaN)],
    ['gradient format "float64"', RangeError, /options\.format must be one of 'number', 'fixed', 'float32'/,
     () => texture.gradient(0, 0, { format: 'float64' })],
    ['gradient format 1', TypeError, /options\.format must be a string/,
     () => texture.continuousGradient(0, 0, { format: 1 })],
    ['gradient option fmt', TypeError, /unknown option 'fmt'/,
     () => texture.gradient(0, 0, { fmt: 'fixed' })],
    ['gradient options null', TypeError, /options must be an object/, () => texture.gradient(0, 0, null)],
    ['gradient tile format "number"', RangeError, /options\.format must be one of 'float32', 'fixed'/,
     () => texture.gradientTile(0, 0, 8, 8, null, { format: 'number' })],
    ['gradient tile 2^12 x 2^11', RangeError, /gradient tile is at most 4194304 pixels/,
     () => texture.gradientTile(0, 0, 1 << 12, 1 << 11)],
    ['gradient tile height 0', RangeError, /height must be an integer within \[1, /,
     () => texture.gradientTile(0, 0, 8, 0)],
    ['gradient tile scale 0', RangeError, /view\.scale/,
     () => texture.gradientTile(0, 0, 8, 8, { scale: 0 })],
    ['gradient tile lattice x 0.5', RangeError, /\bx must be an integer/,
     () => texture.gradientTile(0.5, 0, 8, 8)],
];
texture.configure({ seed: 4, density: 12 });
const before = rgbHash(texture.tile(0, 0, 16, 16));
for (const [name, type, pattern, call] of refusals) {
    let thrown = null;
    try {
        call();
    } catch (error) {
        thrown = error;
    }
    check(`${name} refused: ${type.name}`, thrown instanceof type && pattern.test(thrown.message),
          thrown ? `${thrown.name}: ${thrown.message}` : 'accepted');
}
check('refused settings leave the texture as it was',
      texture.seed === 4 && texture.density === 12 && rgbHash(texture.tile(0, 0, 16, 16)) === before);

if (bakerPath) {
    // The baker in wasm: its asset loads and has the bake's shape (3 channels for the demo's colour
    // exemplar, a 31 x 31 texton, bilinear); what it refuses comes back as BakeError with its message.
    const baker = await loadBaker(readFileSync(bakerPath));
    const start = performance.now();
    const baked = baker.bake(readFileSync(exemplarPath));
    const seconds = ((performance.now() - start) / 1000).toFixed(1);
    let loaded = null;
    try {
        loaded = runtime.load(baked);
    } catch (error) {
        check('baked asset loads', false, error.message);
    }
    check(`bake of ${exemplarPath} in wasm (${seconds} s, ${baked.length} bytes)`,
          loaded !== null && loaded.channels === 3 && loaded.textonWidth === 31 &&
              loaded.interpolation === 'bilinear',
          loaded ? JSON.stringify(loaded) : '');
    const bakeRefused = (data) => {
        try {
            baker.bake(data);
            return null;
        } catch (error) {
            return error;
        }
    };
    const notImage = bakeRefused(new TextEncoder().encode('not an image'));
    check('baker: not an image -> BakeError',
          notImage instanceof BakeError && /not a readable image/.test(notImage.message), String(notImage));
    // A 4 x 4 PNG: readable, but too small for any texton (both sides must be at least 4r + 1).
    const tiny = readFileSync(render('tiny.png', ['--size', '4x4']));
    const tooSmall = bakeRefused(tiny);
    check('baker: image too small -> BakeError', tooSmall instanceof BakeError && tooSmall.message.length > 0,
          String(tooSmall));
    console.log(`module-test: the baker said: ${tooSmall && tooSmall.message}`);
    // What bake.mjs says it reads is what the baker reads: a BMP is refused by name.
    const bmp = bakeRefused(Uint8Array.from([0x42, 0x4d, 0x36, 0x30, 0, 0, 0, 0, 0, 0, 0x36, 0, 0, 0, 0x28]));
    check('baker: BMP -> BakeError naming BMP', bmp instanceof BakeError && /BMP/.test(bmp.message),
          String(bmp));
}

console.log(`module-test: ${failures} failed`);
process.exit(failures === 0 ? 0 : 1);
