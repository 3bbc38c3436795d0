"""Scene files as Python dicts: JSON with comments in, dotted-path overrides, JSON out."""

from __future__ import annotations

import copy
import json
from pathlib import Path
from typing import Any, Dict, Mapping, Union

from ._errors import InvalidSceneError

__all__ = ["load_scene", "override"]


def _without_comments(text: str) -> str:
    """``text`` with ``//`` and ``/* */`` comments outside strings replaced by spaces (the
    scene format of scenes/README.md allows both)."""
    out = []
    i, n = 0, len(text)
    in_string = False
    while i < n:
        c = text[i]
        if in_string:
            out.append(c)
            if c == "\\" and i + 1 < n:
                out.append(text[i + 1])
                i += 1
            elif c == '"':
                in_string = False
        elif c == '"':
            in_string = True
            out.append(c)
        elif text.startswith("//", i):
            end = text.find("\n", i)
            i = n if end < 0 else end
            continue
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            if end < 0:
                raise InvalidSceneError("an unterminated /* comment in the scene")
            out.append(" ")
            i = end + 2
            continue
        else:
            out.append(c)
        i += 1
    return "".join(out)


def load_scene(scene: Union[str, Path, Mapping[str, Any]]) -> Dict[str, Any]:
    """A scene as a dict: from a path to a scene file, from its JSON text (comments allowed)
    or from a dict (copied).

    Raises:
        InvalidSceneError: the text is not JSON (the message gives line and column).
        ProgsimIOError: the file cannot be read (as :class:`OSError`).
    """
    if isinstance(scene, Mapping):
        return copy.deepcopy(dict(scene))
    text = Path(scene).read_text(encoding="utf-8") if isinstance(scene, Path) else scene
    try:
        value = json.loads(_without_comments(text))
    except json.JSONDecodeError as error:
        raise InvalidSceneError(f"the scene is not JSON: {error}") from None
    if not isinstance(value, dict):
        raise InvalidSceneError("a scene is a JSON object")
    return value


def override(scene: Mapping[str, Any], path: str, value: Any) -> Dict[str, Any]:
    """A copy of ``scene`` with the member at dotted ``path`` set to ``value``; list entries
    are addressed by index (``bodies.0.material.youngs_modulus``), missing objects are made.

    Raises:
        InvalidSceneError: the path crosses a value that is neither an object nor a list, or
            an index out of range.
    """
    result = copy.deepcopy(dict(scene))
    keys = path.split(".")
    node: Any = result
    for depth, key in enumerate(keys):
        last = depth == len(keys) - 1
        where = ".".join(keys[: depth + 1])
        if isinstance(node, list):
            if not key.isdigit() or int(key) >= len(node):
                raise InvalidSceneError(f"scene path {path}: no entry {where}")
            index = int(key)
            if last:
                node[index] = value
            node = node[index]
        elif isinstance(node, dict):
            if last:
                node[key] = value
            else:
                node = node.setdefault(key, {})
        else:
            raise InvalidSceneError(f"scene path {path}: {where} is not an object or a list")
    return result
