#!/usr/bin/python3
"""Committed results live in the top-level results/ only, one documented folder per experiment.

    scripts/check_results_layout.py [--root DIR]     # DIR: the repository (default: this one)

Fails (exit 1, one line per problem) when a tracked path has a `results` folder anywhere but at
the top (a code folder's own results/, as ste/results/ was before issue 43), or when a folder of
results/ has no README.md (what it measures and the command that made it). The tracked files are
git's (`git ls-files`); outside a git checkout, the files on disk.
"""
import argparse
import os
import subprocess
import sys
from pathlib import Path, PurePosixPath

SKIPPED_ON_DISK = {".git", "build", "out"}


def tracked_files(root):
    """The repository's tracked files, relative POSIX paths."""
    try:
        listing = subprocess.run(["git", "-C", str(root), "ls-files", "-z"], check=True,
                                 capture_output=True).stdout
        return [p for p in listing.decode().split("\0") if p]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for folder, subfolders, names in os.walk(root):
            subfolders[:] = [s for s in subfolders if s not in SKIPPED_ON_DISK]
            files += [Path(folder, n).relative_to(root).as_posix() for n in names]
        return files


def problems(paths):
    found = []
    misplaced = sorted({str(PurePosixPath(*PurePosixPath(p).parts[:i + 1]))
                        for p in paths
                        for i, part in enumerate(PurePosixPath(p).parts[:-1])
                        if part == "results" and i > 0})
    found += [f"{folder}/: committed results belong in the top-level results/<experiment>/"
              for folder in misplaced]
    parts = [PurePosixPath(p).parts for p in paths]
    experiments = sorted({q[1] for q in parts if len(q) > 2 and q[0] == "results"})
    documented = {q[1] for q in parts if len(q) == 3 and q[0] == "results" and q[2] == "README.md"}
    found += [f"results/{e}/: no README.md (what it measures, the command that made it)"
              for e in experiments if e not in documented]
    return found


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=Path, default=Path(__file__).resolve().parent.parent)
    args = parser.parse_args(argv[1:])
    found = problems(tracked_files(args.root))
    for line in found:
        print(line)
    if not found:
        print("results layout: committed results only under results/, every experiment documented")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
