#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks the layers of docs/architecture.md in the source tree's #include lines.

  Core includes no VTK and nothing of Filters or Rendering;
  Core's public headers include only the standard library and other public Core headers;
  a subsystem's private files (Core/<subsystem>/detail/) are included only by that subsystem,
  its tests (Testing/Core/<subsystem>/), or, for Core/common/detail/, by any of Core;
  a VTK module includes no private header of another module (its public headers are its
  CLASSES), and its public headers include no Eigen, CGAL, OpenMesh, gemmi or GROMACS.

Usage: check_layers.py [ROOT]  (default: the checkout this script is in). Prints one line per
violation and exits with 1 when there is any.
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)
THIRD_PARTY = ("Eigen/", "CGAL/", "OpenMesh/", "gemmi/", "gromacs/", "tao/", "boost/", "zlib.h")
MODULES = ("Filters", "Rendering")
SOURCE_SUFFIXES = (".h", ".hpp", ".cpp", ".cxx", ".cc")


def sources(root, folder):
    """Paths (relative to root) of the C++ files under root/folder."""
    found = []
    for directory, _, files in os.walk(os.path.join(root, folder)):
        for name in files:
            if name.endswith(SOURCE_SUFFIXES):
                found.append(os.path.relpath(os.path.join(directory, name), root))
    return sorted(found)


def includes(root, path):
    """(line number, '<' or '"', included name) of every #include in the file."""
    with open(os.path.join(root, path), encoding="utf-8", errors="replace") as text:
        content = text.read()
    for match in INCLUDE.finditer(content):
        line = content.count("\n", 0, match.start()) + 1
        yield line, match.group(1), match.group(2)


def is_vtk(name):
    base = os.path.basename(name)
    return base.startswith("vtk") or base.endswith("Module.h")


def module_public_headers(root, module):
    """The module's public headers in its CMakeLists.txt: its CLASSES' and its HEADERS and
    NOWRAP_HEADERS (PRIVATE_HEADERS are private)."""
    with open(os.path.join(root, module, "CMakeLists.txt"), encoding="utf-8") as text:
        cmake = text.read()
    classes = set()
    for block in re.findall(r"set\(classes\s+([^)]*)\)", cmake):
        classes.update(block.split())
    for block in re.findall(r"CLASSES\s+([^\n]*)", cmake):
        classes.update(word for word in block.split() if not word.startswith("$"))
    headers = {name + ".h" for name in classes}
    for block in re.findall(r"(?<!PRIVATE_)\b(?:NOWRAP_)?HEADERS\s+([^\n]*)", cmake):
        headers.update(word for word in block.split() if word.endswith(".h"))
    return headers


def check(root):
    problems = []

    def report(path, line, message):
        problems.append(f"{path}:{line}: {message}")

    # Core and its tests.
    if os.path.exists(os.path.join(root, "Core", "vtk.module")):
        report("Core/vtk.module", 1, "Core is a plain library, not a VTK module")
    for path in sources(root, "Core") + sources(root, "Testing/Core"):
        in_core = path.startswith("Core/")
        public = path.startswith("Core/include/")
        parts = path.split("/")
        subsystem = parts[2] if path.startswith("Testing/Core/") else parts[1]
        for line, kind, name in includes(root, path):
            if in_core and is_vtk(name):
                report(path, line, f"Core includes VTK or a MesoLens VTK module ({name})")
            if public:
                if kind == '"' and not name.startswith("mesolens/"):
                    report(path, line, f"a public Core header includes a private file ({name})")
                if kind == "<" and ("/" in name or "." in name):
                    report(path, line, f"a public Core header includes a third-party header ({name})")
            detail = re.match(r"([a-z_0-9]+)/detail/", name)
            if detail and detail.group(1) != subsystem and detail.group(1) != "common":
                report(path, line, f"{subsystem} includes a private file of {detail.group(1)} ({name})")
            if detail and detail.group(1) == "common" and not in_core and subsystem != "common":
                report(path, line, f"a test outside Core/common includes its private file ({name})")

    # Everything outside Core: no Core private file, and the modules' own boundaries.
    public_headers = {module: module_public_headers(root, module) for module in MODULES}
    private_headers = {
        module: {os.path.basename(p) for p in sources(root, module)
                 if p.endswith(".h") and "/Testing/" not in p} - public_headers[module]
        for module in MODULES
    }
    for folder in ("Filters", "Rendering", "Support", "Examples", "Wrapping", "Testing/Benchmarks"):
        for path in sources(root, folder):
            is_test = "/Testing/" in path or path.startswith("Testing/")
            owner = path.split("/")[0]
            for line, _, name in includes(root, path):
                if re.match(r"[a-z_0-9]+/detail/", name):
                    report(path, line, f"a private Core file is included outside Core ({name})")
                if is_test:
                    continue
                for module in MODULES:
                    if module != owner and name in private_headers[module]:
                        report(path, line, f"{owner} includes a private header of {module} ({name})")
                if owner in MODULES and os.path.basename(path) in public_headers[owner]:
                    if name.startswith(THIRD_PARTY):
                        report(path, line, f"a public VTK header includes a third-party header ({name})")
    return problems


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))
    problems = check(root)
    for problem in problems:
        print(problem)
    if problems:
        print(f"{len(problems)} layer violation(s); see docs/architecture.md")
        return 1
    print("layers: Core, Filters and Rendering keep to their boundaries")
    return 0


if __name__ == "__main__":
    sys.exit(main())
