"""Semantic scorers: the learned default prefers human iTHOR layouts; the VLM client speaks the
OpenAI-compatible chat protocol to a real HTTP server on loopback."""

import json
import threading
from http.server import BaseHTTPRequestHandler, HTTPServer

import numpy as np
import pytest

from models.semantic import LayoutItem, default_scorer
from models.semantic.learned import HELD_OUT, ithor_layouts, perturb
from models.semantic.vlm import VLMError, VLMScorer


def test_learned_scorer_ranks_held_out_human_layouts_above_perturbed():
    rng = np.random.default_rng(5)
    scorer = default_scorer()
    wins, total = 0, 0
    for k, (room, w, d, items) in enumerate(ithor_layouts()):
        if k % HELD_OUT:
            continue
        human = scorer.score(room, w, d, items).score
        for _ in range(3):
            wins += human > scorer.score(room, w, d, perturb(rng, w, d, items)).score
            total += 1
    assert wins / total > 0.7


def test_empty_layout_gets_features_and_a_score():
    s = default_scorer().score("kitchen", 4, 4, [])
    assert s.features.shape == (default_scorer().dim,) and 0 <= s.score <= 1


class _Fake(BaseHTTPRequestHandler):
    requests: list = []
    answer = '{"score": 7, "reason": "fine"}'

    def do_POST(self):  # noqa: N802
        body = json.loads(self.rfile.read(int(self.headers["Content-Length"])))
        _Fake.requests.append((self.path, dict(self.headers), body))
        out = json.dumps({"choices": [{"message": {"role": "assistant", "content": _Fake.answer}}]}).encode()
        self.send_response(200)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(out)))
        self.end_headers()
        self.wfile.write(out)

    def log_message(self, *args):
        pass


@pytest.fixture
def server():
    srv = HTTPServer(("127.0.0.1", 0), _Fake)
    threading.Thread(target=srv.serve_forever, daemon=True).start()
    yield f"http://127.0.0.1:{srv.server_address[1]}/v1"
    srv.shutdown()


def test_vlm_scorer_sends_a_top_view_and_reads_the_score(server):
    items = [LayoutItem("Bed", 1.0, 1.2, 0.0, 1.6, 2.0), LayoutItem("Dresser", 3.0, 0.3, 0.0, 1.0, 0.5)]
    _Fake.requests.clear()
    _Fake.answer = '{"score": 7, "reason": "fine"}'
    s = VLMScorer(server, "qwen2-vl", api_key="k").score("bedroom", 4, 4, items)
    assert s.score == pytest.approx(0.7)
    path, headers, body = _Fake.requests[0]
    assert path == "/v1/chat/completions" and headers["Authorization"] == "Bearer k"
    content = body["messages"][0]["content"]
    assert body["model"] == "qwen2-vl"
    assert content[1]["image_url"]["url"].startswith("data:image/png;base64,iVBOR")  # a PNG


def test_vlm_scorer_names_an_unusable_answer(server):
    _Fake.answer = "I cannot judge this."
    with pytest.raises(VLMError, match="no score"):
        VLMScorer(server, "m").score("bedroom", 4, 4, [])
    with pytest.raises(VLMError, match="no usable answer"):
        VLMScorer("http://127.0.0.1:9/v1", "m", timeout_s=2).score("bedroom", 4, 4, [])
