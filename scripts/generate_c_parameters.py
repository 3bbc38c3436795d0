#!/usr/bin/env python3
"""Writes ps_sim_def's numeric fields into capi/include/progsim.h from the one parameter table,
core/scene/parameters.def (STYLE.md item 10): one field per row, named group_name, int32_t for
integer rows and double otherwise, documented with the row's doc, unit, range and default.

Usage: scripts/generate_c_parameters.py          rewrites the block between the markers
       scripts/generate_c_parameters.py --check  exits 1 if the header differs (a ctest test)
"""

import argparse
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
TABLE = ROOT / "core" / "scene" / "parameters.def"
HEADER = ROOT / "capi" / "include" / "progsim.h"
BEGIN = (
    "  /* BEGIN fields generated from core/scene/parameters.def by"
    " scripts/generate_c_parameters.py */\n"
)
END = "  /* END generated fields */\n"
WIDTH = 100

ROW = re.compile(
    r"PROGSIM_PARAMETER\(\s*(\w+),\s*(\w+),\s*([^,]+),\s*\"([^\"]*)\",\s*([^,]+),\s*(\w+),"
    r"\s*([^,]+),\s*(\w+),\s*(\w+),\s*\"((?:[^\"\\]|\\.)*)\"\s*\)",
    re.S,
)


def number(text, integer):
    """A table number as the header shows it: 1e6, 0.3, 100."""
    value = float(text)
    if integer or value == int(value) and abs(value) < 1e5:
        return str(int(value))
    return f"{value:g}".replace("e+0", "e").replace("e+", "e").replace("e-0", "e-")


def comment_lines(text, indent):
    """A /** ... */ comment of text wrapped at WIDTH columns."""
    words, lines, line = text.split(), [], indent + "/**"
    for word in words:
        if len(line) + 1 + len(word) > WIDTH - 3:
            lines.append(line)
            line = indent + " *"
        line += " " + word
    lines.append(line + " */")
    return [entry + "\n" for entry in lines]


def fields(table_text):
    out = []
    for match in ROW.finditer(table_text):
        group, name, default, unit, lo, lo_in, hi, hi_in, integer, doc = match.groups()
        is_int = integer.strip() == "true"
        if is_int:  # an int32_t field must hold its range and default
            for value in (lo, hi, default):
                assert -(2**31) <= float(value) < 2**31, f"{group}.{name}: {value} exceeds int32"
        bounds = "[" if lo_in == "true" else "("
        bounds += f"{number(lo, is_int)}, {number(hi, is_int)}"
        bounds += "]" if hi_in == "true" else ")"
        text = f"{doc} Unit {unit}, range {bounds}; default {number(default, is_int)}."
        out += comment_lines(text, "  ")
        out.append(f"  {'int32_t' if is_int else 'double'} {group}_{name};\n")
    return out


def generated_header(header_text, table_text):
    start, stop = header_text.index(BEGIN) + len(BEGIN), header_text.index(END)
    return header_text[:start] + "".join(fields(table_text)) + header_text[stop:]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="fail if the header is stale")
    args = parser.parse_args()
    header = HEADER.read_text(encoding="utf-8")
    wanted = generated_header(header, TABLE.read_text(encoding="utf-8"))
    if args.check:
        if wanted != header:
            print(f"{HEADER} is stale: run scripts/generate_c_parameters.py", file=sys.stderr)
            return 1
        print(f"{HEADER}: ps_sim_def's parameter fields match {TABLE.name}")
        return 0
    HEADER.write_text(wanted, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
