"""The `lora` InstructionParser: the base LM plus the shipped LoRA adapter, constrained decoding.

The model is loaded on the first parse (or by `load()`), not at construction, so the CLI and the
studio start fast. Inference uses one torch thread by default: decoding one instruction is a chain of
small matrix products, and on a busy 2-core machine a second thread waiting at every barrier made it
slower (0.41-0.50 s per instruction with one thread, 0.49-0.95 s with two, same machine and load). The adapter is merged into the base weights after loading: inference then costs
exactly what the base model costs.
"""

from __future__ import annotations

import json
import threading
from importlib import resources
from pathlib import Path

from models.language.alfred import named_types
from models.language.base import check_instruction
from models.language.llm.graph_text import GraphFields, graph_of
from models.values import TaskGraph
from models.world import normalise_room_type


def default_adapter() -> Path:
    return Path(str(resources.files("models").joinpath("weights/lora")))


class LoraParser:
    """Instruction -> TaskGraph with the fine-tuned language model (f_theta1)."""

    name = "lora"

    def __init__(self, adapter: str | Path | None = None, base: str | None = None, threads: int | None = 1):
        from models.language.rule_parser import RuleParser
        self.adapter = Path(adapter) if adapter else default_adapter()
        self.base = base
        self.threads = threads
        self.rules = RuleParser()  # its lexicon (which types are named) and room-type inference
        self._lock = threading.Lock()
        self._model = self._grammar = None

    @property
    def loaded(self) -> bool:
        return self._model is not None

    def load(self) -> "LoraParser":
        with self._lock:
            if self._model is None:
                self._model, self._grammar = load_adapter(self.adapter, self.base, self.threads)
        return self

    def read(self, text: str, room_type: str | None):
        """The decoded fields (with per-field log-probabilities) of a checked instruction."""
        from models.language.llm.decoding import constrained_decode, prompt_text
        self.load()
        ids = self._grammar.tok(prompt_text(text, room_type)).input_ids
        with self._lock:  # one decoding at a time per model: torch already uses every core
            return constrained_decode(self._model, self._grammar, ids)

    def parse(self, instruction: str, room_type: str | None = None) -> TaskGraph:
        text = check_instruction(instruction)
        room = normalise_room_type(room_type) if room_type else None
        decoded = self.read(text, room)
        return self.graph(decoded.fields, text, room)

    def graph(self, fields: GraphFields, text: str, room: str | None) -> TaskGraph:
        graph = graph_of(fields, text, room or "kitchen", named_types(text), self.name)
        if room is None:
            graph = graph.model_copy(update={"room_type": self.rules.infer_room_type([o.type for o in graph.objects])})
        return graph


def load_adapter(adapter: Path, base: str | None = None, threads: int | None = None):
    """(merged model, grammar) from an adapter folder written by `h3ds train language`."""
    import torch

    from models.language.adapters import quiet_peft
    from models.language.llm.base_model import SMOLLM2, load_base
    from models.language.llm.decoding import Grammar
    from models.language.llm.train import META_FILE

    if not (adapter / "adapter_config.json").exists():
        raise FileNotFoundError(f"no LoRA adapter in {adapter} (train one with `h3ds train language`)")
    if threads:
        torch.set_num_threads(threads)
    meta = json.loads((adapter / META_FILE).read_text()) if (adapter / META_FILE).exists() else {}
    model, tok = load_base(base or meta.get("config", {}).get("base", SMOLLM2))
    from peft import PeftModel  # imported only when a model is loaded
    with quiet_peft():
        model = PeftModel.from_pretrained(model, str(adapter)).merge_and_unload()
    model.eval()
    return model, Grammar(tok)
