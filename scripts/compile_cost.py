#!/usr/bin/env python3
"""Compile time and peak memory of big `#[system]` models, in the dev and release profiles
(issues 16.4 and 23; not part of CI: the biggest case takes minutes).

Generates a throw-away crate per case under a scratch directory, depending on an odyn checkout
by path, builds its dependencies once per profile with a trivial `main`, then times `cargo build`
of the model crate alone with `/usr/bin/time -v` (peak resident memory of the biggest process,
i.e. rustc). The crate's `[profile.dev]` settings are the workspace's: dependencies at
opt-level 3, the model's own crate at 2 with full debuginfo, as odyn's tests and examples compile.
A build that crashes rustc reports the signal.

Cases (KIND:N):
  stencil N — [f64; N] state (N = side², a side × side grid), u̇ = k·∇²u by the 5-point stencil
              with zero outside the grid, written out component by component (`#[system]`
              differentiates straight-line code, not loops over the state): 5N − 4·side
              non-zeros, so the Jacobian comes from coloured forward mode.
  terms N   — [f64; 30] state, a derivative of N terms c·yᵢ·yⱼ split into 30 `let`s of N/30
              terms each (a dense 30 × 30 Jacobian, one expression per entry), read through
              `let y = self.y;`: spelt `self.y[i]`, a 100-term `let` has more than 512
              punctuation tokens in a row, which `#[system]` refuses (macros/src/limits.rs).
  dense N   — SVector<f64, N> state, ẏ = −k·y·|y|²: N² structural non-zeros.
  chain N   — [f64; N] state, ẏᵢ = k·(yᵢ₋₁ − 2yᵢ + yᵢ₊₁) written out (1-D diffusion): 3N − 2.
  chosen N  — N damped springs (position/velocity, so every method can take them), each run with
              RK4 chosen at run time, `.integrator(Method::Rk4).run()`: every method's loop is
              compiled for each model (issue 52, "compile only what runs").
  typed N   — the same N springs, each run with `.run_with::<method::Rk4>()`: RK4's loop alone.

Measured on the 2-core machine shared with three other engineers' builds (rustc 1.95), so wall
times swing by up to 2.5x with the load; CPU seconds (user + system of the build) are steadier.
`python3 scripts/compile_cost.py --odyn <checkout>`:

  before: commit 6b17856, one `let` per value in one block
            case  profile  wall s   CPU s  peak MiB  result
    stencil:1024      dev    13.3    12.8       479  rustc SIGSEGV (stack overflow)
    stencil:1024  release    12.2    11.0       411  ok
    stencil:4096      dev    88.7    80.6      2075  rustc SIGSEGV (stack overflow)
    stencil:4096  release   104.5    86.6      1305  ok
      terms:3000      dev    45.2    39.6       783  rustc SIGSEGV (stack overflow)
      terms:3000  release    44.1    42.3       483  ok

  before, with rustc's stack raised (RUST_MIN_STACK=268435456), dev only
    stencil:1024      dev    19.4    16.4       687  ok
    stencil:4096      dev   154.1   136.7     13971  ok
      terms:3000      dev    89.5    84.7      3532  ok

  after: at most 256 `let`s in a row, longer runs in blocks (macros/src/generate/code.rs)
    stencil:1024      dev    29.6    14.4       464  ok
    stencil:1024  release    22.0    11.6       414  ok
    stencil:4096      dev   419.8   163.1      1253  ok
    stencil:4096  release   117.3    79.5      1394  ok
      terms:3000      dev    58.2    51.2       773  ok
      terms:3000  release    45.1    43.0       509  ok

The Jacobian and the derivative at a fixed state are the same bit for bit before and after, in
release, for all three models.

  methods as types (issue 52; commit 3dd4fb8, another engineer's build running beside it)
            case  profile  wall s   CPU s  peak MiB  result
        chosen:1      dev    12.2     7.3       475  ok
        chosen:1  release     6.1     4.0       242  ok
         typed:1      dev     7.2     3.3       453  ok
         typed:1  release     1.5     1.5       221  ok
        chosen:4      dev    24.1    19.5       486  ok
        chosen:4  release    12.9    10.6       279  ok
         typed:4      dev     8.3     6.5       459  ok
         typed:4  release     7.1     3.6       231  ok

Usage: python3 scripts/compile_cost.py [--cases stencil:1024,stencil:4096,terms:3000]
                                        [--profiles dev,release] [--odyn PATH] [--scratch DIR]
"""

