// Reads a .usda with TinyUSDZ (npm "tinyusdz", WebAssembly), a USD reader independent
// of pelage, and writes what it read as JSON for the tests to compare with what pelage
// rendered:
//   meshes: TinyUSDZ's own render-scene conversion of each Mesh (points, indices, UVs);
//   prims:  every prim of the layer TinyUSDZ parsed, with each attribute's value (or
//           time samples) as a flat list of numbers, or a string for tokens and assets,
//           and its interpolation; read from the layer as TinyUSDZ serialises it back.
// Usage: node read_usd.mjs NODE_MODULES FILE.usda OUT.json. Exit 1 when TinyUSDZ rejects
// the file.
import fs from 'fs';
import path from 'path';
import { pathToFileURL } from 'url';

const [modules, file, out] = process.argv.slice(2);
// The package is built for browsers: it runs under Node as a renderer process with a
// window object, given the WebAssembly bytes directly.
process.type = 'renderer';
globalThis.window = globalThis;
const pkg = path.join(modules, 'tinyusdz');
const { default: init } = await import(pathToFileURL(path.join(pkg, 'tinyusdz.js')).href);
const usd = await init({ wasmBinary: fs.readFileSync(path.join(pkg, 'tinyusdz.wasm')) });
const bytes = new Uint8Array(fs.readFileSync(file));

const scene = new usd.TinyUSDZLoaderNative();
if (!scene.loadFromBinary(bytes, path.basename(file))) {
    console.error(`tinyusdz rejects ${file}: ${scene.error()}`);
    process.exit(1);
}
const meshes = [];
for (let i = 0; i < scene.numMeshes(); ++i) {
    const m = scene.getMesh(i);
    meshes.push({
        path: m.absPath,
        points: Array.from(m.points ?? []),
        faceVertexIndices: Array.from(m.faceVertexIndices ?? []),
        faceVertexCounts: Array.from(m.faceVertexCounts ?? []),
        texcoords: Array.from(m.texcoords ?? []),
    });
}

const layer = new usd.TinyUSDZLoaderNative();
if (!layer.loadAsLayerFromBinary(bytes, path.basename(file))) {
    console.error(`tinyusdz rejects ${file} as a layer: ${layer.error()}`);
    process.exit(1);
}
const text = layer.layerToString();

// The layer's text as TinyUSDZ writes it: one attribute per line (`TYPE NAME = VALUE`,
// or `NAME.timeSamples = {` and one `TIME: VALUE,` per line), its metadata in the
// parentheses that follow, prims as `def TYPE "NAME"` with braces.
const numbers = (v) => (v.match(/-?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|-?inf|nan/g) ?? [])
    .map(Number);
const value = (v) => {
    v = v.trim();
    if (v.startsWith('"') || v.startsWith('@')) return v.slice(1, -1);
    if (v.startsWith('<')) return v;
    return numbers(v);
};
const prims = {};
const stack = [];
let pendingPrim = null, current = null, lastAttr = null, samples = null;
const stage = {};
let inStageMeta = true;
for (const raw of text.split('\n')) {
    const line = raw.trim();
    if (inStageMeta) {
        const m = line.match(/^(\w+) = (.*)$/);
        if (m) stage[m[1]] = value(m[2]);
        if (line.startsWith('def ')) inStageMeta = false; else continue;
    }
    if (samples) {
        if (line === '}') { samples = null; continue; }
        const m = line.match(/^([-\d.e]+): (.*?),?$/);
        if (m) samples[m[1]] = value(m[2]);
        continue;
    }
    let m = line.match(/^def (\w+) "(\w+)"/);
    if (m) { pendingPrim = { type: m[1], name: m[2] }; continue; }
    if (line === '{' && pendingPrim) {
        stack.push(pendingPrim.name);
        current = { type: pendingPrim.type, attrs: {} };
        prims['/' + stack.join('/')] = current;
        pendingPrim = null;
        continue;
    }
    if (line === '}') {
        stack.pop();
        current = stack.length ? prims['/' + stack.join('/')] : null;
        continue;
    }
    m = line.match(/interpolation = "(\w+)"/);
    if (m && lastAttr) { lastAttr.interpolation = m[1]; continue; }
    m = line.match(/^(?:uniform )?[\w\[\]]+ ([\w:]+)\.timeSamples = \{$/);
    if (m && current) {
        lastAttr = current.attrs[m[1]] ?? (current.attrs[m[1]] = {});
        samples = lastAttr.samples = {};
        continue;
    }
    m = line.match(/^(?:uniform |prepend |rel )?(?:[\w\[\]]+ )?([\w:]+(?:\.connect)?) = (.*?)( \()?$/);
    if (m && current) {
        lastAttr = current.attrs[m[1]] = { value: value(m[2]) };
        continue;
    }
    m = line.match(/^(?:uniform )?[\w\[\]]+ ([\w:]+)( \()?$/);
    if (m && current) lastAttr = current.attrs[m[1]] ?? (current.attrs[m[1]] = {});
}
fs.writeFileSync(out, JSON.stringify({ stage, meshes, prims }));
