"""cffi build script of the ``progsim._progsim_cffi`` extension (out-of-line, API mode).

The C declarations are not copied by hand: :func:`cdef_from_header` derives them from
``progsim.h`` at build time, so the header and the bindings cannot drift apart. Only the
Python-side progress trampoline (an ``extern "Python"`` function) is declared here.

Where things are found (both overridable through the environment):

* ``PROGSIM_INCLUDE_DIR``: the folder holding ``progsim.h``
  (default ``<repo>/capi/include``);
* ``PROGSIM_LIB_DIR``: the folder holding ``libprogsim.so`` (default
  ``<repo>/build/release/core``, as made by ``scripts/build.sh release``). The extension
  gets that folder as its run-time search path (rpath), so ``import progsim`` needs no
  ``LD_LIBRARY_PATH``.
"""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

from cffi import FFI

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent

INCLUDE_DIR = Path(os.environ.get("PROGSIM_INCLUDE_DIR") or REPO / "capi" / "include").resolve()
LIB_DIR = Path(os.environ.get("PROGSIM_LIB_DIR") or REPO / "build" / "release" / "core").resolve()
HEADER = INCLUDE_DIR / "progsim.h"

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


def make_ffibuilder() -> FFI:
    """An FFI builder for ``progsim._progsim_cffi`` compiled against :data:`HEADER`."""
    if not HEADER.is_file():
        sys.exit(
            f"progsim_build.py: {HEADER} not found; set PROGSIM_INCLUDE_DIR to the folder "
            "holding progsim.h"
        )
    library_files = list(LIB_DIR.glob("libprogsim.so*")) + list(LIB_DIR.glob("libprogsim.dylib"))
    if not library_files:
        sys.exit(
            f"progsim_build.py: no libprogsim in {LIB_DIR}; build it first "
            "(scripts/build.sh release) or set PROGSIM_LIB_DIR"
        )
    builder = FFI()
    builder.cdef(cdef_from_header(HEADER.read_text(encoding="utf-8")) + PYTHON_CDEF)
    builder.set_source(
        "progsim._progsim_cffi",
        '#include "progsim.h"\n',
        include_dirs=[str(INCLUDE_DIR)],
        library_dirs=[str(LIB_DIR)],
        runtime_library_dirs=[str(LIB_DIR)],
        libraries=["progsim"],
    )
    return builder


ffibuilder = make_ffibuilder()

if __name__ == "__main__":
    if "--print-cdef" in sys.argv:
        print(cdef_from_header(HEADER.read_text(encoding="utf-8")))
    else:
        ffibuilder.compile(verbose=True)
