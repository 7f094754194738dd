// page.js - the demo page: an endless, pannable and zoomable canvas of a dsn texture. The plane is cut
// into 256 x 256 pixel tiles per zoom level (level L: one tile pixel is 2^-L texels, evaluated in the
// runtime's continuous mode), rendered by a few Web Workers (tile_worker.js) and cached; between levels
// the cached tiles are drawn scaled, so panning and zooming stay smooth while sharp tiles arrive. A .dsnt
// given to the file picker (or dropped) replaces the texture; a photo is baked first (bake_worker.js).
//
// URL parameters (all optional): asset=FILE.dsnt (default demo.dsnt), seed=S, density=D, and for a fixed
// view x=X&y=Y (top-left texel), zoom=Z (screen pixels per texel), width=W&height=H (canvas pixels).
// With test=1 the page writes the SHA-256 of the canvas's RGB bytes into #canvas-hash once every tile of
// the view is drawn (examples/web/web-test compares it with dsn-render), or the error into #status.
import {loadRuntime} from './dsn.mjs';

const TILE = 256;
const MIN_LEVEL = -3, MAX_LEVEL = 6;
const CACHE_LIMIT = 192; // tiles (256 KiB each)
const JOBS_PER_WORKER = 2;

const parameters = new URLSearchParams(location.search);
const testMode = parameters.get('test') === '1';
const elements = Object.fromEntries([
    'canvas', 'seed', 'new-seed', 'density', 'density-value', 'file', 'reset-view', 'zoom-value', 'status',
    'canvas-hash'
].map((id) => [id, document.getElementById(id)]));
const canvas = elements.canvas;
const context = canvas.getContext('2d', { alpha: false });

const state = {
    runtime: null,
    generation: 0, // bumps with every asset or setting change: older tiles and answers are dropped
    asset: null,   // { bytes, name, texture } of the texture shown
    settings: { seed: 1, density: 0 },
    view: { x: 0, y: 0, zoom: 1 }, // texel at the canvas's top-left corner, screen pixels per texel
    pixelRatio: 1,
    cache: new Map(),   // key -> { bitmap, used }
    pending: new Set(), // keys sent to a worker
    workers: [],
    frame: 0,
    drawQueued: false,
    tileTimes: [],
};

function setStatus(text, isError = false) {
    elements.status.textContent = text;
    elements.status.classList.toggle('error', isError);
}

// The view or the texture changed: the page reports again once the new view is drawn, and until then
// says nothing (a test reading <html data-state> must not take the previous view's answer).
// Without a texture there is no view to report: an error then stays the page's answer.
function viewChanged() {
    state.reported = false;
    if (state.asset) delete document.documentElement.dataset.state;
}

// ---- Workers ----

function startWorkers(module) {
    const count = testMode ? 2 : Math.max(1, Math.min(4, (navigator.hardwareConcurrency || 2) - 1));
    for (let i = 0; i < count; i++) {
        const worker = new Worker(new URL('tile_worker.js', import.meta.url), { type: 'module' });
        const entry = { worker, busy: 0, moduleSent: false };
        worker.onmessage = ({ data }) => onWorkerMessage(entry, data);
        worker.onerror = (event) => setStatus(`tile worker failed: ${event.message}`, true);
        state.workers.push(entry);
    }
    state.module = module;
}

function sendAsset() {
    for (const entry of state.workers) {
        entry.busy = 0;
        entry.worker.postMessage({
            type: 'asset',
            module: entry.moduleSent ? null : state.module,
            bytes: state.asset.bytes,
            settings: state.settings,
            generation: state.generation
        });
        entry.moduleSent = true;
    }
}

