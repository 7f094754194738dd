// tile_worker.js - renders the page's tiles off the main thread (a module worker; page.js starts a few).
// It holds its own texture (its own copy of the runtime's memory) and answers, in order:
//   {type: 'asset', module, bytes, settings}  -> {type: 'asset', generation} or {type: 'error', message}
//   {type: 'tile', key, generation, x, y, size, scale} -> {type: 'tile', key, generation, rgba, size, ms}
// `module` is the compiled dsn.wasm (a WebAssembly.Module, sent once by the page), `generation` tells the
// page which asset and settings a tile belongs to, so it can drop answers that arrive late.
import {Runtime} from './dsn.mjs';

let runtime = null;
let texture = null;
let generation = -1;

self.onmessage = ({ data }) => {
    try {
        if (data.type === 'asset') {
            if (data.module) runtime = new Runtime(data.module);
            texture = null;
            texture = runtime.load(data.bytes, data.settings);
            generation = data.generation;
            self.postMessage({ type: 'asset', generation });
        } else if (data.type === 'tile') {
            if (data.generation !== generation || texture === null) {
                self.postMessage({ type: 'tile', key: data.key, generation: data.generation, rgba: null });
                return;
            }
            const start = performance.now();
            const rgba = texture.tile(data.x, data.y, data.size, data.size, { scale: data.scale });
            const ms = performance.now() - start;
            self.postMessage({ type: 'tile', key: data.key, generation, rgba, size: data.size, ms },
                             [rgba.buffer]);
        }
    } catch (error) {
        self.postMessage(
            { type: 'error', key: data.key, generation: data.generation, message: error.message });
    }
};
