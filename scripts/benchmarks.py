#!/usr/bin/env python3
"""Runs odyn's benchmarks and writes BENCHMARKS.md (through scripts/benchmarks.sh).

Every section of BENCHMARKS.md is one command: a divan bench of the workspace or of peers/, a
SciPy script, an example, the compile-cost script. Running a section runs its command, keeps
its raw output in target/benchmarks/<name>.log, and rewrites that section of BENCHMARKS.md:
its heading, the command, the machine, the date and the commit, then divan's timings as a
Markdown table (with each row's median over its group's baseline, when the group has one) and
anything else the command printed (calibrations, the scripts' tables) verbatim. Sections not
run keep what they had; the past-measurements section at the end is never touched.

    python3 scripts/benchmarks.py [--list] [SECTION ...]     # no SECTION: all of them
    python3 scripts/benchmarks.py --rerender [SECTION ...]   # reformat from the kept logs
"""

import os
import platform
import re
import subprocess
import sys
import time
from datetime import datetime, timezone
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "BENCHMARKS.md"
LOGS = ROOT / "target" / "benchmarks"
PEERS = ["--manifest-path", "peers/Cargo.toml"]

# name, title, command (run from the repository root), what it measures.
SECTIONS = [
    ("generated_vs_hand", "Generated code against hand-written loops",
     ["cargo", "bench", "--bench", "generated_vs_hand"],
     "10⁶ steps of each generated model under each integrator, beside the same arithmetic "
     "written by hand in the same process (`generated`: the `Integrator` trait driven directly; "
     "`runner`: the whole `Simulation::run`). ÷ baseline is over the hand-written loop of the "
     "same method: about 1 is parity."),
    ("deterministic", "The `deterministic` feature's cost",
     ["cargo", "bench", "--bench", "generated_vs_hand", "--features", "deterministic", "--",
      "double_pendulum"],
     "10⁵ RK4 steps of the double pendulum with every transcendental function through `libm`, "
     "against the hand-written loop, which keeps the platform's functions. Compare with the "
     "`double_pendulum` rows of the section above (the platform's functions in both)."),
    ("jacobian", "Jacobians: generated, hand-written, dual numbers, differences",
     ["cargo", "bench", "--bench", "jacobian"],
     "One evaluation of ∂f/∂y by each way a user could get it (every variant `#[inline(never)]`, "
     "so each pays one call), and one implicit Euler step against one RK4 step."),
    ("particles", "One implicit cloth step, by size",
     ["cargo", "bench", "--bench", "particles"],
     "One Baraff–Witkin step of the `cloth` example's sheet at rest (k = 10⁴) and its parts: "
     "kernel blocks, assembly, numeric Cholesky, solve (`step_falling`: from the falling cloth "
     "at t = 0.5 s); the quasi-Newton step at its defaults (8 L-BFGS iterations; "
     "`step_quasi_newton`, `step_quasi_newton_falling`) and its one-time set-up "
     "(`setup_quasi_newton`: link weights, symbolic and numeric factorization of the link "
     "Laplacian); and half a second of the falling cloth, Cholesky against block-Jacobi CG."),
    ("gray_scott", "Gray–Scott: one implicit step by size, and Krylov solves",
     ["cargo", "bench", "--bench", "gray_scott", "--", "--skip", "equal_accuracy"],
     "One linearized implicit Euler step at Pearson's set-up (h = 10) and its parts (`jacobian`, "
     "`assembly`, `factorization` (sparse LU; `factorization_symmetric`: Cholesky of the "
     "symmetric matrix at the background state), `solve`), the step with Krylov solves "
     "(`step_krylov`: block Jacobi, `step_ilu`, `step_multigrid`), ten full-Newton steps "
     "(`run_direct` against `run_krylov`), the explicit rate against a hand-written loop, and "
     "1000 explicit steps through the runner against the bare integrator. The argument is the "
     "grid's side."),
    ("gray_scott_equal_accuracy", "Gray–Scott at equal error",
     ["cargo", "bench", "--bench", "gray_scott", "--", "equal_accuracy"],
     "Whole solves of \"coral\" on 64² cells to t = 500, each method at the loosest half-decade "
     "tolerance whose final error is within the target (printed first) against a DOP853 "
     "reference at rtol 1e-12; the SciPy side is `scipy_gray_scott` below."),
    ("fluids", "Stable Fluids: one step by size",
     ["cargo", "bench", "--bench", "fluids"],
     "One step of the `smoke` example's plume at 32² to 256² cells, and the projection's "
     "Cholesky substitution alone."),
    ("sph", "SPH: one step by size",
     ["cargo", "bench", "--bench", "sph"],
     "One step of the dam break at 10 to 80 particles across the column (the argument), after "
     "100 steps of collapse."),
    ("mpm", "MLS-MPM: the 88-line program's substep by size and threads",
     ["cargo", "bench", "--bench", "mpm"],
     "One substep of the 88-line MLS-MPM program's scene (`scenes::hybrid::mpm88`) at 8 192, "
     "32 768 and 131 072 particles (grids of 128², 256², 512²), after 100 substeps: `Mpm::step` "
     "on 1 and 2 rayon threads (bit-identical), beside `hand`, the program transliterated as a "
     "plain serial loop. Taichi's times on the same scene: the next section."),
    ("taichi_mpm88", "MLS-MPM against Taichi on the 88-line program's scene",
     ["python3", "scripts/taichi_mpm88.py", "--sizes", "8192,32768,131072"],
     "Taichi 1.7.4's CPU backend (double precision, 2 and 1 threads) and odyn's "
     "`examples/mpm88.rs` (1 and 2 rayon threads) from the same positions, ms per substep, "
     "best of 3; the last column is the largest difference of a particle's position between "
     "the two programs after 20 substeps, which shows the scene is the same. The issue's "
     "target is Taichi on 2 threads ÷ odyn on 2 threads ≥ 2.5."),
    ("continua", "The continuum methods at a common resolution",
     ["cargo", "bench", "--bench", "continua"],
     "One step of SPH, FLIP 0.95, APIC and MPM water on Martin & Moyce's dam break at 3 200 "
     "particles (40 across the column for SPH, 20 cells across it for the grids), after 50 "
     "steps of collapse, and of Stable Fluids on the same 100 × 60 grid. Steps differ in "
     "length: `examples/continua.rs` prints the cost per simulated second."),
    ("stiff_suite", "The Bari stiff test set",
     ["cargo", "run", "--profile", "bench", "--example", "stiff_suite"],
     "Rodas5P and Rosenbrock23 over a sweep of tolerances and implicit Euler over a sweep of "
     "steps on Robertson, HIRES, POLLU and van der Pol, against the test set's reference final "
     "states: error, steps and time of each run."),
    ("peers_fixed_step", "Peers: fixed-step methods",
     ["cargo", "bench", *PEERS, "--bench", "fixed_step"],
     "RK4 and implicit Euler against hand-written loops, `ode_solvers` and "
     "`differential-equations`; every variant's final state is checked first (printed)."),
    ("peers_adaptive", "Peers: adaptive methods at equal error",
     ["cargo", "bench", *PEERS, "--bench", "adaptive"],
     "Tsit5 and DOP853 against `ode_solvers`, `differential-equations` and diffsol on Lorenz, "
     "Arenstorf and the Pleiades. Each solver's tolerance is calibrated to the target error "
     "(printed first: the loosest tolerance of a quarter-decade sweep meeting it), never equal "
     "tolerances. ÷ baseline is over odyn's fastest method in the group."),
    ("peers_stiff", "Peers: stiff methods at equal error, CVODE included",
     ["cargo", "bench", *PEERS, "--bench", "stiff"],
     "Rodas5P, Rosenbrock23 and BDF against diffsol, `differential-equations` and SUNDIALS "
     "CVODE (C, dense direct solver) on Robertson, HIRES, POLLU and OREGO, each solver "
     "calibrated to the target error (printed first, with steps, f, J and LU counts). Needs "
     "`libsundials-dev`. ÷ baseline is over odyn's fastest method in the group."),
    ("peers_sensitivity", "Peers: forward sensitivities",
     ["cargo", "bench", *PEERS, "--bench", "sensitivity"],
     "Robertson's state and its sensitivities to the three rates, odyn against diffsol's "
     "forward sensitivities, each calibrated to the same error against a reference (printed "
     "first)."),
    ("scipy_adaptive", "SciPy: adaptive methods at equal error",
     ["python3", "scripts/scipy_adaptive.py"],
     "SciPy's DOP853 and RK45 on the adaptive peers' problems with the same calibration; "
     "Python right-hand sides (NumPy for the Pleiades), best of 5 `solve_ivp` calls."),
    ("scipy_stiff", "SciPy: stiff methods at equal error",
     ["python3", "scripts/scipy_stiff.py"],
     "SciPy's Radau, BDF and LSODA on the stiff peers' problems with the same calibration and "
     "analytic Jacobians, best of 5 `solve_ivp` calls."),
    ("scipy_gray_scott", "SciPy: Gray–Scott at equal error",
     ["python3", "scripts/scipy_gray_scott.py"],
     "SciPy's BDF (with `jac_sparsity`), RK45 and DOP853 on the `gray_scott` bench's "
     "equal-accuracy problem, best of 3."),
    ("scipy_fit_robertson", "SciPy: fitting Robertson's rates",
     ["python3", "scripts/scipy_fit_robertson.py"],
     "The `fit_robertson` example's fit, and the same fit by `least_squares` driving "
     "`solve_ivp` on the same data, weights, guess and search variables (needs the example "
     "built in target/release, which this section does first)."),
    ("scipy_tradeoff", "SciPy against odyn on the tradeoff scenes",
     ["python3", "scripts/scipy_tradeoff.py"],
     "For each SciPy run (RK45, DOP853, Radau over a sweep of tolerances), odyn's fastest run "
     "of the `tradeoff` example at least as accurate, fixed-step or adaptive (this section runs "
     "the example first). The SciPy right-hand sides are Python, so much of the gap is the "
     "interpreter, not the algorithm."),
    ("compile_cost", "Compile cost of big models",
     ["python3", "scripts/compile_cost.py", "--cases",
      "dense:40,dense:200,chain:1000,dense:1000,stencil:1024,terms:3000",
      "--profiles", "dev,release"],
     "Wall and CPU seconds and peak memory of `cargo build` of a crate holding one big "
     "`#[system]` model alone (dependencies built beforehand): dense models of n² structural "
     "non-zeros, a written-out 1-D chain and 2-D stencil, and 3 000 terms in 30 `let`s."),
]

