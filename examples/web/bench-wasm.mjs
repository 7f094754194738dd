// bench-wasm.mjs - wasm tile throughput against native in the same run: 256 x 256 tiles of the demo
// asset on one thread, lattice and continuous, through dsn.mjs under Node (texture.tile(): the runtime's
// 8-bit tile plus its expansion to RGBA) and through the native runtime (dsn-web-bench-native, whichever
// copy of the tile code the CPU gets). Rounds alternate native and wasm; the best of each is kept.
// Usage: node bench-wasm.mjs dsn.wasm ASSET.dsnt DSN-WEB-BENCH-NATIVE [SECONDS-PER-ROUND]
import {execFileSync} from 'node:child_process';
import {readFileSync} from 'node:fs';

import {loadRuntime} from './dsn.mjs';

const [wasmPath, assetPath, nativePath, secondsText = '1'] = process.argv.slice(2);
if (!nativePath) {
    console.error('usage: node bench-wasm.mjs dsn.wasm ASSET.dsnt DSN-WEB-BENCH-NATIVE [SECONDS-PER-ROUND]');
    process.exit(2);
}
const seconds = Number(secondsText), rounds = 3, side = 256;
const runtime = await loadRuntime(readFileSync(wasmPath));
const texture = runtime.load(readFileSync(assetPath), { seed: 1 });

function wasmRate(continuous) {
    const start = performance.now();
    let tiles = 0, elapsed = 0;
    for (; elapsed < seconds * 1000; tiles++) {
        texture.tile(tiles * side, 0, side, side, continuous ? { scale: 1 } : null);
        elapsed = performance.now() - start;
    }
    return (tiles * side * side) / (elapsed / 1000) / 1e6;
}

console.log(
    `web: ${side}x${side} tiles of ${assetPath}, one thread, best of ${rounds} rounds of ${seconds} s`);
for (const mode of ['lattice', 'continuous']) {
    let native = 0, wasm = 0;
    for (let round = 0; round < rounds; round++) {
        native =
            Math.max(native, Number(execFileSync(nativePath, [assetPath, mode, String(seconds)]).toString()));
        wasm = Math.max(wasm, wasmRate(mode === 'continuous'));
    }
    console.log(`  ${mode.padEnd(10)}  native ${native.toFixed(2).padStart(7)} Mpixel/s  wasm ` +
                `${wasm.toFixed(2).padStart(7)} Mpixel/s  wasm/native ${(wasm / native).toFixed(3)}`);
}
