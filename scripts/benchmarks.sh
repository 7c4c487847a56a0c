#!/usr/bin/env bash
# Runs odyn's benchmarks and rewrites BENCHMARKS.md: every divan bench of the workspace and of
# peers/ (its own workspace), the SciPy scripts, the stiff test-set example and the compile-cost
# script, each section headed by its command, the machine, the date and the commit
# (scripts/benchmarks.py does the work and the formatting).
#
#     bash scripts/benchmarks.sh            # everything: about an hour on 2 cores, once built
#     bash scripts/benchmarks.sh --list     # the sections and their commands
#     bash scripts/benchmarks.sh jacobian peers_stiff   # some of them
#
# Needs: the toolchain of rust-toolchain.toml; python3 with numpy, scipy and mpmath (the SciPy
# sections); libsundials-dev (the CVODE peer in peers_stiff; apt-get install libsundials-dev).
# Not part of CI: the numbers are the machine's, and the machine is shared.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v python3 >/dev/null || { echo "benchmarks: python3 is needed" >&2; exit 1; }
exec python3 scripts/benchmarks.py "$@"
