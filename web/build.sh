#!/usr/bin/env bash
# Builds the lab page: the WebAssembly module (release, `deterministic` feature) and
# wasm-bindgen's JavaScript glue, into web/pkg/. Installs the wasm-bindgen CLI with cargo when
# it is missing or not the version of the crate (Cargo.toml pins both).
set -euo pipefail
cd "$(dirname "$0")/.."
version=0.2.130
if [ "$(wasm-bindgen --version 2>/dev/null)" != "wasm-bindgen $version" ]; then
  echo "lab: installing wasm-bindgen-cli $version with cargo (a few minutes, once)"
  # Not --locked: its lock file pins a webpki-roots release crates.io no longer resolves.
  cargo install -q wasm-bindgen-cli --version "$version"
fi
cargo build -q --release -p odyn-web --features deterministic --target wasm32-unknown-unknown --lib
wasm-bindgen --target web --no-typescript --out-dir web/pkg \
  target/wasm32-unknown-unknown/release/lab.wasm
echo "lab: web/pkg/lab_bg.wasm $(stat -c %s web/pkg/lab_bg.wasm) bytes, web/pkg/lab.js $(stat -c %s web/pkg/lab.js) bytes"
