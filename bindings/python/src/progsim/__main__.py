"""``python -m progsim sweep SCENE --param NAME=SPEC ... --out DIR`` (also ``progsim sweep``).

A SPEC is ``a:b:n`` (n values from a to b), ``v1,v2,...`` (numbers or words) or a JSON list
(``[[0,0,1],[0,0,2]]``, for vectors and keyframe dicts).
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any, Sequence, Tuple

from ._errors import ProgsimError


def _word_or_number(text: str) -> Any:
    """A list entry of a SPEC: a number where it parses as one, else the word."""
    try:
        return float(text)
    except ValueError:
        return text


def parse_param(text: str) -> Tuple[str, Any]:
    """``NAME=SPEC`` → (name, list of values or Range)."""
    from .sweep import Range

    name, sep, spec = text.partition("=")
    if not sep or not name or not spec:
        raise argparse.ArgumentTypeError(f"--param {text!r}: expected NAME=SPEC")
    if spec.lstrip().startswith("["):
        try:
            values = json.loads(spec)
        except json.JSONDecodeError as error:
            raise argparse.ArgumentTypeError(f"--param {name}: not a JSON list ({error})")
        if not isinstance(values, list):
            raise argparse.ArgumentTypeError(f"--param {name}: a JSON SPEC must be a list")
        return name, values
    parts = spec.split(":")
    if len(parts) == 3:
        try:
            return name, Range(float(parts[0]), float(parts[1]), int(parts[2]))
        except ValueError:
            raise argparse.ArgumentTypeError(f"--param {name}: a:b:n needs numbers, n whole")
    return name, [_word_or_number(part) for part in spec.split(",")]


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="progsim", description="progsim's Python tools")
    commands = parser.add_subparsers(dest="command", required=True)
    sweep = commands.add_parser(
        "sweep",
        help="one preview per parameter combination, on Dask",
        description=__doc__.splitlines()[0],
    )
    sweep.add_argument("scene", help="scene file (JSON)")
    sweep.add_argument(
        "--param",
        action="append",
        type=parse_param,
        default=[],
        metavar="NAME=SPEC",
        help="a swept parameter (repeatable)",
    )
    sweep.add_argument("--out", required=True, help="folder for runs.csv and contact_sheet.png")
    sweep.add_argument("--scheduler", help="a Dask scheduler address (default: a local cluster)")
    sweep.add_argument("--serial", action="store_true", help="run in this process, no Dask")
    sweep.add_argument("--workers", type=int, help="local worker processes (default: cores)")
    sweep.add_argument("--samples", type=int, help="random combinations instead of the grid")
    sweep.add_argument("--seed", type=int, default=0, help="seed of --samples (default 0)")
    sweep.add_argument("--steps", type=int, help="preview steps (default: the scene's duration)")
    return parser


def _run_sweep(args: argparse.Namespace) -> int:
    from .sweep import sweep

    if not args.param:
        print("progsim sweep: give at least one --param NAME=SPEC", file=sys.stderr)
        return 2
    client = "serial" if args.serial else args.scheduler
    runs = sweep(
        args.scene,
        dict(args.param),
        client,
        samples=args.samples,
        seed=args.seed,
        steps=args.steps,
        workers=args.workers,
    )
    directory = runs.write(args.out)
    failed = [row for row in runs.rows() if row["status"] != "PS_OK"]
    print(
        f"progsim sweep: {len(runs)} runs ({len(failed)} failed) -> {directory}/runs.csv, "
        f"{directory}/contact_sheet.png"
    )
    for row in failed:
        print(f"  run {row['index']}: {row['status']}: {row['error']}", file=sys.stderr)
    return 1 if failed else 0


def main(argv: Sequence[str]) -> int:
    """The command line; returns the exit status (1 if a run failed, 2 for bad usage)."""
    args = _parser().parse_args(list(argv))
    try:
        return _run_sweep(args)
    except (ProgsimError, OSError) as error:
        print(f"progsim {args.command}: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
