"""The `openai` InstructionParser: the compact task graph from an OpenAI-compatible chat endpoint.

For users who serve a bigger model (vLLM, Ollama, llama.cpp's server): POST {base_url}/chat/completions
with a few-shot prompt that asks for the same compact form the LoRA model writes. A served model
cannot be constrained to the catalogue here, so each type name it writes is snapped to the catalogue
(exact, case-insensitive, then the project's synonym lexicon, then the closest spelling); an answer
that cannot be read raises InstructionError naming the problem. Standard library HTTP only.
"""

from __future__ import annotations

import difflib
import json
import os
import re
import urllib.error
import urllib.request

from models.language.alfred import named_types
from models.language.base import InstructionError, check_instruction
from models.language.llm.decoding import prompt_text
from models.language.llm.graph_text import (SLICE_WORDS, TASK_WORDS, GraphFields, GraphTextError,
                                            destination_types, graph_of, target_types)
from models.values import TaskGraph
from models.world import normalise_room_type

SYSTEM = (
    "You turn a household instruction into a task graph for an AI2-THOR robot. Answer with exactly one "
    "line: <task> | <whole or sliced> | <Target> | <Destination>. task is one of: place, look, cool, heat "
    "(cool: it goes through the fridge; heat: through the microwave; look: examine it under a lamp). "
    "Target and Destination are AI2-THOR object types in CamelCase (Apple, Mug, CounterTop, SinkBasin, "
    "DiningTable, DeskLamp, FloorLamp, ...). For look, Destination is the lamp. No other text."
)
SHOTS = (
    ("Put a chilled bread on the counter", "kitchen", "cool | whole | Bread | CounterTop"),
    ("Examine the remote under the tall lamp", "living room", "look | whole | RemoteControl | FloorLamp"),
    ("Put a warm slice of apple in the sink", "kitchen", "heat | sliced | Apple | SinkBasin"),
    ("Move the pencil from the desk to the dresser", "bedroom", "place | whole | Pencil | Dresser"),
)


class OpenAIParser:
    """Instruction -> TaskGraph through /v1/chat/completions."""

    name = "openai"

    def __init__(self, base_url: str | None = None, model: str | None = None, api_key: str | None = None,
                 timeout: float = 30.0):
        self.base_url = (base_url or os.environ.get("H3DS_OPENAI_BASE_URL") or "http://127.0.0.1:8000/v1").rstrip("/")
        self.model = model or os.environ.get("H3DS_OPENAI_MODEL") or "default"
        self.api_key = api_key or os.environ.get("H3DS_OPENAI_API_KEY") or os.environ.get("OPENAI_API_KEY")
        self.timeout = timeout
        from models.language.rule_parser import RuleParser
        self.rules = RuleParser()

    def messages(self, text: str, room: str | None) -> list[dict]:
        out = [{"role": "system", "content": SYSTEM}]
        for instr, shot_room, answer in SHOTS:
            out += [{"role": "user", "content": prompt_text(instr, shot_room)}, {"role": "assistant", "content": answer}]
        return out + [{"role": "user", "content": prompt_text(text, room)}]

    def complete(self, messages: list[dict]) -> str:
        body = json.dumps({"model": self.model, "messages": messages, "temperature": 0.0, "max_tokens": 48}).encode()
        headers = {"Content-Type": "application/json"}
        if self.api_key:
            headers["Authorization"] = f"Bearer {self.api_key}"
        req = urllib.request.Request(f"{self.base_url}/chat/completions", data=body, headers=headers, method="POST")
        try:
            with urllib.request.urlopen(req, timeout=self.timeout) as resp:
                data = json.loads(resp.read().decode())
        except urllib.error.HTTPError as e:
            raise InstructionError(f"the chat endpoint {self.base_url} answered HTTP {e.code}: "
                                   f"{e.read()[:200].decode(errors='replace')}") from e
        except (urllib.error.URLError, TimeoutError, OSError) as e:
            raise InstructionError(f"cannot reach the chat endpoint {self.base_url}: {e}") from e
        except json.JSONDecodeError as e:
            raise InstructionError(f"the chat endpoint {self.base_url} did not answer JSON") from e
        try:
            return data["choices"][0]["message"]["content"]
        except (KeyError, IndexError, TypeError) as e:
            raise InstructionError(f"the chat endpoint's answer has no choices[0].message.content: "
                                   f"{json.dumps(data)[:200]}") from e

    def parse(self, instruction: str, room_type: str | None = None) -> TaskGraph:
        text = check_instruction(instruction)
        room = normalise_room_type(room_type) if room_type else None
        answer = self.complete(self.messages(text, room))
        try:
            fields = self.read_answer(answer)
        except GraphTextError as e:
            raise InstructionError(f"the served model's answer could not be read ({e})") from e
        graph = graph_of(fields, text, room or "kitchen", named_types(text), self.name)
        if room is None:
            graph = graph.model_copy(update={"room_type": self.rules.infer_room_type([o.type for o in graph.objects])})
        return graph

    def read_answer(self, answer: str) -> GraphFields:
        line = next((ln for ln in answer.strip().splitlines() if ln.count("|") >= 3), answer.strip())
        parts = [p.strip().strip("`*. ").lower() if i < 2 else p.strip().strip("`*. ")
                 for i, p in enumerate(line.split("|"))]
        if len(parts) != 4:
            raise GraphTextError(f"expected 'task | whole/sliced | Target | Destination', got {line[:120]!r}")
        task, sliced, target, dest = parts
        task = task.split()[-1] if task else task  # "Sure! place" -> "place"
        if task not in TASK_WORDS or sliced not in SLICE_WORDS:
            raise GraphTextError(f"unknown task {task!r} or slicing {sliced!r}")
        task_type = TASK_WORDS[task]
        return GraphFields(task_type, sliced == "sliced", self.snap(target, target_types()),
                           self.snap(dest, destination_types(task_type)))

    def snap(self, name: str, allowed: tuple[str, ...]) -> str:
        """A served model's type name -> an allowed catalogue type, or GraphTextError."""
        if name in allowed:
            return name
        folded = {a.lower(): a for a in allowed}
        key = re.sub(r"[^a-z0-9]", "", name.lower())
        if key in folded:
            return folded[key]
        words = " ".join(re.findall(r"[a-z]+|[A-Z][a-z]*", name)).lower()
        hits = [t for t in self.rules.lexicon.get(words, ()) if t in allowed]
        if hits:
            return hits[0]
        close = difflib.get_close_matches(key, list(folded), n=1, cutoff=0.8)
        if close:
            return folded[close[0]]
        raise GraphTextError(f"{name!r} is not an AI2-THOR type this task allows")
