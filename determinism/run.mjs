// Runs the WebAssembly build of the determinism scenes under Node and prints `name hash` lines,
// as the native binary does: `node determinism/run.mjs <odyn_determinism.wasm>`.
import { readFileSync } from "node:fs";

const module = await WebAssembly.compile(readFileSync(process.argv[2]));
// Dependencies built for the browser (indicatif's clock, through web-time and wasm-bindgen)
// leave imports that only wasm-bindgen's JavaScript glue provides; no scene calls them, so each
// is a function that fails loudly if one ever does.
const imports = {};
for (const { module: from, name, kind } of WebAssembly.Module.imports(module)) {
  if (kind !== "function") throw new Error(`unexpected ${kind} import ${from}.${name}`);
  imports[from] ??= {};
  imports[from][name] = () => {
    throw new Error(`${from}.${name} called: not available outside wasm-bindgen`);
  };
}
const instance = await WebAssembly.instantiate(module, imports);
const odyn = instance.exports;
const count = odyn.odyn_scene_count();
for (let i = 0; i < count; i++) {
  const hash = odyn.odyn_scene_hash(i);
  const pointer = odyn.odyn_scene_name(i);
  const length = odyn.odyn_scene_name_len(i);
  const name = new TextDecoder().decode(new Uint8Array(odyn.memory.buffer, pointer, length));
  console.log(`${name} ${BigInt.asUintN(64, hash).toString(16).padStart(16, "0")}`);
}