function onWorkerMessage(entry, data) {
    if (data.type === 'asset') return;
    if (data.type === 'error') {
        if (data.generation === state.generation) setStatus(data.message, true);
        if (data.key) finishJob(entry, data.key);
        return;
    }
    finishJob(entry, data.key);
    if (data.generation !== state.generation || !data.rgba) return schedule();
    state.tileTimes.push(data.ms);
    if (state.tileTimes.length > 32) state.tileTimes.shift();
    const image = new ImageData(data.rgba, data.size, data.size);
    createImageBitmap(image, { premultiplyAlpha: 'none', colorSpaceConversion: 'none' }).then((bitmap) => {
        if (data.generation !== state.generation) return bitmap.close();
        state.cache.set(data.key, { bitmap, used: state.frame });
        trimCache();
        requestDraw();
    });
    schedule();
}

function finishJob(entry, key) {
    entry.busy = Math.max(0, entry.busy - 1);
    state.pending.delete(key);
}

function trimCache() {
    if (state.cache.size <= CACHE_LIMIT) return;
    const entries = [...state.cache.entries()].sort((a, b) => a[1].used - b[1].used);
    for (const [key, tile] of entries.slice(0, state.cache.size - CACHE_LIMIT)) {
        tile.bitmap.close();
        state.cache.delete(key);
    }
}

// ---- Tiles of the view ----

function level() {
    const scale = state.view.zoom * state.pixelRatio;
    return Math.min(MAX_LEVEL, Math.max(MIN_LEVEL, Math.round(Math.log2(scale))));
}

function tileKey(generation, lvl, column, row) { return `${generation}/${lvl}/${column}/${row}`; }

// The tiles of level `lvl` that cover the canvas, nearest to its centre first.
function visibleTiles(lvl) {
    const { x, y, zoom } = state.view;
    const texelsPerTile = TILE / 2 ** lvl;
    const width = canvas.width / (zoom * state.pixelRatio),
          height = canvas.height / (zoom * state.pixelRatio);
    const c0 = Math.floor(x / texelsPerTile), c1 = Math.floor((x + width) / texelsPerTile - 1e-9);
    const r0 = Math.floor(y / texelsPerTile), r1 = Math.floor((y + height) / texelsPerTile - 1e-9);
    const tiles = [];
    for (let row = r0; row <= r1; row++)
        for (let column = c0; column <= c1; column++) tiles.push({ lvl, column, row, texelsPerTile });
    const cx = (c0 + c1) / 2, cy = (r0 + r1) / 2;
    return tiles.sort((a, b) =>
                          Math.hypot(a.column - cx, a.row - cy) - Math.hypot(b.column - cx, b.row - cy));
}

function schedule() {
    if (!state.asset) return;
    const wanted = visibleTiles(level()).filter((tile) => {
        const key = tileKey(state.generation, tile.lvl, tile.column, tile.row);
        return !state.cache.has(key) && !state.pending.has(key);
    });
    for (const tile of wanted) {
        const entry = state.workers.reduce((best, w) => (w.busy < best.busy ? w : best));
        if (entry.busy >= JOBS_PER_WORKER) break;
        const key = tileKey(state.generation, tile.lvl, tile.column, tile.row);
        entry.busy++;
        state.pending.add(key);
        entry.worker.postMessage({
            type: 'tile',
            key,
            generation: state.generation,
            size: TILE,
            x: tile.column * tile.texelsPerTile,
            y: tile.row * tile.texelsPerTile,
            scale: 2 ** tile.lvl
        });
    }
}

// ---- Drawing ----

function requestDraw() {
    if (state.drawQueued) return;
    state.drawQueued = true;
    requestAnimationFrame(draw);
}

function drawLevel(lvl, onlyCached) {
    const { x, y, zoom } = state.view;
    const scale = zoom * state.pixelRatio;
    let missing = 0;
    for (const tile of visibleTiles(lvl)) {
        const cached = state.cache.get(tileKey(state.generation, lvl, tile.column, tile.row));
        if (!cached) {
            missing++;
            continue;
        }
        cached.used = state.frame;
        // Tile corners are placed on whole pixels where the scale allows it, so a tile drawn at its own
        // level (scale exactly 2^level) is copied pixel for pixel.
        const left = Math.round((tile.column * tile.texelsPerTile - x) * scale);
        const top = Math.round((tile.row * tile.texelsPerTile - y) * scale);
        const right = Math.round(((tile.column + 1) * tile.texelsPerTile - x) * scale);
        const bottom = Math.round(((tile.row + 1) * tile.texelsPerTile - y) * scale);
        context.drawImage(cached.bitmap, left, top, right - left, bottom - top);
    }
    return onlyCached ? 0 : missing;
}

