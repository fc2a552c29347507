#!/usr/bin/python3
# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Extracts the C++ programs of the manual (every ```cpp block of the given Markdown pages) into
one source file each, so that the build compiles them (doc/CMakeLists.txt).

Each block must be a whole program (blocks marked `<!-- example: examples/NAME.cpp -->` are
copies of the example programs and are left to them): its #include lines, then code with a main(). The includes
stay at file scope; the rest goes into a namespace of its own with main() renamed run(), so that
the programs can be compiled together (the unity build) and none is run. A block without main()
is an error: signature listings and outlines are fenced as ```text.

    extract_doc_snippets.py OUT_DIR PAGE.md...   (writes OUT_DIR/<page>_<k>.cpp and a stamp)
"""

import os
import re
import sys


def blocks(page):
    """The ```cpp blocks of a page with the line of their first line, except those marked
    `<!-- example: examples/NAME.cpp -->`: copies of example programs, compiled as such (a test
    checks that they are the files)."""
    with open(page) as f:
        text = f.read()
    for match in re.finditer(r"^```cpp\n(.*?)^```", text, re.S | re.M):
        before = text[:match.start()].rstrip("\n").rsplit("\n", 1)[-1]
        if before.startswith("<!-- example:"):
            continue
        yield text.count("\n", 0, match.start()) + 2, match.group(1)


def translate(page, line, code, name):
    lines = code.split("\n")
    includes = [l for l in lines if l.startswith("#include")]
    body = [l for l in lines if not l.startswith("#include")]
    body_text = "\n".join(body)
    if not re.search(r"\bint\s+main\s*\(", body_text):
        raise ValueError(f"{page}:{line}: this ```cpp block has no main(): fence listings and outlines as ```text")
    body_text = re.sub(r"\bint\s+main\s*\(", "int run(", body_text, count=1)
    return (f"// Generated from {page}, the ```cpp block at line {line}, by scripts/extract_doc_snippets.py.\n"
            + "\n".join(includes) + f"\n\nnamespace {name} {{\n#line {line + len(includes)} \"{page}\"\n"
            + body_text + f"\n}} // namespace {name}\n")


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    out_dir, pages = argv[1], argv[2:]
    os.makedirs(out_dir, exist_ok=True)
    written = []
    try:
        for page in pages:
            stem = re.sub(r"\W", "_", os.path.splitext(os.path.basename(page))[0])
            for k, (line, code) in enumerate(blocks(page)):
                name = f"doc_snippet_{stem}_{k}"
                source = translate(page, line, code, name)
                path = os.path.join(out_dir, name + ".cpp")
                # Rewritten only when changed, so that an edit of one page recompiles its programs only.
                if not os.path.exists(path) or open(path).read() != source:
                    with open(path, "w") as f:
                        f.write(source)
                written.append(path)
    except (OSError, ValueError) as e:
        print(f"extract_doc_snippets: {e}", file=sys.stderr)
        return 1
    with open(os.path.join(out_dir, "snippets.txt"), "w") as f:
        f.write("\n".join(written) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
