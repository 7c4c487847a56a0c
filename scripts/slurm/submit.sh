#!/bin/sh
# The pendulum ensemble of examples/monte_carlo.rs on Slurm, from the repository's root:
#   sh scripts/slurm/submit.sh N      runs it in N shards (array tasks 0 … N−1) and merges them;
#   sh scripts/slurm/submit.sh N K    runs shard K of N again (K may be a list: 1,4) and merges.
# Waits for the merge; exits non-zero, with Slurm's account of the merge job, when it failed or
# was cancelled. Shard files, the statistics and the jobs' logs go to out/slurm/.
set -eu
# Build once: every task runs this binary (tasks running cargo would queue on its lock).
cargo build --release --example monte_carlo
mkdir -p out/slurm
if [ $# -eq 1 ]; then
  # Task k of an array of N runs shard k/N ($SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT).
  array=$(sbatch --parsable --array="0-$(($1 - 1))" scripts/slurm/shard.sbatch)
else
  # Tasks run again form an array of their own, of another size: they are told N.
  array=$(sbatch --parsable --array="$2" scripts/slurm/shard.sbatch "$1")
fi
# The merge starts once every task has succeeded, and is cancelled if one fails.
merge=$(sbatch --parsable --wait --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  scripts/slurm/merge.sbatch "$1") || true
# `sbatch --wait` exits with the merge's status, but with 0 when Slurm cancelled the merge: ask
# Slurm how it ended.
scontrol show job "${merge:?the merge was not submitted}" | grep -q JobState=COMPLETED || {
  scontrol show job "$merge" >&2
  exit 1
}
