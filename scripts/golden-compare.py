#!/usr/bin/env python3
"""Compares two folders written by scripts/golden-outputs.sh number by number.

    scripts/golden-compare.py OLD NEW [--rel 1e-9] [--most 40] [--ignore GLOB ...]

A refactor that must not move the numbers is checked with it: every file of
OLD is read beside the same file of NEW.
- JSON (a .json file, or a .out whose text before its 'exit N' line is JSON)
  is compared as a tree: keys missing from NEW are differences, keys only in
  NEW are listed as additions; numbers within the tolerance below.
- Any other text is split into numbers and the text between them; the text
  must be the same (runs of white space folded), the numbers within:
    * full-precision numbers (12 or more significant digits): --rel relative;
    * rounded ones (fewer digits): --rel relative or one unit in their last
      printed digit, whichever is larger (two roundings of values 1e-12 apart
      can differ there);
    * integers exactly, but in SVG, where a pixel coordinate may round the
      other way, within 1.
- PNG and other binary files are not compared (counted).
Exit 0 when nothing differs, 1 otherwise; each difference as FILE:LINE.
"""
import argparse
import fnmatch
import json
import math
import os
import re
import sys

NUM = re.compile(r'(?<![\w.])[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?(?![\w])')


def sig_digits(tok):
    mant = re.split(r'[eE]', tok)[0].lstrip('+-').replace('.', '').lstrip('0')
    return len(mant)


def last_unit(tok):
    parts = re.split(r'[eE]', tok)
    mant, exp = parts[0], int(parts[1]) if len(parts) > 1 else 0
    dec = len(mant.split('.')[1]) if '.' in mant else 0
    return 10.0 ** (exp - dec)


def is_int(tok):
    return re.fullmatch(r'[-+]?\d+', tok) is not None


def num_close(a_tok, b_tok, rel, svg):
    try:
        a, b = float(a_tok), float(b_tok)
    except ValueError:
        return a_tok == b_tok
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    if a == b:
        return True
    if is_int(a_tok) and is_int(b_tok):
        return svg and abs(a - b) <= 1
    tol = rel * max(abs(a), abs(b))
    if min(sig_digits(a_tok), sig_digits(b_tok)) < 12:
        tol = max(tol, max(last_unit(a_tok), last_unit(b_tok)) * 1.000001)
    return abs(a - b) <= tol


def tokens(text):
    out, pos = [], 0
    for m in NUM.finditer(text):
        out.append(('t', ' '.join(text[pos:m.start()].split())))
        out.append(('n', m.group()))
        pos = m.end()
    out.append(('t', ' '.join(text[pos:].split())))
    return out


def compare_text(a, b, rel, svg, where, diffs):
    la, lb = a.splitlines(), b.splitlines()
    if len(la) != len(lb):
        diffs.append(f"{where}: {len(la)} lines against {len(lb)}")
    for i, (x, y) in enumerate(zip(la, lb), 1):
        if x == y:
            continue
        tx, ty = tokens(x), tokens(y)
        ok = len(tx) == len(ty) and all(
            (p[0] == q[0]) and (p[1] == q[1] if p[0] == 't' else num_close(p[1], q[1], rel, svg))
            for p, q in zip(tx, ty))
        if not ok:
            diffs.append(f"{where}:{i}:\n    - {x[:300]}\n    + {y[:300]}")


def compare_json(a, b, rel, path, diffs, adds):
    if isinstance(a, dict) and isinstance(b, dict):
        for k in a:
            if k not in b:
                diffs.append(f"{path}: key '{k}' missing")
            else:
                compare_json(a[k], b[k], rel, f"{path}.{k}", diffs, adds)
        adds.extend(f"{path}.{k}" for k in b if k not in a)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            diffs.append(f"{path}: {len(a)} items against {len(b)}")
        for i, (x, y) in enumerate(zip(a, b)):
            compare_json(x, y, rel, f"{path}[{i}]", diffs, adds)
    elif isinstance(a, bool) or isinstance(b, bool) or a is None or b is None:
        if a != b:
            diffs.append(f"{path}: {a!r} against {b!r}")
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if not num_close(repr(a) if isinstance(a, float) else str(a),
                         repr(b) if isinstance(b, float) else str(b), rel, False):
            diffs.append(f"{path}: {a!r} against {b!r}")
    elif isinstance(a, str) and isinstance(b, str):
        sub = []
        compare_text(a, b, rel, False, path, sub)
        diffs.extend(sub)
    elif a != b:
        diffs.append(f"{path}: {a!r} against {b!r}")


def split_exit(text):
    lines = text.rstrip('\n').split('\n')
    if lines and re.fullmatch(r'exit \d+', lines[-1]):
        return '\n'.join(lines[:-1]), lines[-1]
    return text, None


def as_json(text):
    t = text.strip()
    if not t or t[0] not in '[{':
        return None
    try:
        return json.loads(t)
    except ValueError:
        return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('old')
    ap.add_argument('new')
    ap.add_argument('--rel', type=float, default=1e-9)
    ap.add_argument('--most', type=int, default=40, help='differences shown at most')
    ap.add_argument('--ignore', nargs='*', default=[], help='glob(s) of relative paths not compared')
    args = ap.parse_args()
    diffs, adds, skipped, compared = [], [], 0, 0
    for root, _, files in os.walk(args.old):
        for f in sorted(files):
            pa = os.path.join(root, f)
            rel_path = os.path.relpath(pa, args.old)
            if any(fnmatch.fnmatch(rel_path, g) for g in args.ignore):
                continue
            pb = os.path.join(args.new, rel_path)
            if not os.path.exists(pb):
                diffs.append(f"{rel_path}: missing in {args.new}")
                continue
            ra, rb = open(pa, 'rb').read(), open(pb, 'rb').read()
            if ra == rb:
                compared += 1
                continue
            try:
                ta, tb = ra.decode(), rb.decode()
            except UnicodeDecodeError:
                skipped += 1
                continue
            compared += 1
            body_a, exit_a = split_exit(ta)
            body_b, exit_b = split_exit(tb)
            if exit_a != exit_b:
                diffs.append(f"{rel_path}: {exit_a} against {exit_b}")
            ja, jb = as_json(body_a), as_json(body_b)
            if ja is not None and jb is not None:
                compare_json(ja, jb, args.rel, rel_path, diffs, adds)
            else:
                compare_text(body_a, body_b, args.rel, f.endswith('.svg'), rel_path, diffs)
    for root, _, files in os.walk(args.new):
        for f in files:
            rel_path = os.path.relpath(os.path.join(root, f), args.new)
            if not os.path.exists(os.path.join(args.old, rel_path)):
                adds.append(f"{rel_path} (new file)")
    for d in diffs[:args.most]:
        print(d)
    if len(diffs) > args.most:
        print(f"... and {len(diffs) - args.most} more differences")
    if adds:
        print(f"additions ({len(adds)}): " + ', '.join(adds[:20]) + (' …' if len(adds) > 20 else ''))
    print(f"{compared} files compared, {skipped} binary files not compared, {len(diffs)} differences")
    sys.exit(1 if diffs else 0)


if __name__ == '__main__':
    main()
