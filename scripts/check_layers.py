#!/usr/bin/env python3
"""The whiteboard kept true: every #include "folder/..." in a library folder must name a folder that
docs/architecture.md allows it to include (its table between the `layers:` markers), and no folder
may reach past the ones listed. Exit 1 with each offending line, file:line, when one does.

Usage: check_layers.py [--root DIR]
"""
import argparse
import pathlib
import re
import sys


def read_rules(doc: pathlib.Path) -> dict:
    """Folder -> set of folders it may include, from the ```layers block of docs/architecture.md."""
    text = doc.read_text(encoding="utf-8")
    m = re.search(r"```layers\n(.*?)```", text, re.S)
    if not m:
        sys.exit(f"{doc}: no ```layers block (folder: allowed folders) found")
    rules = {}
    for n, line in enumerate(m.group(1).splitlines(), 1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        folder, _, allowed = line.partition(":")
        if not _:
            sys.exit(f"{doc}: layers line {n} '{line}' is not 'folder: allowed ...'")
        rules[folder.strip()] = set(allowed.split()) | {folder.strip()}
    return rules


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", default=str(pathlib.Path(__file__).resolve().parent.parent))
    root = pathlib.Path(ap.parse_args().root)
    rules = read_rules(root / "docs" / "architecture.md")
    include = re.compile(r'^\s*#\s*include\s+"([A-Za-z_]+)/')
    bad = []
    for folder, allowed in sorted(rules.items()):
        for f in sorted((root / folder).rglob("*")):
            if f.suffix not in (".cpp", ".hpp") or "results" in f.parts:
                continue
            for n, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
                m = include.match(line)
                if m and m.group(1) in rules and m.group(1) not in allowed:
                    bad.append(f"{f.relative_to(root)}:{n}: {folder}/ may not include "
                               f"{m.group(1)}/ ({line.strip()}); docs/architecture.md")
    for b in bad:
        print(b)
    if bad:
        print(f"{len(bad)} include(s) break the layering")
        return 1
    print(f"layers: {len(rules)} folders, every include points down")
    return 0


if __name__ == "__main__":
    sys.exit(main())
