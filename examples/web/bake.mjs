// bake.mjs - the baker in JavaScript: runs dsn-bake.wasm (offline/ compiled for wasm32-wasi, see
// examples/web/bake/) on the bytes of an exemplar image and returns the bytes of a .dsnt asset, baked for
// the continuous mode (bilinear). Each bake gets a fresh instance (a baker error stops the module).
// Bakes take seconds: call it from a worker in a page (bake_worker.js).
//
//   import { loadBaker } from './bake.mjs';
//   const baker = await loadBaker(new URL('dsn-bake.wasm', import.meta.url));
//   const asset = baker.bake(pngBytes, { radius: 0, iterations: 0, seed: 0 }); // Uint8Array; throws
//   BakeError

import { compileModule } from './dsn.mjs';

/** A refusal or failure of the baker: `message` is its own (what() of the exception it threw). */
export class BakeError extends Error {
    constructor(message) {
        super(message);
        this.name = 'BakeError';
    }
}

/** Compiles dsn-bake.wasm once: `source` as for loadRuntime (a URL, the bytes, or a WebAssembly.Module). */
export async function loadBaker(source) {
    return new Baker(await compileModule(source));
}

const WASI_ERRNO_BADF = 8;

export class Baker {
    constructor(module) { this.module = module; }

    /**
       Bakes `image` (Uint8Array: the bytes of a file in a format dsn-bake reads: PNG of 8 or 16 bits,
        JPEG, or binary PGM/PPM; BMP, GIF, TGA, WebP and the others are refused with a BakeError naming
        the format). radius 0: the largest up to 15 that the image allows; iterations 0: the baker's
        default. Returns the asset's bytes.
     */
    bake(image, { radius = 0, iterations = 0, seed = 0 } = {}) {
        let memory = null, error = null, output = '';
        const text = (pointer, size) =>
            new TextDecoder().decode(new Uint8Array(memory.buffer, pointer >>> 0, size >>> 0));
        const imports = {
            env: { bake_error: (pointer, size) => (error = text(pointer, size)) },
            // The baker touches no file; whatever it prints (stdio) is kept for the error message.
            wasi_snapshot_preview1: {
                fd_write(fd, iovs, count, written) {
                    const view = new DataView(memory.buffer);
                    let total = 0;
                    for (let i = 0; i < count; i++) {
                        const pointer = view.getUint32(iovs + 8 * i, true),
                              size = view.getUint32(iovs + 8 * i + 4, true);
                        output += text(pointer, size);
                        total += size;
                    }
                    view.setUint32(written, total, true);
                    return 0;
                },
                fd_close: () => WASI_ERRNO_BADF,
                fd_seek: () => WASI_ERRNO_BADF,
            },
        };
        const exports = new WebAssembly.Instance(this.module, imports).exports;
        memory = exports.memory;
        exports._initialize();
        const bytes = image instanceof ArrayBuffer ? new Uint8Array(image) : image;
        const input = exports.dsn_web_malloc(bytes.length) >>> 0;
        const sizeAt = exports.dsn_web_malloc(4) >>> 0;
        if (!input || !sizeAt) throw new BakeError('out of memory for the image');
        new Uint8Array(memory.buffer, input, bytes.length).set(bytes);
        let asset;
        try {
            asset = exports.dsn_web_bake(input, bytes.length, radius, iterations, seed >>> 0, sizeAt) >>> 0;
        } catch (trap) {
            throw new BakeError(error || output.trim() || `the baker stopped: ${trap.message}`);
        }
        if (!asset) throw new BakeError('out of memory for the asset');
        const size = new DataView(memory.buffer).getUint32(sizeAt, true);
        return new Uint8Array(memory.buffer, asset, size).slice();
    }
}
