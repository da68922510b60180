#!/usr/bin/env python3
"""Compiles the C++ snippets of Markdown files as written (a drift check of the docs).

    python3 tests/docs/readme_snippets.py COMPILER INCLUDE_DIR MARKDOWN [MARKDOWN ...]

Every ```cpp block is compiled on its own (-fsyntax-only, C++20) with INCLUDE_DIR (the public
headers) on the include path: its #include lines at file scope, the rest as the body of a
function that declares what a snippet leaves to the game (`myGetProcAddress`, `fatal`,
`myLightingCode`; the parameters `camera`, `mesh`, `localPoint`). Exit 0 when every block
compiles and there is at least one; 1 naming the file, the block's first line and the
compiler's message otherwise.
"""
import os
import re
import subprocess
import sys
import tempfile

# What the README's game code calls without defining: the game's own names.
GAME_DECLARATIONS = """#include <shadow/scene.h>
#include <string>
void* myGetProcAddress(const char* name);
[[noreturn]] void fatal(const std::string& message);
extern const std::string myLightingCode;
"""


def blocks(text):
    """(first line number, code) of each ```cpp block."""
    out = []
    for m in re.finditer(r"^```cpp\n(.*?)^```", text, re.S | re.M):
        out.append((text.count("\n", 0, m.start()) + 2, m.group(1)))
    return out


def translation_unit(code):
    includes = [l for l in code.splitlines() if l.lstrip().startswith("#include")]
    body = [l for l in code.splitlines() if not l.lstrip().startswith("#include")]
    return ("\n".join(includes) + "\n" + GAME_DECLARATIONS +
            "void readmeSnippet(const shadow::CameraView& camera, const shadow::MeshData& mesh,\n"
            "                   const glm::vec3& localPoint) {\n    (void)camera, (void)mesh, (void)localPoint;\n" +
            "\n".join(body) + "\n}\n")


def main():
    if len(sys.argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    compiler, include = sys.argv[1:3]
    found, failed = 0, 0
    for path in sys.argv[3:]:
        for line, code in blocks(open(path).read()):
            found += 1
            with tempfile.NamedTemporaryFile("w", suffix=".cpp", delete=False) as f:
                f.write(translation_unit(code))
                name = f.name
            try:
                r = subprocess.run([compiler, "-std=c++20", "-fsyntax-only", "-Wall", "-I", include, name],
                                   capture_output=True, text=True)
            finally:
                os.unlink(name)
            if r.returncode != 0:
                failed += 1
                print(f"{path}:{line}: the C++ block does not compile:\n{r.stderr}", file=sys.stderr)
            else:
                print(f"{path}:{line}: compiles")
    if found == 0:
        print("no ```cpp block in " + " ".join(sys.argv[3:]), file=sys.stderr)
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
