"""python/Cargo.lock keeps the main workspace's version of every crate both
build: the binding must compute with the code the `rbf` binary runs (its numbers
are compared to the CLI's), and a version moved in one lock file only would
drift silently. Fix: copy Cargo.lock over python/Cargo.lock and build once in
python/ (cargo adds the binding's own crates and keeps the rest)."""

import re

from conftest import REPO


def versions(lock):
    text = (REPO / lock).read_text()
    found = {}
    for name, version in re.findall(r'\[\[package\]\]\nname = "([^"]+)"\nversion = "([^"]+)"', text):
        found.setdefault(name, set()).add(version)
    return found


def test_shared_crates_have_the_workspace_versions():
    main, binding = versions("Cargo.lock"), versions("python/Cargo.lock")
    assert {"rbf", "faer", "pyo3"} <= set(binding)
    shared = set(main) & set(binding)
    assert len(shared) > 50
    # the main workspace may hold more versions of a crate (other members need them)
    moved = {n: (main[n], binding[n]) for n in shared if not binding[n] <= main[n]}
    assert not moved, f"versions differ (Cargo.lock, python/Cargo.lock): {moved}"
