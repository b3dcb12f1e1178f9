#!/usr/bin/env python3
"""Compares the numbers of two report pages (index.html) table by table.

    scripts/report-compare.py OLD.html NEW.html [--rel 1e-9] [--rename 'OLD=NEW' ...]

A page may gain sections, tables, columns and sentences; what the old page
shows must still be on the new one with the same numbers. Each table of OLD
is found on NEW in the section of the same heading (or its --rename), by its
caption, or else by its header; each of its columns by header, each row by
its first cell; every number of a cell must be within --rel relative or one
unit in its last printed digit (scripts/golden-compare.py's rule). Each
summary paragraph's sentences are matched on NEW by their words with the
numbers masked, and their numbers compared the same way. Dates and the SHA-256
of files that name a date are not compared. Exit 0 when nothing differs, 1
otherwise, each difference on a line; the last line counts what was compared.
"""
import argparse, html, importlib.util, os, re, sys
from html.parser import HTMLParser

spec = importlib.util.spec_from_file_location(
    "gc", os.path.join(os.path.dirname(__file__), "golden-compare.py"))
gc = importlib.util.module_from_spec(spec); spec.loader.exec_module(gc)


class Page(HTMLParser):
    """Sections (h2) with their tables (caption, header, rows) and the
    summary paragraphs."""
    def __init__(self):
        super().__init__()
        self.sections, self.summary = {}, []
        self.cur, self.stack, self.text = None, [], None
        self.table = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag in ("h2", "caption", "th", "td") or (tag == "p" and a.get("class") == "summary"):
            self.text = []
            self.stack.append(tag)
        if tag == "table":
            self.table = {"caption": "", "header": [], "rows": []}
        if tag == "tr" and self.table is not None:
            self.row = []

    def handle_endtag(self, tag):
        if self.stack and self.stack[-1] == tag:
            self.stack.pop()
            t = " ".join("".join(self.text).split())
            self.text = None
            if tag == "h2":
                self.cur = t
                self.sections.setdefault(t, [])
            elif tag == "p":
                self.summary.append(t)
            elif tag == "caption":
                self.table["caption"] = t
            elif tag in ("th", "td"):
                self.row.append(t)
        if tag == "tr" and self.table is not None:
            if self.row and not self.table["header"]:
                self.table["header"] = self.row
            elif self.row:
                self.table["rows"].append(self.row)
        if tag == "table" and self.table is not None:
            self.sections.setdefault(self.cur, []).append(self.table)
            self.table = None

    def handle_data(self, d):
        if self.text is not None:
            self.text.append(d)


def read(path):
    p = Page()
    p.feed(open(path, encoding="utf-8").read())
    return p


def numbers(text):
    return [tok for kind, tok in gc.tokens(text) if kind == "n"]


def masked(text):
    return " ".join(tok if kind == "t" else "#" for kind, tok in gc.tokens(text))


def same_numbers(a, b, rel):
    na, nb = numbers(a), numbers(b)
    return len(na) == len(nb) and all(gc.num_close(x, y, rel, False) for x, y in zip(na, nb))


def find_table(tables, old):
    for t in tables:
        if old["caption"] and t["caption"] == old["caption"]:
            return t
    for t in tables:
        if set(old["header"]) <= set(t["header"]):
            return t
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("old"); ap.add_argument("new")
    ap.add_argument("--rel", type=float, default=1e-9)
    ap.add_argument("--rename", action="append", default=[])
    a = ap.parse_args()
    rename = dict(r.split("=", 1) for r in a.rename)
    old, new = read(a.old), read(a.new)
    diffs, cells = [], 0
    for sec, tables in old.sections.items():
        target = rename.get(sec, sec)
        if tables and target not in new.sections:
            diffs.append(f"section {sec!r}: not on the new page")
            continue
        for t in tables:
            n = find_table(new.sections[target], t)
            if n is None:
                diffs.append(f"{sec!r}: table {t['caption'] or t['header']} not found")
                continue
            cols = {h: i for i, h in enumerate(n["header"])}
            rows = {r[0]: r for r in n["rows"]}
            for r in t["rows"]:
                m = rows.get(r[0])
                if m is None:
                    diffs.append(f"{sec!r}: row {r[0]!r} missing")
                    continue
                for h, cell in zip(t["header"], r):
                    if h in ("SHA-256",) or "UTC" in cell or h == "value":
                        continue
                    other = m[cols[h]] if h in cols else None
                    if other is None:
                        diffs.append(f"{sec!r}: column {h!r} missing"); break
                    cells += 1
                    if not same_numbers(cell, other, a.rel):
                        diffs.append(f"{sec!r} row {r[0]!r} column {h!r}: {cell!r} against {other!r}")
    sentences = [s for p in new.summary for s in re.split(r"(?<=\.) (?=[A-Z])", p)]
    said = 0
    for p in old.summary:
        for s in re.split(r"(?<=\.) (?=[A-Z])", p):
            for o, n in rename.items():
                s = s.replace(o, n)
            if not numbers(s):
                continue
            key = masked(s)
            hits = [x for x in sentences if masked(x).endswith(key) or key in masked(x)]
            if not hits:
                diffs.append(f"summary sentence not on the new page: {s!r}")
            elif not any(same_numbers(s, x, a.rel) or numbers(s) == numbers(x)[-len(numbers(s)):] for x in hits):
                diffs.append(f"summary: {s!r} against {hits[0]!r}")
            said += 1
    for d in diffs:
        print(d)
    print(f"{cells} table cells and {said} summary sentences compared, {len(diffs)} differences")
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main())