# Divan arguments that are indices into a bench's own list, named for the table.
LABELS = {
    ("gray_scott_equal_accuracy", "equal_accuracy"): [
        "Tsit5 1e-3", "Tsit5 1e-6", "DOP853 1e-3", "DOP853 1e-6", "Rosenbrock23 1e-3",
        "Rosenbrock23 1e-6", "Rodas5P 1e-3", "Rodas5P 1e-6"],  # benches/gray_scott.rs, RACES
}

# Benchmarks a section's command skips (`--skip`), left out when its log is rendered again.
SKIPS = {"gray_scott": ["equal_accuracy"]}

# Commands a section needs run first (not timed, not recorded). Examples are built with the
# bench profile (the release profile with line tables), so they reuse the benches' build in
# target/release instead of building every dependency a second time.
BEFORE = {
    "scipy_fit_robertson": [["cargo", "build", "--profile", "bench", "--example", "fit_robertson"]],
    "scipy_tradeoff": [["cargo", "run", "--profile", "bench", "--example", "tradeoff"]],
}

HEADER = """# Benchmarks

Every measurement of odyn in one place. Each section below is regenerated by one command, shown
under its heading with the machine, the date and the commit it ran on; `bash
scripts/benchmarks.sh` reruns them all and rewrites this file (`bash scripts/benchmarks.sh NAME…`
reruns some; `--list` names them). Only the last section, past measurements without a bench,
is kept by hand.

**Read the numbers as of one run on a shared machine.** They were taken on a 2-core virtual
machine that other engineers' builds share, so a time can move by ±10–25 % between runs and
more under load (the load average at each section's start is given). Compare within a table —
the rows of a table ran side by side in one process — rather than across tables or dates. The
peer comparisons are at equal accuracy: each solver's tolerance is calibrated to the same error
against a reference, never set equal. Divan's times are per iteration of the benchmarked
closure; "÷ baseline" is a row's fastest time over its group's baseline's (the hand-written
loop, or odyn's fastest method): on a loaded machine the fastest of many samples is the one
least disturbed by other processes, where the medians move with the load. The peer benches
live in `peers/`, a workspace of their own that `cargo test` never builds; the SciPy scripts
need `pip install numpy scipy mpmath`, the CVODE peer `apt-get install libsundials-dev`.
"""