function draw() {
    state.drawQueued = false;
    state.frame++;
    context.fillStyle = '#222';
    context.fillRect(0, 0, canvas.width, canvas.height);
    if (!state.asset) return;
    const lvl = level();
    const exact = state.view.zoom * state.pixelRatio === 2 ** lvl;
    context.imageSmoothingEnabled = !exact;
    context.imageSmoothingQuality = 'medium';
    // Coarser levels first as a backdrop, then finer ones, then the level of the view on top.
    for (const other of [lvl - 2, lvl - 1, lvl + 1]) {
        if (other >= MIN_LEVEL && other <= MAX_LEVEL) {
            context.imageSmoothingEnabled = true;
            drawLevel(other, true);
        }
    }
    context.imageSmoothingEnabled = !exact;
    const missing = drawLevel(lvl, false);
    elements['zoom-value'].textContent = `zoom ${state.view.zoom.toFixed(state.view.zoom < 1 ? 3 : 2)}x`;
    if (missing === 0 && !state.reported) reportView();
    schedule();
}

function reportView() {
    state.reported = true;
    const times = state.tileTimes;
    const mean = times.length ? times.reduce((a, b) => a + b, 0) / times.length : 0;
    const { texture, name } = state.asset;
    setStatus(`${name}: ${texture.channels === 3 ? 'RGB' : 'grey'}, texton ${texture.textonWidth}x` +
              `${texture.textonHeight}, ${texture.interpolation}; runtime ${state.runtime.version}; ` +
              (times.length
                   ? `${mean.toFixed(0)} ms per ${TILE}x${TILE} tile (${state.workers.length} workers)`
                   : ''));
    if (testMode && !state.opening) hashCanvas();
}

async function hashCanvas() {
    const pixels = context.getImageData(0, 0, canvas.width, canvas.height).data;
    const rgb = new Uint8Array((pixels.length / 4) * 3);
    for (let p = 0, q = 0; p < pixels.length; p += 4, q += 3) {
        rgb[q] = pixels[p];
        rgb[q + 1] = pixels[p + 1];
        rgb[q + 2] = pixels[p + 2];
    }
    const digest = new Uint8Array(await crypto.subtle.digest('SHA-256', rgb));
    if (!state.reported || state.opening) return; // the view or the texture changed meanwhile
    elements['canvas-hash'].textContent = [...digest].map((b) => b.toString(16).padStart(2, '0')).join('');
    document.documentElement.dataset.state = 'ready';
}

// ---- Asset and settings ----

function changed() {
    state.generation++;
    viewChanged();
    for (const tile of state.cache.values()) tile.bitmap.close();
    state.cache.clear();
    state.pending.clear();
    requestDraw();
}

// Validates the bytes on this thread first, so a damaged file is reported with the loader's message and
// the texture shown before stays.
function useAsset(bytes, name) {
    let texture;
    try {
        texture = state.runtime.load(bytes,
                                     state.settings.density ? state.settings : { seed: state.settings.seed });
    } catch (error) {
        setStatus(`${name}: ${error.message}`, true);
        if (testMode) document.documentElement.dataset.state = 'error';
        return false;
    }
    state.asset = { bytes, name, texture };
    if (!state.settings.density) setDensity(texture.defaultDensity);
    changed();
    sendAsset();
    return true;
}

function setDensity(density) {
    state.settings.density = density;
    elements.density.value = String(Math.round(density));
    elements['density-value'].textContent = String(density);
}

function applySettings() {
    if (!state.asset) return;
    try {
        state.asset.texture.configure(state.settings);
    } catch (error) {
        setStatus(error.message, true);
        return;
    }
    changed();
    sendAsset();
}

