#!/usr/bin/env python3
"""Compile time and peak memory of big `#[system]` models (issue 16.4; not part of CI).

Generates a throw-away crate per case under a scratch directory, depending on this checkout's
`odyn` by path, builds its dependencies once, then times `cargo build --release` of the model
crate alone with `/usr/bin/time -v` (peak resident memory of the slowest child, i.e. rustc).

Cases:
  dense N  — SVector<f64, N> state, ẏ = −k·y·|y|²: every component couples to every other, so
             the Jacobian has N² structural non-zeros.
  chain N  — [f64; N] state, ẏᵢ = k·(yᵢ₋₁ − 2yᵢ + yᵢ₊₁) written out (a 1-D diffusion stencil):
             3N − 2 non-zeros.

Usage: python3 scripts/compile_cost.py [--cases dense:40,dense:200,chain:1000]
"""

import argparse
import os
import pathlib
import re
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent


def dense(n):
    return f"""
use odyn::prelude::*;
use odyn::nalgebra::SVector;

#[system(integrator = ImplicitEuler, dt = 0.01)]
pub struct Big {{
    #[state]
    pub y: SVector<f64, {n}>,
    pub k: f64,
}}

#[system]
impl Big {{
    fn derivative(&self) -> BigState {{
        BigState {{ y: -self.y * (self.k * self.y.norm_squared()) }}
    }}
}}

fn main() {{
    let model = Big {{ y: SVector::from_element(0.1), k: 1.0 }};
    let run = model.simulate().steps(10).run().unwrap();
    println!("{{}}", run.samples.last().unwrap().state.y[0]);
}}
"""


def chain(n):
    terms = []
    for i in range(n):
        left = f"self.y[{i - 1}]" if i > 0 else "0.0"
        right = f"self.y[{i + 1}]" if i + 1 < n else "0.0"
        terms.append(f"self.k * ({left} - 2.0 * self.y[{i}] + {right})")
    body = ",\n                ".join(terms)
    return f"""
use odyn::prelude::*;

#[system(integrator = ImplicitEuler, dt = 0.01)]
pub struct Big {{
    #[state]
    pub y: [f64; {n}],
    pub k: f64,
}}

#[system]
impl Big {{
    fn derivative(&self) -> BigState {{
        BigState {{
            y: [
                {body}
            ],
        }}
    }}
}}

fn main() {{
    let model = Big {{ y: [0.1; {n}], k: 1.0 }};
    let run = model.simulate().steps(10).run().unwrap();
    println!("{{}}", run.samples.last().unwrap().state.y[0]);
}}
"""


def measure(kind, n, scratch, odyn):
    crate = scratch / f"{kind}{n}"
    (crate / "src").mkdir(parents=True, exist_ok=True)
    (crate / "Cargo.toml").write_text(
        f"""[package]
name = "compile-cost-{kind}{n}"
version = "0.0.0"
edition = "2024"

[dependencies]
odyn = {{ path = "{odyn}", default-features = false }}

[workspace]
"""
    )
    env = dict(os.environ, CARGO_TARGET_DIR=str(scratch / "target"))
    # Dependencies first, with a trivial main, so the timed build is the model crate alone.
    (crate / "src" / "main.rs").write_text("fn main() {}\n")
    subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=crate, env=env, check=False,
                   capture_output=True)
    (crate / "src" / "main.rs").write_text({"dense": dense, "chain": chain}[kind](n))
    start = time.time()
    out = subprocess.run(["/usr/bin/time", "-v", "cargo", "build", "--release", "--quiet"],
                         cwd=crate, env=env, capture_output=True, text=True)
    seconds = time.time() - start
    peak = re.search(r"Maximum resident set size \(kbytes\): (\d+)", out.stderr)
    ok = out.returncode == 0
    first_error = next((l for l in out.stderr.splitlines() if l.startswith("error")), "")
    return seconds, int(peak.group(1)) / 1024 if peak else float("nan"), ok, first_error


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cases", default="dense:40,dense:200,chain:1000")
    parser.add_argument("--scratch", default="/tmp/odyn-compile-cost")
    parser.add_argument("--odyn", default=str(ROOT), help="the odyn checkout to measure")
    args = parser.parse_args()
    scratch = pathlib.Path(args.scratch)
    print(f"{'case':>12} {'seconds':>8} {'peak MiB':>9}  result")
    for case in args.cases.split(","):
        kind, n = case.split(":")
        seconds, mib, ok, error = measure(kind, int(n), scratch, args.odyn)
        print(f"{case:>12} {seconds:8.1f} {mib:9.0f}  {'ok' if ok else error}")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
