// Runs the WebAssembly build of the determinism scenes under Node and prints `name hash` lines,
// as the native binary does: `node determinism/run.mjs <odyn_determinism.wasm>`.
import { readFileSync } from "node:fs";

const module = await WebAssembly.compile(readFileSync(process.argv[2]));
// The module is self-contained (odyn's wasm build pulls in no JavaScript glue); an import would
// mean a dependency that expects a browser's, and is reported rather than stubbed.
const imports = WebAssembly.Module.imports(module);
if (imports.length > 0) {
  const names = imports.map(({ module: from, name }) => `${from}.${name}`).join(", ");
  throw new Error(`the determinism module imports ${names}; it must be self-contained`);
}
const instance = await WebAssembly.instantiate(module, {});
const odyn = instance.exports;
const count = odyn.odyn_scene_count();
for (let i = 0; i < count; i++) {
  const hash = odyn.odyn_scene_hash(i);
  const pointer = odyn.odyn_scene_name(i);
  const length = odyn.odyn_scene_name_len(i);
  const name = new TextDecoder().decode(new Uint8Array(odyn.memory.buffer, pointer, length));
  console.log(`${name} ${BigInt.asUintN(64, hash).toString(16).padStart(16, "0")}`);
}
