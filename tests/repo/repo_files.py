"""repo_files.py - the files of the repository that the repository checks read (tests/repo/*.py).

Tracked files (`git ls-files`) when the tree is a git checkout, else every file outside build and output
directories. Text only: files that are not UTF-8 or contain NUL bytes are skipped.
"""
import os
import subprocess

# Directories never scanned when the tree is not a git checkout (build trees, outputs, dependencies).
_UNTRACKED_DIRS = {".git", "assets", "out", "node_modules", "__pycache__", ".bench-bundle"}


def _is_build_dir(name):
    return name == "build" or name.startswith("build-") or name.startswith("cmake-build")


def list_files(root):
    """Repository-relative paths ('/'-separated) of the files to check, sorted."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], check=True, capture_output=True).stdout
        files = [p for p in out.decode("utf-8", "surrogateescape").split("\0") if p]
        if files:
            return sorted(p for p in files if os.path.isfile(os.path.join(root, p)))
    except (OSError, subprocess.CalledProcessError):
        pass
    files = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = [d for d in dirnames if d not in _UNTRACKED_DIRS and not _is_build_dir(d)]
        for name in filenames:
            files.append(os.path.relpath(os.path.join(dirpath, name), root).replace(os.sep, "/"))
    return sorted(files)


def read_text(root, path):
    """The file's text, or None for binary / non-UTF-8 files."""
    with open(os.path.join(root, path), "rb") as f:
        data = f.read()
    if b"\0" in data:
        return None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return None
