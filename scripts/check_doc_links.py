#!/usr/bin/env python3
"""Every relative link in the project's Markdown (README.md, docs/, module and results READMEs)
names a file that exists and, for a #fragment into a Markdown page, a heading it has. And every
quoted-section pointer in the sources and pages, `PATH.md, "Heading"` (in a comment, a docstring or
prose, across line breaks), names a heading of PATH when PATH exists: the quoted text is the start
of one of its headings, or of a bold title opening a paragraph (case and Markdown marks aside), so
a reader can search the page for it; so is each further title chained after it
(`PATH.md, "Floors", "Seen sources"`). Exit 1 with each broken link or pointer as FILE: WHAT.
Links in code blocks are skipped; pointers are read everywhere (a script's comment in a block).

Usage: check_doc_links.py [--root DIR]
"""
import argparse
import os
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


def headings(page: pathlib.Path) -> list:
    """The page's sections outside code blocks, normalised as in normal(): its headings and the
    bold run-in titles that open a paragraph or a list item (`**Memory estimate.** ...`)."""
    text = re.sub(r"^```.*?^```", "", page.read_text(encoding="utf-8"), flags=re.S | re.M)
    found = re.findall(r"^#+ (.*)$", text, flags=re.M)
    found += re.findall(r"^\s*(?:[-*] |\d+\. )?\*\*([^*]+)\*\*", text, flags=re.M)
    return [normal(m) for m in found]


def normal(title: str) -> str:
    return " ".join(re.sub(r"[`*_]", "", title).lower().split())


SOURCES = (".cpp", ".hpp", ".h", ".py", ".sh", ".md", ".txt", ".cmake")


def sources(root: pathlib.Path):
    """The tree's source and text files; build folders, outputs (out/), hidden folders and the
    shared/ notes are not the project's."""
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if not (d.startswith((".", "build", "__pycache__"))
                                                 or (folder == str(root) and d in ("out", "shared"))))
        yield from (pathlib.Path(folder, f) for f in sorted(files) if f.endswith(SOURCES))


def joined(path: pathlib.Path) -> str:
    """The file's lines without indentation and comment marks, joined by spaces: a pointer that a
    comment or a string wraps over two lines reads as one."""
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    text = " ".join(re.sub(r"^\s*(//+|#+(?=\s)|\*|-(?=\s)|>)?\s*", "", line) for line in lines)
    if path.suffix in (".cpp", ".hpp", ".h"):
        # A help string's pointer: adjacent literals are one string, \" a quote.
        text = re.sub(r'"\s+"', "", text).replace('\\"', '"')
    return text


POINTER = re.compile(r'([\w./-]+\.md)`?,? \(?("[^"\\]{2,160}"(?:, "[^"\\]{2,160}")*)')


def section_pointers(root: pathlib.Path, bad: list) -> int:
    """Checks every `PATH.md, "Heading"` whose PATH exists (from the root, else from the file's
    folder); returns how many it checked."""
    count, cache = 0, {}
    for src in sources(root):
        for path, titles in POINTER.findall(joined(src)):
            page = next((p for p in (root / path, src.parent / path) if p.is_file()), None)
            if page is None:
                continue
            if page not in cache:
                cache[page] = headings(page)
            for title in re.findall(r'"([^"]*)"', titles):
                if not title.strip():
                    continue
                count += 1
                if not any(h.startswith(normal(title)) for h in cache[page]):
                    bad.append(f'{src.relative_to(root)}: {path}, "{title}" (no such heading)')
    return count


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
    pointers = section_pointers(root, bad)
    print("\n".join(bad + [f"{links} links, {pointers} section pointers, {len(bad)} broken"]))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
