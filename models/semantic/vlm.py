"""A VLM judge over HTTP: the layout is drawn as a top view (PNG) and sent to an OpenAI-compatible chat
endpoint (`POST {base_url}/chat/completions`, as vLLM, Ollama and llama.cpp's server speak it, e.g.
Qwen2-VL under vLLM), which answers a realism score 0-10. The endpoint returns no hidden state, so h_vl is
the learned scorer's arrangement statistics and only r_vlm comes from the VLM.
"""

from __future__ import annotations

import base64
import io
import json
import re
import urllib.request

from models.semantic.base import LayoutItem, SemanticScore, _boxes
from models.semantic.learned import default_scorer

PROMPT = ("This is a top view of a {room} ({w:.1f} m x {d:.1f} m) with its furniture drawn as labelled boxes; "
          "a tick marks each object's front. How realistic and usable is this arrangement for a person? "
          'Answer with JSON only: {{"score": <0-10>, "reason": "<one sentence>"}}')


class VLMError(RuntimeError):
    pass


def top_view_png(room_type: str, width: float, depth: float, items: list[LayoutItem]) -> bytes:
    import numpy as np
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Rectangle

    fig = Figure(figsize=(4, 4 * depth / max(width, 1e-6)))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    ax.add_patch(Rectangle((0, 0), width, depth, fill=False))
    for it, b in zip(items, _boxes(items)):
        ax.add_patch(Rectangle((b[0], b[1]), b[2] - b[0], b[3] - b[1], alpha=0.4))
        r = np.radians(it.rotation)
        ax.plot([it.x, it.x + 0.3 * np.sin(r)], [it.z, it.z + 0.3 * np.cos(r)], "k-")
        ax.text(it.x, it.z, it.type, fontsize=6, ha="center")
    ax.set_xlim(-0.1, width + 0.1)
    ax.set_ylim(-0.1, depth + 0.1)
    ax.set_aspect("equal")
    ax.set_title(room_type)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=60)
    return buf.getvalue()


class VLMScorer:
    """Scores a layout by asking a VLM served over an OpenAI-compatible chat API."""

    def __init__(self, base_url: str, model: str, api_key: str | None = None, timeout_s: float = 30.0):
        self.url = base_url.rstrip("/") + "/chat/completions"
        self.model, self.api_key, self.timeout_s = model, api_key, timeout_s
        self.dim = default_scorer().dim

    def request_body(self, room_type: str, width: float, depth: float, items: list[LayoutItem]) -> dict:
        image = base64.b64encode(top_view_png(room_type, width, depth, items)).decode()
        return {"model": self.model, "temperature": 0, "max_tokens": 128, "messages": [{"role": "user", "content": [
            {"type": "text", "text": PROMPT.format(room=room_type, w=width, d=depth)},
            {"type": "image_url", "image_url": {"url": f"data:image/png;base64,{image}"}}]}]}

    def score(self, room_type: str, width: float, depth: float, items: list[LayoutItem]) -> SemanticScore:
        body = json.dumps(self.request_body(room_type, width, depth, items)).encode()
        headers = {"Content-Type": "application/json"} | (
            {"Authorization": f"Bearer {self.api_key}"} if self.api_key else {})
        req = urllib.request.Request(self.url, data=body, headers=headers, method="POST")
        try:
            with urllib.request.urlopen(req, timeout=self.timeout_s) as resp:
                answer = json.loads(resp.read())["choices"][0]["message"]["content"]
        except (OSError, KeyError, IndexError, ValueError) as exc:
            raise VLMError(f"VLM endpoint {self.url} gave no usable answer: {exc}") from exc
        match = re.search(r'"score"\s*:\s*(-?[0-9.]+)', answer) or re.search(r"(-?[0-9]+(?:\.[0-9]+)?)", answer)
        if not match:
            raise VLMError(f"VLM answer has no score: {answer[:200]!r}")
        r = min(max(float(match.group(1)) / 10, 0.0), 1.0)
        features = default_scorer().score(room_type, width, depth, items).features
        return SemanticScore(features, r)