// ---- Your own texture: a .dsnt, or a photo baked here ----

// A .dsnt file is loaded as it is; anything else is taken for an exemplar image and baked (bake_worker.js).
async function openFile(file) {
    // Until this file is loaded or refused, the page reports nothing in test mode (data-opened names it).
    state.opening = file.name;
    if (testMode) {
        document.documentElement.dataset.opened = file.name;
        delete document.documentElement.dataset.state;
    }
    const done = () => (state.opening = null);
    const refuse = (message) => {
        done();
        setStatus(message, true);
        if (testMode) document.documentElement.dataset.state = 'error';
    };
    const bytes = new Uint8Array(await file.arrayBuffer());
    if (file.name.toLowerCase().endsWith('.dsnt') || !file.type.startsWith('image/')) {
        done();
        useAsset(bytes, file.name);
        return;
    }
    setStatus(`${file.name}: baking (a few seconds)…`);
    let image;
    try {
        image = await exemplarOf(file);
    } catch (error) {
        refuse(`${file.name}: ${error.message}`);
        return;
    }
    if (!state.bakeWorker) {
        state.bakeWorker = new Worker(new URL('bake_worker.js', import.meta.url), { type: 'module' });
        state.bakeWorker.onmessage = ({ data }) => {
            if (data.error)
                refuse(`${data.name}: ${data.error}`);
            else {
                done();
                useAsset(data.asset, `${data.name} (baked in ${(data.ms / 1000).toFixed(1)} s)`);
            }
        };
        state.bakeWorker.onerror = (event) => refuse(`the baker failed: ${event.message}`);
    }
    state.bakeWorker.postMessage({ image, name: file.name }, [image.buffer]);
}

// The exemplar the baker gets: the photo scaled down until its shorter side is at most 512 pixels, then
// its centre, at most 256 x 256 (bakes stay a few seconds and texture features stay a few pixels wide), as
// PNG bytes. Images the browser cannot decode are passed as they are: the baker names the problem.
async function exemplarOf(file) {
    let bitmap;
    try {
        bitmap = await createImageBitmap(file);
    } catch {
        return new Uint8Array(await file.arrayBuffer());
    }
    const scale = Math.min(1, 512 / Math.min(bitmap.width, bitmap.height));
    const width = Math.min(256, Math.round(bitmap.width * scale));
    const height = Math.min(256, Math.round(bitmap.height * scale));
    const sourceWidth = width / scale, sourceHeight = height / scale;
    const scaled = new OffscreenCanvas(width, height);
    scaled.getContext('2d').drawImage(bitmap, (bitmap.width - sourceWidth) / 2,
                                      (bitmap.height - sourceHeight) / 2, sourceWidth, sourceHeight, 0, 0,
                                      width, height);
    bitmap.close();
    const blob = await scaled.convertToBlob({ type: 'image/png' });
    return new Uint8Array(await blob.arrayBuffer());
}

// ---- Input ----

function zoomAt(factor, screenX, screenY) {
    const view = state.view;
    const zoom = Math.min(2 ** MAX_LEVEL, Math.max(2 ** MIN_LEVEL, view.zoom * factor));
    // Keep the texel under the cursor where it is (screen coordinates in CSS pixels).
    view.x += screenX / view.zoom - screenX / zoom;
    view.y += screenY / view.zoom - screenY / zoom;
    view.zoom = zoom;
    viewChanged();
    requestDraw();
}

