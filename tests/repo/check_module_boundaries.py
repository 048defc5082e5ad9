#!/usr/bin/env python3
"""check_module_boundaries.py - the allowed dependencies between modules (ctest RepoModuleBoundaries).

The rules (docs/ARCHITECTURE.md §2), checked on #include lines of the sources and on the link lines of every
CMakeLists.txt (add_library / add_executable / ht_add_test define a target in the module of their directory;
target_link_libraries / ht_add_test LIBS name what it links directly):
 1. Apps never depend on each other: cli/ neither includes server/ nor links a server/ target, and vice versa.
    Code both need lives in a library.
 2. Core libraries (camera_models, bvh, gpu, scene, common) include and link (also transitively, through our own
    targets) no gRPC/protobuf, OpenImageIO, libusb, MPI or Embree, and no app, protocol or frame_io code.
 3. Only the frame-output library (OIIO_MODULES) includes or links OpenImageIO; tests may read images back with it.
 4. Only tests, benchmarks and tools include or link Embree.
KNOWN_VIOLATIONS lists the violations of today's tree that pending work removes; a violation not in it fails.
Usage: check_module_boundaries.py [--root DIR]. Exit 0 when clean, 1 with one line per violation.
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from repo_files import list_files, read_text  # noqa: E402

APPS = ("cli", "server")
CORE = ("camera_models", "bvh", "gpu", "scene", "common")
# Modules allowed to use OpenImageIO: the frame-output library (issue 13 part 1 creates `frame_io/`; adjust the name
# here if it lands under another one) and the tests, which read written images back independently.
OIIO_MODULES = ("frame_io", "tests")
EMBREE_MODULES = ("tests", "bench", "tools")
# Our modules a core library must not depend on.
ABOVE_CORE = APPS + ("protocol", "frame_io", "tests", "bench", "tools")

# Violations tolerated while a refactor is in flight, as printed by this script (issue 13 emptied it when frame_io/
# took the image code out of cli/ and server/). Never add one to make a new violation pass.
KNOWN_VIOLATIONS = set()

SOURCE_SUFFIXES = (".h", ".hpp", ".cpp", ".cc", ".c", ".comp", ".glsl", ".in")
INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*[<"]([^>"]+)[>"]', re.MULTILINE)

# External dependencies: (name, #include pattern, link-item pattern).
EXTERNAL = [
    ("gRPC", r"^(grpc|grpcpp|grpc\+\+)/|^google/protobuf/|^holotrace/v1/", r"^(gRPC::|protobuf::|grpc)"),
    ("OpenImageIO", r"^OpenImageIO/", r"^OpenImageIO::"),
    ("libusb", r"^libusb(-1\.0)?[/.]", r"^(PkgConfig::LIBUSB|usb-1\.0)$"),
    ("MPI", r"^mpi\.h$|^mpi/", r"^MPI::"),
    ("Embree", r"^embree\d/", r"^embree$"),
]
EXTERNAL_INCLUDES = [(kind, re.compile(include)) for kind, include, _ in EXTERNAL]
EXTERNAL_LINKS = [(kind, re.compile(link)) for kind, _, link in EXTERNAL]
CMAKE_KEYWORDS = {"PUBLIC", "PRIVATE", "INTERFACE", "LINK_PUBLIC", "LINK_PRIVATE", "LINK_INTERFACE_LIBRARIES",
                  "debug", "optimized", "general"}
HT_ADD_TEST_KEYWORDS = {"SOURCES", "LIBS", "LABELS", "TIMEOUT"}


def module_of(path):
    """First directory of a repository path ("" for top-level files)."""
    return path.split("/", 1)[0] if "/" in path else ""


def strip_cmake_comments(text):
    return "\n".join(re.sub(r'#(?![^"]*"[^"]*$).*$', "", line) for line in text.splitlines())


def cmake_commands(text, names):
    """(command, argument tokens) of every call of the named commands, in order."""
    text = strip_cmake_comments(text)
    pattern = re.compile(r"\b(" + "|".join(names) + r")\s*\(")
    pos = 0
    while True:
        m = pattern.search(text, pos)
        if not m:
            return
        depth, i = 1, m.end()
        while i < len(text) and depth:
            depth += {"(": 1, ")": -1}.get(text[i], 0)
            i += 1
        args = text[m.end():i - 1]
        tokens = [t.strip('"') for t in re.findall(r'"[^"]*"|[^\s"]+', args)]
        yield m.group(1), tokens
        pos = i


def parse_targets(root, files):
    """({target: module}, {target: [direct link items]}) from every CMakeLists.txt."""
    owner, links, variables = {}, {}, {}
    module_dirs = {module_of(f) for f in files}
    for path in files:
        if os.path.basename(path) != "CMakeLists.txt":
            continue
        text = read_text(root, path) or ""
        module = module_of(path)
        for command, tokens in cmake_commands(text, ["set", "list", "add_library", "add_executable", "ht_add_test",
                                                      "target_link_libraries"]):
            # ${VAR} of a plain set()/list(APPEND) earlier in the tree is expanded, so a link cannot hide in one.
            tokens = tokens[:1] + [x for t in tokens[1:] for x in expand(t, variables)]
            if command == "set" and tokens:
                variables[tokens[0]] = [t for t in tokens[1:] if t not in ("CACHE", "PARENT_SCOPE")]
                continue
            if command == "list":
                if len(tokens) > 1 and tokens[0] == "APPEND":
                    variables.setdefault(tokens[1], []).extend(tokens[2:])
                continue
            if not tokens or "$" in tokens[0]:
                continue  # function bodies (${name}) are resolved at their call sites
            name = tokens[0]
            if command in ("add_library", "add_executable"):
                if "IMPORTED" in tokens or "ALIAS" in tokens:
                    continue
                # Top-level targets belong to the module they are named after (ht_common -> common/).
                suffix = name[3:] if name.startswith("ht_") else name
                owner[name] = module or (suffix if suffix in module_dirs else "")
                links.setdefault(name, [])
            elif command == "ht_add_test":
                owner[name] = module
                items, collecting = [], False
                for t in tokens[1:]:
                    if t in HT_ADD_TEST_KEYWORDS:
                        collecting = t == "LIBS"
                    elif collecting:
                        items.append(t)
                links.setdefault(name, []).extend(items)
            else:
                links.setdefault(name, []).extend(
                    t for t in tokens[1:] if t not in CMAKE_KEYWORDS and "$" not in t and not t.startswith("-"))
    return owner, links


def expand(token, variables):
    m = re.fullmatch(r"\$\{(\w+)\}", token)
    return variables.get(m.group(1), [token]) if m else [token]


def external_kind(item, table):
    for kind, pattern in table:
        if pattern.search(item):
            return kind
    return None


def dependency_rule(module, other, kind, verb):
    """The rule a dependency of `module` on our module `other` or on external `kind` breaks (apps, OIIO, Embree)."""
    if module in APPS and other in APPS and other != module:
        return "app %s %s app %s" % (module, verb, other)
    if kind == "OpenImageIO" and module not in OIIO_MODULES:
        return "only %s use OpenImageIO" % ", ".join(OIIO_MODULES)
    if kind == "Embree" and module not in EMBREE_MODULES:
        return "only %s use Embree" % ", ".join(EMBREE_MODULES)
    return None


def check_includes(root, files):
    violations = []
    for path in files:
        if not path.endswith(SOURCE_SUFFIXES):
            continue
        module = module_of(path)
        text = read_text(root, path)
        if text is None:
            continue
        for header in INCLUDE.findall(text):
            other = module_of(header)
            kind = external_kind(header, EXTERNAL_INCLUDES)
            if module in CORE and other in ABOVE_CORE:
                rule = "core library %s includes %s" % (module, other)
            elif module in CORE and kind:
                rule = "core library %s uses %s" % (module, kind)
            else:
                rule = dependency_rule(module, other, kind, "includes")
            if rule:
                violations.append("include %s -> %s: %s" % (path, header, rule))
    return violations


def check_links(owner, links):
    violations = []
    for target in sorted(links):
        module = owner.get(target)
        if module is None:
            continue  # linked to in our files but defined elsewhere (none today)
        for item in links[target]:
            kind = external_kind(item, EXTERNAL_LINKS)
            other = owner.get(item)
            rule = dependency_rule(module, other, kind, "links")
            if rule:
                shown = "%s (%s)" % (item, other) if other is not None else item
                violations.append("link %s (%s) -> %s: %s" % (target, module, shown, rule))
        if module in CORE:
            violations.extend(core_closure_violations(target, owner, links))
    return violations


def core_closure_violations(target, owner, links):
    """What a core target reaches through its links, ours followed transitively."""
    found, seen, stack = [], {target}, [target]
    while stack:
        current = stack.pop()
        for item in links.get(current, []):
            kind = external_kind(item, EXTERNAL_LINKS)
            other = owner.get(item)
            if kind:
                found.append("link %s (%s) -> %s via %s: core library uses %s"
                             % (target, owner[target], item, current, kind))
            elif other is not None:
                if other in ABOVE_CORE:
                    found.append("link %s (%s) -> %s (%s) via %s: core library depends on %s"
                                 % (target, owner[target], item, other, current, other))
                if item not in seen:
                    seen.add(item)
                    stack.append(item)
    return found


def check(root):
    files = list_files(root)
    owner, links = parse_targets(root, files)
    return sorted(set(check_includes(root, files) + check_links(owner, links))), owner


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    args = parser.parse_args(argv)
    violations, owner = check(os.path.abspath(args.root))
    new = [v for v in violations if v not in KNOWN_VIOLATIONS]
    known = [v for v in violations if v in KNOWN_VIOLATIONS]
    for v in new:
        print(v)
    if known:
        print("known violations that the frame_io work removes (%d, not failures):" % len(known))
        for v in known:
            print("  " + v)
    for v in sorted(KNOWN_VIOLATIONS - set(violations)):
        print("note: gone, remove from KNOWN_VIOLATIONS: " + v)
    if not owner:
        print("no CMake targets found under %s" % args.root)
        return 1
    if new:
        print("%d module-boundary violation(s) (rules: docs/ARCHITECTURE.md §2)" % len(new))
        return 1
    print("module boundaries: OK (%d targets)" % len(owner))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