import argparse
import os
import pathlib
import random
import re
import shutil
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent


def program(state, body, init, integrator="ImplicitEuler"):
    """A model file: `Big` with `state`, `fn derivative` with `body`, a `main` running it."""
    return f"""
use odyn::prelude::*;

#[system(integrator = {integrator}, dt = 0.01)]
pub struct Big {{
{state}
}}

#[system]
impl Big {{
    fn derivative(&self) -> BigState {{
{body}
    }}
}}

fn main() {{
    let model = Big {{ {init} }};
    let run = model.simulate().steps(10).run().unwrap();
    println!("{{:?}}", run.samples.last().unwrap().state.as_slice()[0]);
}}
"""


def stencil(n):
    side = round(n ** 0.5)
    assert side * side == n, "stencil N must be a square"
    rows = []
    for i in range(side):
        for j in range(side):
            neighbours = [
                f"self.u[{a * side + b}]"
                for a, b in ((i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1))
                if 0 <= a < side and 0 <= b < side
            ]
            rows.append(f"self.k * ({' + '.join(neighbours)} - 4.0 * self.u[{i * side + j}])")
    body = "        BigState {\n            u: [\n                " + \
        ",\n                ".join(rows) + "\n            ],\n        }"
    return program(f"    #[state]\n    pub u: [f64; {n}],\n    pub k: f64,", body,
                   f"u: [0.1; {n}], k: 1.0")


