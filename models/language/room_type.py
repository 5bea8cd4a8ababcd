"""The room type read from the instruction by MiniLM embedding similarity (issue 10 allows it in place
of the paper's few-shot prompt): the most common room type among the K id_train instructions whose
all-MiniLM-L6-v2 sentence embeddings (mean over tokens, unit length) are closest by cosine.

Measured against the rules' frequency rule (`RuleParser.infer_room_type`) by `h3ds bench language`;
the parsers do not use it. K and the memory size were set before measuring, not tuned.
"""

from __future__ import annotations

import random
from collections import Counter

K = 10
MEMORY_ROWS = 3000  # a seeded sample of id_train: about 30 s to embed on this CPU
SEED = 0


def embed(texts: list[str], batch: int = 128):
    """(n, 384) unit-length sentence embeddings."""
    import numpy as np
    import torch

    from models.language.roles.model import MAX_TOKENS, encoder
    tok, model = encoder()
    out = []
    with torch.inference_mode():
        for i in range(0, len(texts), batch):
            enc = tok(texts[i:i + batch], truncation=True, max_length=MAX_TOKENS, padding=True, return_tensors="pt")
            mask = enc["attention_mask"].unsqueeze(-1).float()
            mean = (model(**enc).last_hidden_state * mask).sum(1) / mask.sum(1)
            out.append(torch.nn.functional.normalize(mean, dim=-1).numpy())
    return np.concatenate(out) if out else np.zeros((0, 384), dtype=np.float32)


def memory_rows() -> list:
    """The classifier's memory: MEMORY_ROWS id_train rows drawn with SEED."""
    from models.datasets.language_sets import load_language_set
    return random.Random(SEED).sample(load_language_set("id_train"), MEMORY_ROWS)


class EmbeddingRoomType:
    """k-nearest-neighbour room type over embedded id_train instructions (rows: instruction, room_type)."""

    def __init__(self, rows=None):
        if rows is None:
            rows = memory_rows()
        self.rooms = [r.room_type for r in rows]
        self.memory = embed([r.instruction for r in rows])

    def predict(self, texts: list[str]) -> list[str]:
        import numpy as np
        sims = embed(texts) @ self.memory.T
        nearest = np.argsort(-sims, axis=1)[:, :K]
        return [Counter(self.rooms[j] for j in row).most_common(1)[0][0] for row in nearest]
