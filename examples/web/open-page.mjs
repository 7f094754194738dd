// open-page.mjs - opens a page in headless Chromium, waits until it sets <html data-state> (the demo page
// does in test mode: 'ready' or 'error'), and prints one JSON line: the state, the texts of #status and
// #canvas-hash, and every uncaught exception the page or its workers threw. Optionally saves a
// screenshot (taken last). Chromium is driven over --remote-debugging-pipe (the DevTools protocol on file
// descriptors 3 and 4), so nothing beyond Node and Chromium is needed. --virtual-time-budget cannot be used
// instead: virtual time does not wait for Web Workers.
//
// Usage: node open-page.mjs URL [--screenshot FILE.png] [--size WxH] [--timeout SECONDS] [--interact]
//                            [--upload FILE]
//   --interact  then drags the canvas and zooms with the wheel, and waits for the page again
//               (afterInteraction in the JSON);
//   --upload    then gives FILE to the page's file picker and waits again (afterUpload[i]; repeatable).
//   CHROMIUM names the browser (default chromium); as root it runs with --no-sandbox.
import {spawn} from 'node:child_process';
import {writeFileSync} from 'node:fs';
import {basename, resolve} from 'node:path';

const args = process.argv.slice(2);
const option = (name, fallback) => {
    const at = args.indexOf(name);
    return at >= 0 ? args.splice(at, 2)[1] : fallback;
};
const screenshot = option('--screenshot', null);
const uploads = [];
for (let file; (file = option('--upload', null));) uploads.push(file);
const interact = args.includes('--interact') && Boolean(args.splice(args.indexOf('--interact'), 1));
const [width, height] = option('--size', '1024x768').split('x').map(Number);
const timeoutSeconds = Number(option('--timeout', '60'));
const url = args[0];
if (!url || args.length !== 1 || !(width > 0 && height > 0)) {
    console.error('usage: node open-page.mjs URL [--screenshot FILE.png] [--size WxH] [--timeout SECONDS] ' +
                  '[--interact] [--upload FILE]');
    process.exit(2);
}

const flags = [
    '--headless', '--remote-debugging-pipe', '--disable-gpu', '--no-first-run', '--mute-audio',
    '--disable-extensions', `--window-size=${width},${height}`, 'about:blank'
];
if (process.getuid && process.getuid() === 0) flags.unshift('--no-sandbox');
const browser =
    spawn(process.env.CHROMIUM || 'chromium', flags, { stdio: ['ignore', 'ignore', 'pipe', 'pipe', 'pipe'] });
let browserLog = '';
browser.stderr.on('data', (chunk) => (browserLog = (browserLog + chunk).slice(-4000)));

const fail = (message) => {
    console.error(`open-page: ${message}`);
    if (browserLog) console.error(`open-page: the browser's last words:\n${browserLog}`);
    browser.kill('SIGKILL');
    process.exit(1);
};
const deadline = setTimeout(() => fail(`no result within ${timeoutSeconds} s`), timeoutSeconds * 1000);
process.on('unhandledRejection', (error) => {
    if (!finished) fail(error.message); // after the answer, a worker closing with the browser is no failure
});
browser.on('error', (error) => fail(`cannot start the browser: ${error.message}`));
browser.on('exit', (code, signal) => {
    if (!finished) fail(`the browser exited (${signal || code})`);
});

// The protocol: JSON messages, each ended by a NUL byte.
const toBrowser = browser.stdio[3], fromBrowser = browser.stdio[4];
let nextId = 1, buffered = '', finished = false;
const waiting = new Map();
const exceptions = [];
fromBrowser.on('data', (chunk) => {
    buffered += chunk.toString('utf8');
    let end;
    while ((end = buffered.indexOf('\0')) >= 0) {
        const message = JSON.parse(buffered.slice(0, end));
        buffered = buffered.slice(end + 1);
        if (message.id && waiting.has(message.id)) {
            const { resolve, reject } = waiting.get(message.id);
            waiting.delete(message.id);
            if (message.error)
                reject(new Error(`${message.error.message} (${message.error.code})`));
            else
                resolve(message.result);
        } else if (message.method === 'Runtime.exceptionThrown') {
            const details = message.params.exceptionDetails;
            exceptions.push(details.exception?.description || details.text);
        } else if (message.method === 'Target.attachedToTarget' && message.params.waitingForDebugger) {
            // A worker, paused until told to run: listen to its exceptions too.
            const worker = message.params.sessionId;
            send('Runtime.enable', {}, worker)
                .then(() => send('Runtime.runIfWaitingForDebugger', {}, worker));
        }
    }
});
function send(method, params = {}, sessionId = undefined) {
    const id = nextId++;
    toBrowser.write(JSON.stringify({ id, method, params, sessionId }) + '\0');
    return new Promise((resolve, reject) => waiting.set(id, { resolve, reject }));
}

