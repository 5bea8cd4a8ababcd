"""Instruction -> TaskGraph."""

from models.language.base import InstructionError, InstructionParser, check_instruction
from models.language.rule_parser import RuleParser

__all__ = ["InstructionError", "InstructionParser", "RuleParser", "check_instruction"]
