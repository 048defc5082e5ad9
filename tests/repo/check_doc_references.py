#!/usr/bin/env python3
"""check_doc_references.py - the repository must stand alone (ctest RepoDocReferences).

Checks every text file of the repository (tests/repo/repo_files.py):
 1. Every section reference `<file>.md §N[.M]` (also chained: `OPTICS.md §6, §9 M3`, `SERVICE.md §4-§6`, and JSON's
    `\\u00a7`) names a markdown file of the repository, spelled exactly (case matters), that has a heading for that
    section (`## 9. Camera models`, `### 4.1 Tile layout`). A bare name is looked up next to the citing file, at the
    root and in docs/.
 2. A pitfall reference `<file>.md P7` names a repository file with a bold `**P7` entry.
 3. Every mention of a project doc resolves: `docs/<name>.md`, a lowercase bare `<name>.md`, and relative markdown
    links `[text](FILE.md)` in .md files. (External files are cited with their repository or path, e.g.
    `grpc/grpc doc/naming.md`, and are not checked.)
 4. No path of the machines the project was developed on appears anywhere (the project's workspace, a shared
    background-notes folder, home directories).
Usage: check_doc_references.py [--root DIR]. Exit 0 when clean, 1 with one line per problem.
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from repo_files import list_files, read_text  # noqa: E402

# Written in pieces so that this file does not contain what it forbids.
FORBIDDEN_PATHS = [
    ("workspace path", re.compile("/" + "work/")),
    ("shared background notes", re.compile(r"\.\./" + "shared")),
    ("shared background notes", re.compile("shared/" + "docs")),
    ("home directory", re.compile(r"(?<![\w.])/(?:home|Users)/[A-Za-z_]")),
    ("home directory", re.compile("(?<![\\w.])/" + "root/")),
]

SECTION = r"§\s?\d+(?:\.\d+)*"
# A section token and what may follow it inside a chain: a model (M2, M1/M2), a pitfall (P4), an item; or a pitfall.
TOKEN = r"(?:" + SECTION + r"(?:[ \t]+(?:M\d+(?:/M\d+)*|P\d+|item[ \t]+\d+|\d+\([a-z]\)))?|P\d+\b)"
CHAIN_SEPARATOR = r"[ \t]*(?:,|/|-|–|and|&)?[ \t]*"
REFERENCE = re.compile(
    r"(?P<file>[A-Za-z0-9_.\-/]*[A-Za-z0-9_\-]\.md)\b(?P<refs>(?:" + CHAIN_SEPARATOR + TOKEN + r")+)")
SECTION_NUMBER = re.compile(r"§\s?(\d+(?:\.\d+)*)")
PITFALL_NUMBER = re.compile(r"\bP(\d+)\b")
# Mentions of project docs: docs/<name>.md, or a bare lowercase <name>.md (external files carry a path).
DOC_MENTION = re.compile(r"(?<![A-Za-z0-9_./\-])(?P<file>docs/[A-Za-z0-9_./\-]+\.md|[a-z0-9_\-]+\.md)\b")
# Not checked for references (still for machine paths): verbatim copies of historical code (an experiment's diff must
# keep its context lines to apply) and the self-test, whose fixtures are wrong on purpose.
REFERENCES_NOT_CHECKED = (".patch", "tests/repo/test_repo_checks.py")
HEADING = re.compile(r"^#{1,6}[ \t]+(?:§[ \t]*)?(\d+(?:\.\d+)*)\.?(?:[ \t]|$)", re.MULTILINE)
MARKDOWN_LINK = re.compile(r"\]\((?P<target>[^)\s#]+\.md)(?:#[^)\s]*)?\)")


def resolve(root, files, citing, name):
    """Repository path of the cited markdown file, or None."""
    candidates = []
    citing_dir = os.path.dirname(citing)
    candidates.append(os.path.normpath(os.path.join(citing_dir, name)))
    candidates.append(os.path.normpath(name))
    if "/" not in name:
        candidates.append("docs/" + name)
    for c in candidates:
        c = c.replace(os.sep, "/")
        if c in files:
            return c
    return None


def anchors(root, path, cache):
    """(section numbers with a heading, pitfall numbers with a bold entry) of a markdown file."""
    if path not in cache:
        text = read_text(root, path) or ""
        cache[path] = (set(HEADING.findall(text)), set(re.findall(r"\*\*P(\d+)\b", text)))
    return cache[path]


def check(root):
    """List of (path, line, message, cited name or None) problems."""
    files = list_files(root)
    file_set = set(files)
    cache = {}
    problems = []
    for path in files:
        text = read_text(root, path)
        if text is None:
            continue
        for lineno, line in enumerate(text.splitlines(), 1):
            for what, pattern in FORBIDDEN_PATHS:
                m = pattern.search(line)
                if m:
                    problems.append((path, lineno, "%s '%s' outside the repository: cite the project's docs/ instead"
                                     % (what, line[m.start():m.end() + 20].strip()), None))
            if path.endswith(REFERENCES_NOT_CHECKED):
                continue
            scan = line.replace("\\u00a7", "§")
            missing = set()
            for m in REFERENCE.finditer(scan):
                name = m.group("file")
                target = resolve(root, file_set, path, name)
                if target is None:
                    missing.add(name)
                    problems.append((path, lineno, "'%s' cites %s, which is not a file of the repository"
                                     % (m.group(0).strip(), name), name))
                    continue
                sections, pitfalls = anchors(root, target, cache)
                for number in SECTION_NUMBER.findall(m.group("refs")):
                    if number not in sections:
                        problems.append((path, lineno, "'%s': %s has no heading numbered %s"
                                         % (m.group(0).strip(), target, number), None))
                for number in PITFALL_NUMBER.findall(m.group("refs")):
                    if number not in pitfalls:
                        problems.append((path, lineno, "'%s': %s has no entry **P%s"
                                         % (m.group(0).strip(), target, number), None))
            for m in DOC_MENTION.finditer(scan):
                name = m.group("file")
                if name not in missing and resolve(root, file_set, path, name) is None:
                    missing.add(name)
                    problems.append((path, lineno, "mentions %s, which is not a file of the repository" % name,
                                     name))
            if path.endswith(".md"):
                for m in MARKDOWN_LINK.finditer(line):
                    link = m.group("target")
                    if "://" in link or link.startswith("/"):
                        continue
                    if resolve(root, file_set, path, link) is None:
                        problems.append((path, lineno, "link to %s, which is not a file of the repository" % link,
                                         None))
    return problems


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    args = parser.parse_args(argv)
    root = os.path.abspath(args.root)
    problems = check(root)
    failing = problems
    for path, lineno, message, _ in failing:
        print("%s:%d: %s" % (path, lineno, message))
    if failing:
        print("%d problem(s): every § reference must name a file of the repository with that heading, and no path "
              "outside the repository may appear" % len(failing))
        return 1
    print("doc references: OK (%d files)" % len(list_files(root)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
