// bake_worker.js - bakes an exemplar image into a .dsnt asset off the main thread (a module worker that
// page.js starts on the first image it is given): {image, name} -> {asset, name, ms} or {error, name}.
import {loadBaker} from './bake.mjs';

let baker = null;

self.onmessage = async ({ data }) => {
    try {
        if (baker === null) baker = await loadBaker(new URL('dsn-bake.wasm', import.meta.url));
        const start = performance.now();
        const asset = baker.bake(data.image);
        self.postMessage({ asset, name: data.name, ms: performance.now() - start }, [asset.buffer]);
    } catch (error) {
        self.postMessage({ error: error.message, name: data.name });
    }
};
