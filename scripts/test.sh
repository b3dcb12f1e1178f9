#!/usr/bin/env bash
# The project's tests, as the README and CI (.ci/run) run them: the Rust
# workspace, then the Python package (scripts/python-tests.sh; skipped with a
# notice where there is no Python). Arguments go to `cargo test`.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace --release "$@"
bash scripts/python-tests.sh
