#!/usr/bin/env bash
# Cross-platform determinism (issue 26): the hashes of seven full trajectories, run natively and
# compiled to WebAssembly under Node, both with odyn's `deterministic` feature, must be equal bit
# for bit. Needs the wasm32-unknown-unknown target (rust-toolchain.toml lists it) and `node`.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v node > /dev/null; then
  echo "determinism: node is not installed; the WebAssembly side cannot run" >&2
  exit 1
fi
# rust-toolchain.toml names the target, but a rustup that does not install on its own (as on a
# fresh CI machine, RUSTUP_AUTO_INSTALL=0) leaves it out: add it here.
if command -v rustup > /dev/null && ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
  rustup target add wasm32-unknown-unknown
fi
out=target/determinism
mkdir -p "$out"
cargo build -q -p odyn-determinism --features deterministic --target wasm32-unknown-unknown
cargo run -q -p odyn-determinism --features deterministic > "$out/native.txt"
node determinism/run.mjs target/wasm32-unknown-unknown/debug/determinism.wasm > "$out/wasm.txt"
if diff "$out/native.txt" "$out/wasm.txt"; then
  echo "determinism: $(wc -l < "$out/native.txt") trajectories bit-identical, native and WebAssembly"
else
  echo "determinism: native (<) and WebAssembly (>) trajectories differ" >&2
  exit 1
fi