def terms(n, lets=30, size=30):
    rng = random.Random(1)
    statements = ["        let y = self.y;"]
    for k in range(lets):
        products = [
            f"{rng.uniform(0.1, 1.0):.3f} * y[{rng.randrange(size)}] * y[{rng.randrange(size)}]"
            for _ in range(n // lets)
        ]
        statements.append(f"        let a{k} = " + " + ".join(products) + ";")
    values = ", ".join(f"a{k % lets}" for k in range(size))
    statements.append(f"        BigState {{ y: [{values}] }}")
    return program(f"    #[state]\n    pub y: [f64; {size}],", "\n".join(statements),
                   f"y: [0.01; {size}]")


def dense(n):
    return program(f"    #[state]\n    pub y: odyn::nalgebra::SVector<f64, {n}>,\n    pub k: f64,",
                   "        BigState { y: -self.y * (self.k * self.y.norm_squared()) }",
                   "y: odyn::nalgebra::SVector::from_element(0.1), k: 1.0")


def chain(n):
    rows = []
    for i in range(n):
        left = f"self.y[{i - 1}]" if i > 0 else "0.0"
        right = f"self.y[{i + 1}]" if i + 1 < n else "0.0"
        rows.append(f"self.k * ({left} - 2.0 * self.y[{i}] + {right})")
    body = "        BigState {\n            y: [\n                " + \
        ",\n                ".join(rows) + "\n            ],\n        }"
    return program(f"    #[state]\n    pub y: [f64; {n}],\n    pub k: f64,", body,
                   f"y: [0.1; {n}], k: 1.0")


def springs(n, run):
    """N damped springs, each its own model type, each run once by `run`."""
    models = []
    for i in range(n):
        models.append(f"""
#[system(dt = 0.01)]
pub struct Spring{i} {{
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub k: f64,
}}

#[system]
impl Spring{i} {{
    fn acceleration(&self) -> f64 {{
        -self.k * self.x - 0.1 * self.v
    }}
}}
""")
    runs = "\n".join(
        f"    let run = Spring{i} {{ x: 1.0, v: 0.0, k: {i + 1}.0 }}.simulate().steps(100){run}.unwrap();\n"
        f"    println!(\"{{}}\", run.last().state.x);" for i in range(n))
    return "use odyn::prelude::*;\n" + "".join(models) + f"\nfn main() {{\n{runs}\n}}\n"


def chosen(n):
    return springs(n, ".integrator(Method::Rk4).run()")


def typed(n):
    return springs(n, ".run_with::<method::Rk4>()")


KINDS = {"stencil": stencil, "terms": terms, "dense": dense, "chain": chain, "chosen": chosen,
         "typed": typed}

MANIFEST = """[package]
name = "{name}"
version = "0.0.0"
edition = "2024"

[dependencies]
odyn = {{ path = "{odyn}", default-features = false }}

# The workspace's dev profile (its root Cargo.toml), with this crate in the place of `odyn`.
[profile.dev]
opt-level = 2
[profile.dev.package."*"]
opt-level = 3
[profile.dev.package.odyn-runtime]
opt-level = 3

[workspace]
"""


def measure(kind, n, profile, scratch, odyn):
    """Seconds, peak MiB and the outcome of building case `kind` `n` in `profile`."""
    name = f"compile-cost-{kind}{n}"
    crate = scratch / f"{kind}{n}"
    (crate / "src").mkdir(parents=True, exist_ok=True)
    (crate / "Cargo.toml").write_text(MANIFEST.format(name=name, odyn=odyn))
    # The checkout's dependency versions (cargo drops what the crate does not use).
    lock = pathlib.Path(odyn) / "Cargo.lock"
    if lock.exists() and not (crate / "Cargo.lock").exists():
        shutil.copy(lock, crate / "Cargo.lock")
    target = scratch / "target"
    env = dict(os.environ, CARGO_TARGET_DIR=str(target))
    flags = ["--release"] if profile == "release" else []
    # Dependencies first, with a trivial main, so the timed build is the model crate alone.
    (crate / "src" / "main.rs").write_text("fn main() {}\n")
    subprocess.run(["cargo", "build", "--quiet", *flags], cwd=crate, env=env, check=True,
                   capture_output=True)
    # No incremental state left from an earlier run of the same case.
    shutil.rmtree(target / ("release" if profile == "release" else "debug") / "incremental",
                  ignore_errors=True)
    (crate / "src" / "main.rs").write_text(KINDS[kind](n))
    start = time.time()
    out = subprocess.run(["/usr/bin/time", "-v", "cargo", "build", "--quiet", *flags],
                         cwd=crate, env=env, capture_output=True, text=True)
    seconds = time.time() - start
    peak = re.search(r"Maximum resident set size \(kbytes\): (\d+)", out.stderr)
    mib = int(peak.group(1)) / 1024 if peak else float("nan")
    cpu = sum(float(m) for m in re.findall(r"(?:User|System) time \(seconds\): ([\d.]+)", out.stderr))
    if out.returncode == 0:
        outcome = "ok"
    elif "overflowed its stack" in out.stderr:
        outcome = "rustc SIGSEGV (stack overflow)"
    else:
        outcome = next((l for l in out.stderr.splitlines() if l.startswith("error")), "failed")
    return seconds, cpu, mib, outcome


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cases", default="stencil:1024,stencil:4096,terms:3000")
    parser.add_argument("--profiles", default="dev,release")
    parser.add_argument("--scratch", default="/tmp/odyn-compile-cost")
    parser.add_argument("--odyn", default=str(ROOT), help="the odyn checkout to measure")
    args = parser.parse_args()
    scratch = pathlib.Path(args.scratch)
    print(f"{'case':>14} {'profile':>8} {'wall s':>7} {'CPU s':>7} {'peak MiB':>9}  result")
    for case in args.cases.split(","):
        kind, n = case.split(":")
        for profile in args.profiles.split(","):
            seconds, cpu, mib, outcome = measure(kind, int(n), profile, scratch, args.odyn)
            print(f"{case:>14} {profile:>8} {seconds:7.1f} {cpu:7.1f} {mib:9.0f}  {outcome}")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
