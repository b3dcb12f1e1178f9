#!/usr/bin/env bash
# The project's tests, as the README and CI (.ci/run) run them: the Rust
# workspace (with slurm-wlm installed first where root and apt-get can:
# .ci/install-slurm.sh), then the Python package (scripts/python-tests.sh; skipped with a
# notice where there is no Python). Arguments go to `cargo test`.
set -euo pipefail
cd "$(dirname "$0")/.."
# Debian's slurm-wlm for the fleet's Slurm test, where it can be installed.
bash .ci/install-slurm.sh
cargo test --workspace --release "$@"
bash scripts/python-tests.sh
