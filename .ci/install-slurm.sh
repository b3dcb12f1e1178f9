#!/usr/bin/env bash
# Installs Debian's slurm-wlm for the fleet's Slurm test (tests/fleet_lot.rs
# runs a lot as a job array on a single-node Slurm it starts itself, with
# scripts/slurm-single-node.sh). Where it cannot install (not root, no
# apt-get, no registry), it says so and exits 0: the test then prints a
# notice and passes without Slurm.
set -uo pipefail
if command -v sbatch >/dev/null && command -v slurmctld >/dev/null && command -v slurmd >/dev/null; then
    exit 0
fi
if [[ $(id -u) -ne 0 ]] || ! command -v apt-get >/dev/null; then
    echo "notice: cannot install slurm-wlm here (needs root and apt-get); the Slurm test will be skipped" >&2
    exit 0
fi
export DEBIAN_FRONTEND=noninteractive
if ! { apt-get update -qq && apt-get install -y -qq --no-install-recommends slurm-wlm >/dev/null; }; then
    echo "notice: apt-get install slurm-wlm failed; the Slurm test will be skipped" >&2
fi
exit 0
