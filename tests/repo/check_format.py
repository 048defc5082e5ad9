#!/usr/bin/env python3
"""check_format.py - every C++ source of the repository is formatted by the root .clang-format (ctest RepoFormat).

Runs `clang-format --dry-run -Werror` over the tracked *.cpp / *.h files (tests/repo/repo_files.py); verbatim
historical copies under docs/ are not ours to format. Fix a failure with:
    git ls-files '*.cpp' '*.h' ':!docs' | xargs clang-format -i
Usage: check_format.py [--root DIR] [--clang-format EXE]. Exit 0 when clean, 1 listing the files that differ,
77 (ctest's skip code) when clang-format is not installed.
"""
import argparse
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from repo_files import list_files  # noqa: E402

SKIP = 77
BATCH = 64  # files per clang-format process: bounded command lines


def cpp_sources(root):
    return [p for p in list_files(root) if p.endswith((".cpp", ".h")) and not p.startswith("docs/")]


def unformatted(root, exe, files):
    bad = []
    for i in range(0, len(files), BATCH):
        batch = files[i:i + BATCH]
        run = subprocess.run([exe, "--dry-run", "-Werror", "--style=file"] + batch, cwd=root,
                             capture_output=True, text=True)
        if run.returncode != 0:
            bad.extend(sorted({line.split(":", 1)[0] for line in run.stderr.splitlines()
                               if ": error:" in line}))
    return bad


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    parser.add_argument("--clang-format", default="clang-format")
    args = parser.parse_args(argv)
    exe = shutil.which(args.clang_format)
    if exe is None:
        print("clang-format not found (Debian 12: apt-get install clang-format); format check skipped")
        return SKIP
    root = os.path.abspath(args.root)
    files = cpp_sources(root)
    bad = unformatted(root, exe, files)
    for path in bad:
        print("%s: not clang-formatted (run: clang-format -i %s)" % (path, path))
    if bad:
        print("%d of %d C++ files differ from .clang-format" % (len(bad), len(files)))
        return 1
    print("format: OK (%d C++ files)" % len(files))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
