#!/usr/bin/env python3
"""Import circles between the files of one crate (issue 24's acceptance: none
spanning more than two files).

    scripts/import-cycles.py crates/sysid/src [LIMIT]

Reads the crate's src/ as text: an edge from a file to the file of the longest
module prefix of every `crate::a::b`, `super::x`, `self::x` path and, in a
module file, of every `child::x` path of its own child modules (re-exports);
`pub(in path)` visibilities, comments, strings and a trailing #[cfg(test)]
module are not imports. Prints every simple cycle of more than LIMIT files
(default 2: a parent module and its child importing each other is a cycle of
two) and a summary line. A heuristic over text, not the compiler's view: a
path through a re-export counts as an import of the re-exporting file."""
import os, re, sys
src = sys.argv[1]; limit = int(sys.argv[2]) if len(sys.argv) > 2 else 2
files = {}
for root, _, fs in os.walk(src):
    for f in fs:
        if not f.endswith('.rs'): continue
        p = os.path.join(root, f); rel = os.path.relpath(p, src)[:-3].split(os.sep)
        if rel[-1] in ('mod', 'lib', 'main'): rel = rel[:-1]
        if rel and rel[0] == 'bin': continue
        files[tuple(rel)] = p
# A file declared `#[cfg(test)] mod name;` (plot's src/tests.rs) is a test module
# like a trailing inline one: not the crate's structure.
for k, p in list(files.items()):
    for m in re.finditer(r'#\[cfg\(test\)\]\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+(\w+)\s*;', open(p).read()):
        files.pop(k + (m.group(1),), None)
def strip(text):
    # tests are not the crate's structure: drop a trailing #[cfg(test)] module first
    m = re.search(r'#\[cfg\(test\)\]\s*mod\s+\w+\s*\{', text)
    if m: text = text[:m.start()]
    text = re.sub(r"'(\\.|[^'\\])'", "' '", text)
    text = re.sub(r'//[^\n]*', '', text)
    text = re.sub(r'/\*.*?\*/', '', text, flags=re.S)
    text = re.sub(r'"(\\.|[^"\\])*"', '""', text)
    # drop #[cfg(test)] mod tests { ... } at the end (tests are not the crate's structure)
    m = re.search(r'#\[cfg\(test\)\]\s*mod\s+\w+\s*\{', text)
    if m: text = text[:m.start()]
    return text
def resolve(path):
    for k in range(len(path), -1, -1):
        if tuple(path[:k]) in files: return tuple(path[:k])
def expand(text, i):
    # parse a path tree starting at text[i]; return list of paths (list of idents)
    out = []
    def tree(i, prefix):
        while True:
            m = re.match(r'\s*(\w+)\s*', text[i:])
            if m:
                prefix = prefix + [m.group(1)]; i += m.end()
                if text.startswith('::', i):
                    i += 2
                    if re.match(r'\s*\{', text[i:]):
                        i = text.index('{', i) + 1
                        while True:
                            i = tree(i, prefix)
                            m2 = re.match(r'\s*,\s*', text[i:])
                            if m2: i += m2.end()
                            m3 = re.match(r'\s*\}', text[i:])
                            if m3: return i + m3.end()
                            if not m2: return i
                    continue
                out.append(prefix); return i
            m = re.match(r'\s*\*', text[i:])
            if m: out.append(prefix); return i + m.end()
            out.append(prefix); return i
    tree(i, [])
    return out
edges = {k: set() for k in files}
for mod, p in files.items():
    text = strip(open(p).read())
    children = {k[-1] for k in files if len(k) == len(mod) + 1 and k[:len(mod)] == mod}
    is_dir_mod = p.endswith(('mod.rs', 'lib.rs', 'main.rs'))
    parent = mod[:-1]
    text = re.sub(r'pub\(in [\w:]+\)', 'pub', text)
    # An inline `mod name { ... }` (e.g. rbf's model/matser.rs `mod option { use super::*; }`)
    # is a module of its own: `super::` inside it names the file's module, not the file's
    # parent. Reading it as the parent invented an edge matser.rs -> model/mod.rs.
    inline = []
    for im in re.finditer(r'\bmod\s+(\w+)\s*\{', text):
        depth = 0; j = im.end() - 1
        while j < len(text):
            if text[j] == '{': depth += 1
            elif text[j] == '}':
                depth -= 1
                if depth == 0: break
            j += 1
        inline.append((im.start(), j, im.group(1)))
    for m in re.finditer(r'(?<![\w:])(crate|super|self|\w+)::', text):
        head = m.group(1)
        here = list(mod) + [n for a, b, n in inline if a < m.start() < b]
        if head == 'crate': base = []
        elif head == 'super': base = here[:-1]
        elif head == 'self': base = here
        elif len(here) > len(mod): continue  # a child of the inline module: not a file
        elif head in children: base = list(mod) + [head]
        else: continue
        for path in expand(text, m.end()):
            # `super::super::x`: each further `super` climbs one more level (dropping
            # the word instead made the path resolve to the first parent).
            up = base
            while path and path[0] == 'super': up, path = up[:-1], path[1:]
            full = up + path
            t = resolve(full)
            if t is not None and t != mod: edges[mod].add(t)
# Tarjan
idx = {}; low = {}; st = []; on = set(); sccs = []; c = [0]
sys.setrecursionlimit(10000)
def sc(v):
    idx[v] = low[v] = c[0]; c[0] += 1; st.append(v); on.add(v)
    for w in edges[v]:
        if w not in idx: sc(w); low[v] = min(low[v], low[w])
        elif w in on: low[v] = min(low[v], idx[w])
    if low[v] == idx[v]:
        comp = []
        while True:
            w = st.pop(); on.discard(w); comp.append(w)
            if w == v: break
        sccs.append(comp)
for v in files:
    if v not in idx: sc(v)
name = lambda k: os.path.relpath(files[k], src)
# Simple cycles longer than `limit` (a parent module and its child importing each other
# is a cycle of two; two such pairs sharing the parent are not a longer cycle).
order = {v: i for i, v in enumerate(sorted(files))}
found = []
def longest_from(s, comp):
    best = None; stack = [(s, [s])]; steps = 0
    while stack and steps < 200000:
        steps += 1
        v, path = stack.pop()
        for w in edges[v]:
            if w not in comp: continue
            if w == s and len(path) > limit:
                if best is None or len(path) > len(best): best = list(path)
            elif order[w] > order[s] and w not in path:
                stack.append((w, path + [w]))
    return best
for comp in sccs:
    if len(comp) <= limit: continue
    cs = set(comp)
    for s in sorted(comp, key=lambda v: order[v]):
        c = longest_from(s, cs)
        if c: found.append(c)
found.sort(key=len, reverse=True)
seen = set()
for c in found:
    key = frozenset(c)
    if key in seen: continue
    seen.add(key)
    print(f"cycle of {len(c)} files: " + " -> ".join(name(k) for k in c + [c[0]]))
print(f"{len(files)} files, {sum(len(e) for e in edges.values())} edges, {len(seen)} simple cycles over {limit} files (longest {max((len(c) for c in found), default=0)})")
