#!/usr/bin/env python3
"""Every relative link in the project's Markdown (README.md, docs/, module and results READMEs)
names a file that exists and, for a #fragment into a Markdown page, a heading it has. Exit 1 with
each broken link as PAGE: LINK. Code blocks are skipped.

Usage: check_doc_links.py [--root DIR]
"""
import argparse
import pathlib
import re
import sys


def anchors(page: pathlib.Path) -> set:
    """GitHub's heading anchors: lower case, punctuation dropped, spaces to hyphens."""
    out = set()
    for line in page.read_text(encoding="utf-8").splitlines():
        m = re.match(r"#+ (.*)", line)
        if m:
            out.add(re.sub(r"[^\w\- ]", "", m.group(1).strip().lower()).replace(" ", "-"))
    return out


def pages(root: pathlib.Path):
    yield from sorted(root.glob("*.md"))
    for pattern in ("docs/**/*.md", "*/README.md", "*/*/README.md"):
        yield from sorted(p for p in root.glob(pattern) if "build" not in p.parts[len(root.parts)])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", default=str(pathlib.Path(__file__).resolve().parent.parent))
    root = pathlib.Path(ap.parse_args().root).resolve()
    bad, links = [], 0
    for page in dict.fromkeys(pages(root)):
        text = re.sub(r"```.*?```", "", page.read_text(encoding="utf-8"), flags=re.S)
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", target):
                continue
            links += 1
            path, _, frag = target.partition("#")
            file = (page.parent / path).resolve() if path else page
            if not file.exists():
                bad.append(f"{page.relative_to(root)}: {target} (no such file)")
            elif frag and file.suffix == ".md" and frag not in anchors(file):
                bad.append(f"{page.relative_to(root)}: {target} (no such heading)")
    print("\n".join(bad + [f"{links} links, {len(bad)} broken"]))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
