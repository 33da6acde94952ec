#!/usr/bin/python3
"""The library table of docs/architecture.md against the CMake files.

Reads the table under "## Libraries" (columns: library, what it does, depends on, ...) and every
roadslam_add_library(NAME ... PUBLIC_DEPS ... PRIVATE_DEPS ...) call in libs/*/CMakeLists.txt, keeps
the roadslam:: dependencies only, and fails naming each library and each dependency the page lists but
CMake does not link (extra), or CMake links but the page does not list (missing), and each library one
side has and the other not.

Usage: architecture_doc_test.py SOURCE_DIR [ARCHITECTURE_MD]
"""
import glob
import os
import re
import sys


def cmake_libraries(source_dir):
    """{library: set of roadslam:: dependencies} from libs/*/CMakeLists.txt."""
    libs = {}
    for path in sorted(glob.glob(os.path.join(source_dir, "libs", "*", "CMakeLists.txt"))):
        with open(path, encoding="utf-8") as f:
            text = re.sub(r"#[^\n]*", "", f.read())
        for m in re.finditer(r"roadslam_add_library\(\s*([A-Za-z0-9_]+)([^)]*)\)", text):
            name, body = m.group(1), m.group(2)
            if name in libs:
                raise SystemExit(f"{path}: library {name} is added twice")
            section, deps = None, set()
            for tok in body.split():
                if tok in ("SOURCES", "PUBLIC_DEPS", "PRIVATE_DEPS"):
                    section = tok
                elif section in ("PUBLIC_DEPS", "PRIVATE_DEPS") and tok.startswith("roadslam::"):
                    deps.add(tok[len("roadslam::"):])
            libs[name] = deps
    return libs


def cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def doc_libraries(md_path):
    """{library: set of dependencies} from the table under "## Libraries"."""
    with open(md_path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    try:
        start = lines.index("## Libraries")
    except ValueError:
        raise SystemExit(f"{md_path}: no '## Libraries' heading")
    libs, header = {}, None
    for lineno, line in enumerate(lines[start + 1:], start + 2):
        if line.startswith("## "):
            break
        if not line.startswith("|"):
            if header is not None and libs:
                break  # the table ended
            continue
        row = cells(line)
        if header is None:
            header = row
            if header[:3] != ["library", "what it does", "depends on"]:
                raise SystemExit(f"{md_path}:{lineno}: the table's columns are {header}, "
                                 "expected library | what it does | depends on | ...")
            continue
        if set(line.replace("|", "").strip()) <= set("-: "):
            continue  # the separator row
        if len(row) < 3:
            raise SystemExit(f"{md_path}:{lineno}: a row with {len(row)} cells")
        name = row[0].strip("`")
        deps = set(re.findall(r"`([A-Za-z0-9_]+)`", row[2]))
        if not deps and row[2] not in ("—", "-", ""):
            raise SystemExit(f"{md_path}:{lineno}: library {name}: 'depends on' is '{row[2]}': "
                             "list roadslam libraries in backticks, or — for none")
        if name in libs:
            raise SystemExit(f"{md_path}:{lineno}: library {name} is listed twice")
        libs[name] = deps
    if not libs:
        raise SystemExit(f"{md_path}: no library table under '## Libraries'")
    return libs


def main():
    if len(sys.argv) not in (2, 3):
        raise SystemExit(__doc__)
    source_dir = sys.argv[1]
    md = sys.argv[2] if len(sys.argv) == 3 else os.path.join(source_dir, "docs", "architecture.md")
    cmake, doc = cmake_libraries(source_dir), doc_libraries(md)
    if not cmake:
        raise SystemExit(f"{source_dir}: no roadslam_add_library call in libs/*/CMakeLists.txt")
    errors = []
    for name in sorted(set(cmake) - set(doc)):
        errors.append(f"library {name}: in libs/*/CMakeLists.txt, missing from the table")
    for name in sorted(set(doc) - set(cmake)):
        errors.append(f"library {name}: in the table, but no roadslam_add_library({name} ...)")
    for name in sorted(set(cmake) & set(doc)):
        for dep in sorted(cmake[name] - doc[name]):
            errors.append(f"library {name}: dependency {dep} missing from the table (CMake links it)")
        for dep in sorted(doc[name] - cmake[name]):
            errors.append(f"library {name}: dependency {dep} extra in the table (CMake does not link it)")
    for e in errors:
        print(f"{md}: {e}")
    if errors:
        return 1
    print(f"{md}: {len(doc)} libraries, their roadslam dependencies match libs/*/CMakeLists.txt")
    return 0


if __name__ == "__main__":
    sys.exit(main())
