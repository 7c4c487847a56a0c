//! Prints each scene's trajectory hash, `name hash` a line, as `run.mjs` does for the
//! WebAssembly build: `scripts/determinism.sh` compares the two.

fn main() {
    for (name, hash) in determinism::hashes() {
        println!("{name} {hash:016x}");
    }
}
