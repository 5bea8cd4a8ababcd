"""How the command line reads its input: bad input is one line naming the problem (exit status 2), never a
traceback."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from pydantic import ValidationError


class BadInput(Exception):
    """Input the user can fix; shown as one line, exit status 2."""


class Parser(argparse.ArgumentParser):
    def error(self, message: str):  # one line instead of argparse's usage block
        raise BadInput(message)


def value_error(path: str, err: ValidationError, what: str) -> BadInput:
    first = err.errors()[0]
    where = ".".join(str(p) for p in first["loc"]) or what
    return BadInput(f"{path}: {where}: {first['msg']}")


def load_value(path: str, model, what: str):
    """A JSON file read into `model` (a pydantic value type); each problem is a BadInput naming the file."""
    try:
        raw = Path(path).read_bytes()
    except OSError as e:
        raise BadInput(f"{path}: cannot read the {what} ({e.strerror})") from e
    try:
        data = json.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as e:
        raise BadInput(f"{path}: not valid JSON ({e})") from e
    if not isinstance(data, dict):
        raise BadInput(f"{path}: a {what} must be a JSON object, not {type(data).__name__}")
    try:
        return model.model_validate(data)
    except ValidationError as e:
        raise value_error(path, e, what) from e
