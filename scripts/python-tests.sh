#!/usr/bin/env bash
# The Python package's tests (python/, issue 36 §4), after `cargo test`
# (scripts/test.sh runs both):
#   1. a virtual environment with python/requirements-test.txt's pinned packages,
#      made once and kept in target/python-venv (remade when the pins change);
#   2. the binding crate's fmt and clippy (it is its own workspace: the main
#      workspace's lints do not see it);
#   3. `pip install ./python`, the README's install, with the pinned maturin;
#   4. pytest python/tests, against the release binaries of this checkout.
# Where there is no Python ≥ 3.9 with venv: a notice, and success.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
py=${PYTHON:-python3}
if ! command -v "$py" >/dev/null 2>&1 ||
    ! "$py" -c 'import sys, venv, ensurepip; sys.exit(sys.version_info < (3, 9))' 2>/dev/null; then
    echo "notice: no Python ≥ 3.9 with venv and ensurepip ('$py'): the Python package's tests (python/tests) are skipped"
    exit 0
fi

venv=$root/target/python-venv
pins=python/requirements-test.txt
if ! cmp -s "$pins" "$venv/requirements-test.txt" 2>/dev/null; then
    echo "python-tests: making $venv from $pins"
    rm -rf "$venv"
    "$py" -m venv "$venv"
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$pins"
    cp "$pins" "$venv/requirements-test.txt"
fi

# One target folder for the workspace and the binding: the crates both build are
# compiled once. The same interpreter and extension-module setting for clippy and
# the wheel, so pyo3's build script does not rerun between them.
export CARGO_TARGET_DIR=$root/target
export PYO3_PYTHON=$venv/bin/python
export PYO3_BUILD_EXTENSION_MODULE=1
export PATH=$venv/bin:$PATH   # the pinned maturin, which pip's build runs
(cd python && cargo fmt --check && cargo clippy --release --all-targets -- -D warnings)
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    --no-deps --no-build-isolation --force-reinstall ./python

cargo build --release -p rbf-cli -p dtg-vib
cd "$root/target"   # not python/: its rbf_dtg folder (no extension) would shadow the installed package
RBF_DTG_REQUIRE_BINARIES=1 RBF_DTG_BIN_DIR=$root/target/release \
    "$venv/bin/python" -m pytest -q -p no:cacheprovider "$root/python/tests" "$@"