function installInput() {
    let drag = null;
    canvas.addEventListener('pointerdown', (event) => {
        drag = { x: event.clientX, y: event.clientY };
        canvas.setPointerCapture(event.pointerId);
        canvas.classList.add('dragging');
    });
    canvas.addEventListener('pointermove', (event) => {
        if (!drag) return;
        state.view.x -= (event.clientX - drag.x) / state.view.zoom;
        state.view.y -= (event.clientY - drag.y) / state.view.zoom;
        drag = { x: event.clientX, y: event.clientY };
        viewChanged();
        requestDraw();
    });
    const stop = () => {
        drag = null;
        canvas.classList.remove('dragging');
    };
    canvas.addEventListener('pointerup', stop);
    canvas.addEventListener('pointercancel', stop);
    canvas.addEventListener('wheel', (event) => {
        event.preventDefault();
        const box = canvas.getBoundingClientRect();
        const delta = event.deltaMode === 1 ? event.deltaY * 16 : event.deltaY;
        zoomAt(Math.exp(-delta * 0.0015), event.clientX - box.left, event.clientY - box.top);
    }, { passive: false });
    elements.seed.addEventListener('change', () => {
        state.settings.seed = Number(elements.seed.value) >>> 0;
        applySettings();
    });
    elements['new-seed'].addEventListener('click', () => {
        state.settings.seed = crypto.getRandomValues(new Uint32Array(1))[0];
        elements.seed.value = String(state.settings.seed);
        applySettings();
    });
    elements.density.addEventListener(
        'input', () => { elements['density-value'].textContent = elements.density.value; });
    elements.density.addEventListener('change', () => {
        state.settings.density = Number(elements.density.value);
        applySettings();
    });
    elements.file.addEventListener('change', () => {
        if (elements.file.files[0]) openFile(elements.file.files[0]);
    });
    canvas.addEventListener('dragover', (event) => event.preventDefault());
    canvas.addEventListener('drop', (event) => {
        event.preventDefault();
        if (event.dataTransfer.files[0]) openFile(event.dataTransfer.files[0]);
    });
    elements['reset-view'].addEventListener('click', () => {
        state.view = { x: 0, y: 0, zoom: 1 };
        viewChanged();
        requestDraw();
    });
    if (!fixedSize) new ResizeObserver(resize).observe(canvas);
}

let fixedSize = false;
function resize() {
    const box = canvas.getBoundingClientRect();
    state.pixelRatio = window.devicePixelRatio || 1;
    const width = Math.max(1, Math.round(box.width * state.pixelRatio));
    const height = Math.max(1, Math.round(box.height * state.pixelRatio));
    if (width === canvas.width && height === canvas.height) return;
    canvas.width = width;
    canvas.height = height;
    viewChanged();
    requestDraw();
}

// ---- Start ----

async function main() {
    const number = (name, fallback) => (parameters.has(name) ? Number(parameters.get(name)) : fallback);
    state.settings.seed = number('seed', 1) >>> 0;
    state.settings.density = number('density', 0);
    state.view = { x: number('x', 0), y: number('y', 0), zoom: number('zoom', 1) };
    elements.seed.value = String(state.settings.seed);
    if (parameters.has('width') && parameters.has('height')) {
        // A fixed canvas, one canvas pixel per CSS pixel whatever the display: the view is exactly the
        // window of dsn-render --size WxH --scale ZOOM --origin X,Y --filter none.
        fixedSize = true;
        document.body.classList.add('fixed');
        canvas.width = number('width', 256);
        canvas.height = number('height', 256);
        canvas.style.width = `${canvas.width}px`;
        canvas.style.height = `${canvas.height}px`;
        canvas.parentElement.style.width = `${canvas.width}px`;
        canvas.parentElement.style.height = `${canvas.height}px`;
    } else
        resize();
    installInput();
    try {
        state.runtime = await loadRuntime(new URL('dsn.wasm', import.meta.url));
    } catch (error) {
        setStatus(`cannot load the runtime (dsn.wasm): ${error.message}`, true);
        return;
    }
    startWorkers(state.runtime.module);
    const assetName = parameters.get('asset') || 'demo.dsnt';
    let bytes;
    try {
        const response = await fetch(new URL(assetName, location.href));
        if (!response.ok) throw new Error(`HTTP ${response.status}`);
        bytes = new Uint8Array(await response.arrayBuffer());
    } catch (error) {
        setStatus(`cannot fetch ${assetName}: ${error.message}`, true);
        if (testMode) document.documentElement.dataset.state = 'error';
        return;
    }
    useAsset(bytes, assetName);
}

main();