const { targetId } = await send('Target.createTarget', { url: 'about:blank' });
const { sessionId } = await send('Target.attachToTarget', { targetId, flatten: true });
const page = (method, params) => send(method, params, sessionId);
await page('Runtime.enable');
await page('Page.enable');
await page('Target.setAutoAttach', { autoAttach: true, waitForDebuggerOnStart: true, flatten: true });
await page('Emulation.setDeviceMetricsOverride', { width, height, deviceScaleFactor: 1, mobile: false });
await page('Page.navigate', { url });

const read = async (expression) =>
    (await page('Runtime.evaluate', { expression, returnByValue: true })).result.value;
const readPage = async () => {
    let state = '';
    while (!(state = await read("document.documentElement.dataset.state || ''"))) {
        await new Promise((resolve) => setTimeout(resolve, 100));
    }
    return {
        state,
        status: await read("document.getElementById('status')?.textContent || ''"),
        hash: await read("document.getElementById('canvas-hash')?.textContent || ''"),
    };
};
const result = await readPage();
const clearState = () =>
    read('delete document.documentElement.dataset.state; delete document.documentElement.dataset.opened');
if (interact) {
    // A drag of the canvas, then a zoom by the wheel past the next level; the page reports again once
    // every tile of the new view is drawn.
    const zoomText = "document.getElementById('zoom-value')?.textContent || ''";
    const zoomBefore = await read(zoomText);
    await clearState();
    const mouse = (type, x, y, extra = {}) =>
        page('Input.dispatchMouseEvent', { type, x, y, button: 'left', pointerType: 'mouse', ...extra });
    await mouse('mousePressed', 300, 300, { buttons: 1, clickCount: 1 });
    for (let step = 1; step <= 10; step++)
        await mouse('mouseMoved', 300 - 8 * step, 300 - 5 * step, { buttons: 1 });
    await mouse('mouseReleased', 220, 250, { clickCount: 1 });
    for (let step = 0; step < 6; step++)
        await page('Input.dispatchMouseEvent',
                   { type: 'mouseWheel', x: 250, y: 250, deltaX: 0, deltaY: -100 });
    // Wheel events may reach the page after the protocol has answered: wait for the zoom to show.
    while ((await read(zoomText)) === zoomBefore) await new Promise((resolve) => setTimeout(resolve, 50));
    result.afterInteraction = await readPage();
}
result.afterUpload = [];
for (const file of uploads) {
    // The file picker, as a person would use it (the file chooser's answer set through the protocol).
    await clearState();
    const { root } = await page('DOM.getDocument', {});
    const { nodeId } = await page('DOM.querySelector', { nodeId: root.nodeId, selector: 'input[type=file]' });
    await page('DOM.setFileInputFiles', { nodeId, files: [resolve(file)] });
    // The page names the file it works on (data-opened) before it answers for it.
    const opened = `document.documentElement.dataset.opened === ${JSON.stringify(basename(file))}`;
    while (!(await read(opened))) await new Promise((resolve) => setTimeout(resolve, 50));
    result.afterUpload.push(await readPage());
}
result.exceptions = exceptions;
if (screenshot) {
    const { data } = await page('Page.captureScreenshot', { format: 'png' });
    writeFileSync(screenshot, Buffer.from(data, 'base64'));
}
finished = true;
clearTimeout(deadline);
console.log(JSON.stringify(result));
await send('Browser.close').catch(() => {});
setTimeout(() => browser.kill('SIGKILL'), 2000).unref();
