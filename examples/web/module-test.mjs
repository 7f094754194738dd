// module-test.mjs - checks of the JavaScript module (dsn.mjs) under Node against the native runtime, as
// dsn-render writes it: lattice and continuous tiles (with a rotation, a period, a density and the largest
// seed), lattice and continuous points, and the loader's errors. Run by examples/web/web-test.
// With the baker (dsn-bake.wasm and an exemplar image), also bake.mjs: a bake that loads, refusals.
// Usage: node module-test.mjs dsn.wasm ASSET.dsnt DSN-RENDER OUT-FOLDER [dsn-bake.wasm EXEMPLAR]
import {execFileSync} from 'node:child_process';
import {createHash} from 'node:crypto';
import {readFileSync} from 'node:fs';
import {join} from 'node:path';

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
