"""The parser interface every instruction -> TaskGraph model implements, and input checks they share."""

from __future__ import annotations

from typing import Protocol

from models.errors import InputError
from models.values import TaskGraph

MAX_INSTRUCTION_CHARS = 1000


class InstructionError(InputError):
    """An instruction that cannot be parsed; the message names the problem in one line."""


class InstructionParser(Protocol):
    name: str

    def parse(self, instruction: str, room_type: str | None = None) -> TaskGraph: ...


def check_instruction(text: object) -> str:
    """The instruction, stripped, or an InstructionError saying what is wrong with it."""
    if not isinstance(text, str):
        raise InstructionError(f"the instruction must be text, not {type(text).__name__}")
    if "\x00" in text or any(not (ch.isprintable() or ch.isspace()) for ch in text):
        raise InstructionError("the instruction contains binary or control characters")
    stripped = " ".join(text.split())
    if not stripped:
        raise InstructionError("the instruction is empty")
    if len(stripped) > MAX_INSTRUCTION_CHARS:
        raise InstructionError(f"the instruction is {len(stripped)} characters long; the limit is "
                               f"{MAX_INSTRUCTION_CHARS}")
    if not any(ch.isalpha() for ch in stripped):
        raise InstructionError("the instruction contains no words")
    return stripped
