// run-wasm.mjs - runs the cross test's golden program built for freestanding wasm32 under Node: the module
// imports one function, golden.write(pointer, size), which writes those bytes of its memory to stdout;
// the program's exit status is main's return value.
// Usage: node tests/cross/run-wasm.mjs golden.wasm
import {readFileSync, writeSync} from 'node:fs';

const path = process.argv[2];
if (!path) {
    console.error('usage: node run-wasm.mjs PROGRAM.wasm');
    process.exit(2);
}
let memory = null;
const imports = {
    golden: {
        write(pointer, size) {
            // wasm32 pointers and sizes arrive as signed 32-bit numbers.
            writeSync(1, new Uint8Array(memory.buffer, pointer >>> 0, size >>> 0));
        },
    },
};
const { instance } = await WebAssembly.instantiate(readFileSync(path), imports);
memory = instance.exports.memory;
// Built freestanding, main is an ordinary C++ function (its mangled name); a hosted build names it
// __main_void.
const main = instance.exports._Z4mainv ?? instance.exports.__main_void ?? instance.exports.main;
if (typeof main !== 'function') {
    console.error(`run-wasm: ${path} exports no main`);
    process.exit(2);
}
process.exitCode = main();
