"""Prompt, training targets and greedy decoding restricted to the compact grammar over catalogue types.

Each field's options are tokenised on their own (" cool", " Bread", ...) and closed by the separator
token " |" (the last field by the end-of-sequence token), so an option's token sequence never is a
prefix of another's. The options of a field form a prefix trie; decoding walks it, asking the model
only where the trie branches and feeding forced tokens in one step (a catalogue name of 4 tokens often
costs one forward pass). The output is therefore always a valid graph over catalogue types.
"""

from __future__ import annotations

import inspect
import math
from dataclasses import dataclass, field
from functools import cache

from models.language.llm.graph_text import (SLICE_WORDS, TASK_WORDS, GraphFields, destination_types,
                                            target_types)

PROMPT = "Instruction: {instruction}\nRoom: {room}\nTask graph:"
FIELD_SEPARATOR = " |"


def prompt_text(instruction: str, room_type: str | None) -> str:
    return PROMPT.format(instruction=instruction, room=room_type or "unknown")


@dataclass
class Trie:
    children: dict[int, "Trie"] = field(default_factory=dict)
    value: str | None = None  # set on the node after an option's closing token

    def add(self, ids: list[int], value: str) -> None:
        node = self
        for i in ids:
            node = node.children.setdefault(i, Trie())
        node.value = value


class Grammar:
    """Token tries of the four fields for one tokenizer."""

    def __init__(self, tokenizer):
        self.tok = tokenizer
        self.sep = self._ids(FIELD_SEPARATOR)
        if len(self.sep) != 1:
            raise ValueError(f"the separator {FIELD_SEPARATOR!r} must be one token for this tokenizer")
        self.eos = tokenizer.eos_token_id
        self.tasks = self._trie(TASK_WORDS, self.sep)
        self.slices = self._trie(SLICE_WORDS, self.sep)
        self.targets = self._trie(target_types(), self.sep)
        self.destinations = {t: self._trie(destination_types(t), [self.eos]) for t in TASK_WORDS.values()}

    def _ids(self, text: str) -> list[int]:
        return self.tok(text, add_special_tokens=False).input_ids

    def _trie(self, words, closing: list[int]) -> Trie:
        root = Trie()
        for w in words:
            root.add(self._ids(" " + w) + closing, w)
        return root

    def target_ids(self, fields: GraphFields) -> list[int]:
        """The token ids the model is trained to write for `fields` (the same pieces decoding walks)."""
        task, sliced, target, dest = fields.words()
        return (self._ids(" " + task) + self.sep + self._ids(" " + sliced) + self.sep + self._ids(" " + target)
                + self.sep + self._ids(" " + dest) + [self.eos])


@dataclass(frozen=True)
class Decoded:
    fields: GraphFields
    logprob: tuple[float, float, float, float]  # per field, summed over its chosen tokens (full vocabulary)
    forward_passes: int

    @property
    def confidence(self) -> float:
        return math.exp(sum(self.logprob))


@cache
def cache_keyword(model_class: type) -> str:
    """What the model's forward calls its key-value cache, in and out: `cache` since transformers 5.x
    (`past_key_values` is deprecated there, to be removed in 5.40), `past_key_values` before."""
    return "cache" if "cache" in inspect.signature(model_class.forward).parameters else "past_key_values"


def constrained_decode(model, grammar: Grammar, prompt_ids: list[int]) -> Decoded:
    """Greedy decoding of the four fields, each restricted to its trie."""
    import torch

    past, pending, passes = None, list(prompt_ids), 0
    base = model.get_base_model() if hasattr(model, "get_base_model") else model  # a peft model passes it on
    logits, keyword = None, cache_keyword(type(base))
    values, logps = [], []
    with torch.inference_mode():
        for index in range(4):
            node = (grammar.tasks, grammar.slices, grammar.targets)[index] if index < 3 else \
                grammar.destinations[TASK_WORDS[values[0]]]
            lp = 0.0
            while node.value is None:
                if len(node.children) == 1:
                    (token, node), = node.children.items()
                    # a forced token carries no choice, but its probability still counts for confidence
                    pending.append(token)
                    continue
                out = model(input_ids=torch.tensor([pending]), use_cache=True, **{keyword: past})
                passes += 1
                past, logits = getattr(out, keyword), out.logits[0, -1]
                logsm = torch.log_softmax(logits.float(), dim=-1)
                allowed = torch.tensor(list(node.children))
                token = int(allowed[int(torch.argmax(logsm[allowed]))])
                lp += float(logsm[token])
                pending = [token]
                node = node.children[token]
            values.append(node.value)
            logps.append(lp)
    task, sliced, target, dest = values
    return Decoded(GraphFields(TASK_WORDS[task], sliced == "sliced", target, dest), tuple(logps), passes)


def free_decode(model, tokenizer, prompt_ids: list[int], max_new_tokens: int = 24) -> str:
    """Unconstrained greedy decoding (the alternative to the trie, kept to measure it against)."""
    import torch
    with torch.inference_mode():
        out = model.generate(torch.tensor([prompt_ids]), attention_mask=torch.ones(1, len(prompt_ids), dtype=torch.long),
                             max_new_tokens=max_new_tokens, do_sample=False, eos_token_id=tokenizer.eos_token_id,
                             pad_token_id=tokenizer.eos_token_id)
    return tokenizer.decode(out[0, len(prompt_ids):], skip_special_tokens=True)
