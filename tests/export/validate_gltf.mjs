// Validates a .glb with the Khronos glTF validator (npm "gltf-validator"), a reader
// independent of pelage and of assimp, and writes its report as JSON.
// Usage: node validate_gltf.mjs NODE_MODULES FILE.glb OUT.json. Exit 1 when the
// validator finds an error.
import fs from 'fs';
import path from 'path';
import { pathToFileURL } from 'url';

const [modules, file, out] = process.argv.slice(2);
const { default: validator } =
    await import(pathToFileURL(path.join(modules, 'gltf-validator', 'index.js')).href);
const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)));
fs.writeFileSync(out, JSON.stringify(report));
if (report.issues.numErrors > 0) {
    console.error(JSON.stringify(report.issues.messages.slice(0, 10), null, 1));
    process.exit(1);
}