PAST_MARK = "<!-- past measurements: kept by hand below this line -->"


def machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    cores = os.cpu_count()
    try:
        kib = int(re.search(r"MemTotal:\s+(\d+)", Path("/proc/meminfo").read_text()).group(1))
        memory = f", {kib / 1024 / 1024:.0f} GiB"
    except (OSError, AttributeError):
        memory = ""
    rustc = subprocess.run(["rustc", "--version"], capture_output=True, text=True, cwd=ROOT)
    return f"{cpu}, {cores} cores{memory}, {platform.system()}; {rustc.stdout.strip()}"


def commit() -> str:
    head = subprocess.run(["git", "rev-parse", "--short=10", "HEAD"], capture_output=True,
                          text=True, cwd=ROOT).stdout.strip()
    # Uncommitted changes to what is measured (sources, manifests, locks), not to the docs
    # (BENCHMARKS.md itself changes as the run goes).
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "--",
                            "*.rs", "*Cargo.toml", "*Cargo.lock", "*.py", "*.c"],
                           capture_output=True, text=True, cwd=ROOT).stdout.strip()
    return head + (" with uncommitted changes to the code" if dirty else "")


# ------------------------------------------------------------------------------------------
# divan's output as rows.

UNITS = {"ps": 1e-12, "ns": 1e-9, "µs": 1e-6, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def seconds(text: str):
    match = re.fullmatch(r"\s*([\d.]+)\s*(ps|ns|µs|us|ms|s)\s*", text)
    return float(match.group(1)) * UNITS[match.group(2)] if match else None


TIME = r"[\d.]+ (?:ps|ns|µs|us|ms|s)"


def parse_divan(lines):
    """(rows, other): rows are (path, fastest, median, mean, samples) for every timed leaf of
    divan's tree tables, other the lines that belong to none. A bench that prints while it runs
    (a calibration on its first sample) splits its row: the name, the printed lines, then the
    times on a line of their own; the row is put back together."""
    rows, other, stack, in_table, pending = [], [], [], False, None

    def add(path, fastest, cells):
        # cells: [name and fastest, slowest, median, mean, samples, iterations]
        if len(cells) >= 5 and cells[2].strip():
            rows.append((path, fastest, cells[2].strip(), cells[3].strip(), cells[4].strip()))

    for line in lines:
        if re.search(r"\bfastest\s+│\s+slowest\s+│\s+median", line):
            stack, in_table, pending = [line.split()[0]], True, None
            continue
        branch = re.search(r"[├╰]─ ", line)
        if in_table and branch:
            depth = branch.start() // 3
            cells = line[branch.end():].split("│")
            head = re.match(rf"^(.*?)\s+({TIME})\s*$", cells[0].strip())
            if head:
                name = head.group(1)
            else:
                parts = re.split(r"\s{2,}", cells[0].strip(), maxsplit=1)
                name = parts[0]
                if len(parts) == 2:
                    other.append(parts[1])  # the start of what the bench printed
            stack = stack[: depth + 1] + [name]
            pending = None
            if head:
                add(stack[1:], head.group(2), cells)
            elif len(cells) == 1:
                pending = stack[1:]  # its times come after what the bench printed
            continue
        resumed = re.match(rf"^\s*({TIME})\s*│(.*)$", line)
        if in_table and pending and resumed:
            add(pending, resumed.group(1), ["", *resumed.group(2).split("│")])
            pending = None
            continue
        if in_table and "│" in line:
            continue  # a throughput or counter line under a row
        if line.startswith("Timer precision"):
            continue
        if not pending:
            in_table = False
        other.append(line)
    return rows, other


HAND = re.compile(r"^(?:(.*)_)?hand(?:_written)?$")


def baseline(row, siblings):
    """The fastest time a row is divided by: the hand-written variant beside it (`hand`,
    `hand_written`, or `<prefix>_hand` for the rows named `<prefix>_…`), else odyn's fastest
    variant when the group also holds other libraries' (the peers); None without one."""
    name = row[0][-1]
    for sibling in siblings:
        match = HAND.match(sibling[0][-1])
        if match and (match.group(1) is None or name.startswith(match.group(1) + "_")):
            return seconds(sibling[1])
    ours = [seconds(r[1]) for r in siblings if r[0][-1].startswith("odyn")]
    others = [r for r in siblings if not r[0][-1].startswith("odyn")]
    ours = [s for s in ours if s]
    if ours and others:
        return min(ours)
    return None


def table(rows) -> str:
    groups = {}
    for row in rows:
        groups.setdefault(tuple(row[0][:-1]), []).append(row)
    bases = [baseline(row, groups[tuple(row[0][:-1])]) for row in rows]
    with_ratio = any(bases)
    head = "| benchmark | fastest | median | mean | samples |" + (" ÷ baseline |" if with_ratio else "")
    rule = "|---|---:|---:|---:|---:|" + ("---:|" if with_ratio else "")
    out = [head, rule]
    for row, base in zip(rows, bases):
        path, fastest, median, mean, samples = row
        cells = [" / ".join(path), fastest, median, mean, samples]
        if with_ratio:
            value = seconds(fastest)
            cells.append(f"{value / base:.2f}" if base and value else "")
        out.append("| " + " | ".join(cells) + " |")
    return "\n".join(out)


CARGO_STATUS = re.compile(r"^\s*(Compiling|Finished|Running|Blocking|Fresh|Updating|Locking|"
                          r"Downloading|Downloaded|Adding|Checking|Executable)\b")


def render(name, title, command, about, log_lines, started, load, finished_ok, elapsed) -> str:
    log_lines = [line for line in log_lines if not CARGO_STATUS.match(line)]
    rows, other = parse_divan(log_lines)
    rows = [r for r in rows if r[0][0] not in SKIPS.get(name, [])]
    for i, row in enumerate(rows):
        labels = LABELS.get((name, row[0][0]))
        if labels and len(row[0]) == 2 and row[0][1].isdigit() and int(row[0][1]) < len(labels):
            rows[i] = ([row[0][0], labels[int(row[0][1])]], *row[1:])
    while other and not other[0].strip():
        other.pop(0)
    while other and not other[-1].strip():
        other.pop()
    shown = " ".join(command)
    parts = [
        f"<!-- section: {name} -->",
        f"## {title}",
        "",
        f"`{shown}` — {started}, commit {commit()}; {machine()}; load average "
        f"{load:.1f} at the start, {elapsed:.0f} s in all.",
        "",
        about,
        "",
    ]
    if not finished_ok:
        parts += ["**The command failed**; its output up to the failure:", ""]
    if other:
        parts += ["```text", *other, "```", ""]
    if rows:
        parts += [table(rows), ""]
    parts.append(f"<!-- end: {name} -->")
    return "\n".join(parts)


# ------------------------------------------------------------------------------------------
# BENCHMARKS.md, section by section.

def read_sections(text: str):
    sections = {}
    for match in re.finditer(r"<!-- section: (\w+) -->.*?<!-- end: \1 -->", text, re.S):
        sections[match.group(1)] = match.group(0)
    past = text[text.index(PAST_MARK):] if PAST_MARK in text else PAST_MARK + "\n"
    return sections, past


def write(sections, past):
    parts = [HEADER]
    contents = ["## Contents", ""]
    for name, title, command, _ in SECTIONS:
        anchor = re.sub(r"[^\w\- ]", "", title.lower()).replace(" ", "-")
        contents.append(f"- [{title}](#{anchor})")
    contents.append("- [Past measurements](#past-measurements)")
    parts.append("\n".join(contents) + "\n")
    for name, title, command, about in SECTIONS:
        parts.append(sections.get(name) or "\n".join([
            f"<!-- section: {name} -->", f"## {title}", "",
            f"`{' '.join(command)}` — not run yet.", "", f"<!-- end: {name} -->"]))
        parts.append("")
    parts.append(past.rstrip() + "\n")
    OUT.write_text("\n".join(parts), encoding="utf-8")


def run(name, title, command, about) -> str:
    LOGS.mkdir(parents=True, exist_ok=True)
    for before in BEFORE.get(name, []):
        subprocess.run(before, cwd=ROOT, check=False, stdout=subprocess.DEVNULL)
    load = os.getloadavg()[0]
    started = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    print(f"benchmarks: {name}: {' '.join(command)}", flush=True)
    begin = time.time()
    log = LOGS / f"{name}.log"
    # Both streams, in the order they were written: some benches print their calibration on
    # standard error (cargo's own progress lines are dropped when the log is rendered).
    with open(log, "w", encoding="utf-8") as out:
        done = subprocess.run(command, cwd=ROOT, stdout=out, stderr=subprocess.STDOUT, text=True)
    elapsed = time.time() - begin
    lines = log.read_text(encoding="utf-8").splitlines()
    print(f"benchmarks: {name}: {'ok' if done.returncode == 0 else 'FAILED'} in {elapsed:.0f} s",
          flush=True)
    return render(name, title, command, about, lines, started, load, done.returncode == 0,
                  elapsed)


def rerender(name, title, command, about, old: str) -> str:
    """The section rebuilt from its kept log and its old heading line (after a change to this
    script's formatting), without running anything."""
    meta = re.search(r"^`[^\n]*— (.*)$", old, re.M)
    lines = (LOGS / f"{name}.log").read_text(encoding="utf-8").splitlines()
    section = render(name, title, command, about, lines, "", 0.0, "**The command failed**" not in old,
                     0.0)
    if meta:
        section = re.sub(r"^(`[^\n]*— ).*$", lambda m: m.group(1) + meta.group(1), section,
                         count=1, flags=re.M)
    return section


def main() -> int:
    args = sys.argv[1:]
    known = {s[0]: s for s in SECTIONS}
    if "--rerender" in args:
        names = [a for a in args if a != "--rerender"] or [s[0] for s in SECTIONS]
        sections, past = read_sections(OUT.read_text(encoding="utf-8"))
        for name in names:
            if name in sections and (LOGS / f"{name}.log").exists():
                sections[name] = rerender(*known[name], sections[name])
        write(sections, past)
        return 0
    if "--list" in args:
        for name, title, command, _ in SECTIONS:
            print(f"{name:<22}{' '.join(command)}")
        return 0
    unknown = [a for a in args if a not in known]
    if unknown:
        print(f"benchmarks: unknown section(s) {', '.join(unknown)}; --list names them")
        return 2
    chosen = args or [s[0] for s in SECTIONS]
    sections, past = read_sections(OUT.read_text(encoding="utf-8") if OUT.exists() else "")
    failed = []
    for name in chosen:
        sections[name] = run(*known[name])
        if "**The command failed**" in sections[name]:
            failed.append(name)
        write(sections, past)  # after every section, so an interrupted run keeps what it did
    if failed:
        print(f"benchmarks: failed: {', '.join(failed)} (their sections show the output)")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
