"""Generates the C source of the ``progsim._progsim_cffi`` extension (cffi, out-of-line, API mode).

CMake (``bindings/python/CMakeLists.txt``, driven by scikit-build-core when pip builds the
package) runs ``python progsim_build.py --emit-c OUT.c`` and compiles ``OUT.c`` against the
``progsim`` library target it builds in the same tree, so the wheel carries both.

The C declarations are not copied by hand: :func:`cdef_from_header` derives them from
``progsim.h``, so the header and the bindings cannot drift apart. Only the Python-side
progress trampoline (an ``extern "Python"`` function) is declared here.

Usage: ``python progsim_build.py --emit-c OUT.c [--header progsim.h]`` or
``python progsim_build.py --print-cdef [--header progsim.h]``.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from cffi import FFI

HERE = Path(__file__).resolve().parent
DEFAULT_HEADER = HERE.parent.parent / "capi" / "include" / "progsim.h"

#: Declarations that exist for Python only: the C-callable trampoline of ps_progress_fn.
PYTHON_CDEF = """
extern "Python" int32_t _progsim_progress(void* user_data, int32_t done, int32_t total,
                                          const char* phase);
"""

_BLOCK_COMMENT = re.compile(r"/\*.*?\*/", re.DOTALL)
_LINE_COMMENT = re.compile(r"//[^\n]*")
_CONDITIONAL = re.compile(r"#\s*(if|ifdef|ifndef)\b(.*)")
_OBJECT_MACRO = re.compile(r"#\s*define\s+([A-Za-z_]\w*)(?!\()\s+(\S.*)")


def cdef_from_header(text: str, export_macro: str = "PS_API") -> str:
    """Turns the public header's text into declarations that ``FFI.cdef`` accepts.

    Comments and preprocessor lines are dropped; ``#ifdef __cplusplus`` blocks are left out
    (they only hold ``extern "C" {`` and its ``}``); an object-like ``#define NAME value``
    becomes ``#define NAME ...`` so that the C compiler supplies the value (API mode); the
    export macro disappears from declarations.
    """
    text = _BLOCK_COMMENT.sub(" ", text)
    text = _LINE_COMMENT.sub("", text)
    # Join continued preprocessor lines.
    text = re.sub(r"\\\n", " ", text)
    out: list[str] = []
    skipping: list[bool] = []  # one entry per open conditional: is its body left out?
    for line in text.splitlines():
        stripped = line.strip()
        if stripped.startswith("#"):
            conditional = _CONDITIONAL.match(stripped)
            if conditional:
                skipping.append("__cplusplus" in conditional.group(2))
            elif re.match(r"#\s*(else|elif)\b", stripped):
                if skipping and skipping[-1]:
                    skipping[-1] = False
                elif skipping and "__cplusplus" in stripped:
                    skipping[-1] = True
            elif re.match(r"#\s*endif\b", stripped):
                if skipping:
                    skipping.pop()
            elif not any(skipping):
                macro = _OBJECT_MACRO.match(stripped)
                if macro and macro.group(1) != export_macro:
                    out.append(f"#define {macro.group(1)} ...")
            continue
        if any(skipping):
            continue
        out.append(line)
    cdef = "\n".join(out)
    cdef = re.sub(rf"\b{re.escape(export_macro)}\b", "", cdef)
    return re.sub(r"\n\s*\n+", "\n", cdef).strip() + "\n"


def make_ffibuilder(header: Path) -> FFI:
    """An FFI builder for ``progsim._progsim_cffi`` whose declarations come from ``header``."""
    if not header.is_file():
        sys.exit(f"progsim_build.py: {header} not found")
    builder = FFI()
    builder.cdef(cdef_from_header(header.read_text(encoding="utf-8")) + PYTHON_CDEF)
    builder.set_source("progsim._progsim_cffi", '#include "progsim.h"\n')
    return builder


def main(argv: list[str]) -> int:
    """Command line: ``--emit-c OUT.c`` or ``--print-cdef``, each with optional ``--header``."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    action = parser.add_mutually_exclusive_group(required=True)
    action.add_argument(
        "--emit-c", metavar="OUT.c", type=Path, help="write the extension's C source"
    )
    action.add_argument("--print-cdef", action="store_true", help="print the declarations")
    parser.add_argument("--header", type=Path, default=DEFAULT_HEADER, help="progsim.h to read")
    args = parser.parse_args(argv)
    if args.print_cdef:
        print(cdef_from_header(args.header.read_text(encoding="utf-8")))
        return 0
    args.emit_c.parent.mkdir(parents=True, exist_ok=True)
    make_ffibuilder(args.header).emit_c_code(str(args.emit_c))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
