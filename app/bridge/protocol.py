"""The headset protocol on the studio side: parse and validate a frame against unity-bridge/protocol/v1,
and build the studio's own messages. The schema files are the contract; nothing here restates them."""

from __future__ import annotations

import json
import time
import uuid
from functools import lru_cache
from pathlib import Path

import fastjsonschema
from jsonschema import Draft202012Validator
from jsonschema.exceptions import best_match

VERSION = 1
SCHEMA_DIR = Path(__file__).resolve().parents[2] / "unity-bridge" / "protocol" / f"v{VERSION}"
MAX_MESSAGE_BYTES = 65536  # a headset message larger than this is refused (error too_large)
MAX_FRAME_BYTES = 1 << 20  # the websocket layer closes the connection (1009) above this


class ProtocolError(Exception):
    def __init__(self, code: str, message: str, of: str | None = None):
        super().__init__(message)
        self.code, self.message, self.of = code, message, of


@lru_cache(maxsize=None)
def validators() -> dict[str, Draft202012Validator]:
    return {p.name.removesuffix(".schema.json"): Draft202012Validator(json.loads(p.read_text()))
            for p in sorted(SCHEMA_DIR.glob("*.schema.json")) if p.name != "envelope.schema.json"}


@lru_cache(maxsize=None)
def fast_checks() -> dict[str, object]:
    """The same files compiled to Python by fastjsonschema: ~25x faster on the hot path (glove events).
    Only a message it refuses goes to jsonschema (draft 2020-12, the authority) for the error to report."""
    return {p.name.removesuffix(".schema.json"): fastjsonschema.compile(json.loads(p.read_text()))
            for p in sorted(SCHEMA_DIR.glob("*.schema.json")) if p.name != "envelope.schema.json"}


def parse(frame: str | bytes) -> dict:
    """The message in a frame, or ProtocolError naming what is wrong with it."""
    if len(frame) > MAX_MESSAGE_BYTES:
        raise ProtocolError("too_large", f"message of {len(frame)} bytes; the limit is {MAX_MESSAGE_BYTES}")
    try:
        msg = json.loads(frame)
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise ProtocolError("malformed", f"not JSON: {e}") from None
    if not isinstance(msg, dict):
        raise ProtocolError("malformed", f"a message is a JSON object, not {type(msg).__name__}")
    of = msg.get("id") if isinstance(msg.get("id"), str) else None
    if msg.get("version") != VERSION:
        raise ProtocolError("bad_version", f"protocol version {msg.get('version')!r} is not supported; "
                                           f"this studio speaks version {VERSION}", of)
    kind = msg.get("type")
    validator = validators().get(kind) if isinstance(kind, str) else None
    if validator is None:
        raise ProtocolError("unknown_type", f"unknown message type {kind!r}; known: {', '.join(validators())}", of)
    try:
        fast_checks()[kind](msg)
        return msg
    except fastjsonschema.JsonSchemaException:
        pass
    error = best_match(validator.iter_errors(msg))
    if error is None:  # the two validators disagree: the 2020-12 one decides
        return msg
    where = "/".join(str(p) for p in error.absolute_path) or "(message)"
    raise ProtocolError("invalid", f"{kind} at {where}: {error.message}", of)


def message(kind: str, session: str, seq: int, body: dict) -> dict:
    return {"version": VERSION, "type": kind, "session": session, "id": uuid.uuid4().hex, "seq": seq,
            "ts": time.time(), "body": body}
