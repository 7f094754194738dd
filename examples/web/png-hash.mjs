// png-hash.mjs - prints the SHA-256 of a PNG's pixels as RGB bytes (grey repeated three times), the hash
// the demo page computes over its canvas in test mode. Reads the 8-bit, non-interlaced grey and RGB PNGs
// that dsn-render writes; anything else is refused.
// Usage: node png-hash.mjs FILE.png
import {createHash} from 'node:crypto';
import {readFileSync} from 'node:fs';
import {inflateSync} from 'node:zlib';

const path = process.argv[2];
const fail = (message) => {
    console.error(`png-hash: ${path}: ${message}`);
    process.exit(1);
};
if (!path) fail('usage: node png-hash.mjs FILE.png');
const file = readFileSync(path);
if (file.length < 8 || file.readUInt32BE(0) !== 0x89504e47) fail('not a PNG file');
let width = 0, height = 0, channels = 0;
const compressed = [];
for (let at = 8; at + 8 <= file.length;) {
    const length = file.readUInt32BE(at), type = file.toString('latin1', at + 4, at + 8);
    const data = file.subarray(at + 8, at + 8 + length);
    if (type === 'IHDR') {
        width = data.readUInt32BE(0);
        height = data.readUInt32BE(4);
        const [depth, colour, , , interlace] = data.subarray(8, 13);
        channels = { 0: 1, 2: 3 }[colour] || 0;
        if (depth !== 8 || !channels || interlace !== 0) fail('only 8-bit grey or RGB, not interlaced');
    } else if (type === 'IDAT')
        compressed.push(data);
    at += 12 + length;
}
const raw = inflateSync(Buffer.concat(compressed));
const stride = width * channels;
if (raw.length !== height * (stride + 1)) fail('truncated pixel data');
// Undo the row filters (PNG specification, section 9).
const pixels = new Uint8Array(height * stride);
for (let y = 0; y < height; y++) {
    const filter = raw[y * (stride + 1)];
    const row = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let i = 0; i < stride; i++) {
        const left = i >= channels ? pixels[y * stride + i - channels] : 0;
        const up = y > 0 ? pixels[(y - 1) * stride + i] : 0;
        const upLeft = y > 0 && i >= channels ? pixels[(y - 1) * stride + i - channels] : 0;
        let predicted = 0;
        if (filter === 1)
            predicted = left;
        else if (filter === 2)
            predicted = up;
        else if (filter === 3)
            predicted = (left + up) >> 1;
        else if (filter === 4) {
            const p = left + up - upLeft, pa = Math.abs(p - left), pb = Math.abs(p - up),
                  pc = Math.abs(p - upLeft);
            predicted = pa <= pb && pa <= pc ? left : pb <= pc ? up : upLeft;
        } else if (filter !== 0)
            fail(`unknown row filter ${filter}`);
        pixels[y * stride + i] = (row[i] + predicted) & 255;
    }
}
const rgb =
    channels === 3 ? pixels : Uint8Array.from({ length: pixels.length * 3 }, (_, i) => pixels[(i / 3) | 0]);
console.log(createHash('sha256').update(rgb).digest('hex'));
