"""The OpenAI-compatible backend against a local server on loopback that speaks /v1/chat/completions
the way vLLM, Ollama and llama.cpp's server do (a stand-in for a served model: it answers from a table)."""

from __future__ import annotations

import json
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

import pytest

from models.language import InstructionError
from models.language.llm.openai_backend import OpenAIParser

ANSWERS = {
    "Put a chilled bread on the counter": "cool | whole | Bread | CounterTop",
    "Throw the sliced apple away": "Sure! place | sliced | apple | garbage can",  # chatty, loose spelling
    "Read the book by the lamp": "look | whole | Book | Desk Lamp",
    "Put the mug in the sink": "place | whole | Mug | Countertopp",  # misspelt
    "Put the spoon in the drawer": "place | whole | Spaceship | Drawer",  # not a type
    "Say something": "I am not sure what you mean.",
}


class FakeChatServer(BaseHTTPRequestHandler):
    requests: list[dict] = []

    def log_message(self, *args):  # keep pytest output clean
        pass

    def do_POST(self):
        body = json.loads(self.rfile.read(int(self.headers["Content-Length"])))
        FakeChatServer.requests.append({"path": self.path, "auth": self.headers.get("Authorization"), **body})
        if self.path != "/v1/chat/completions":
            self.send_response(404)
            self.end_headers()
            self.wfile.write(b'{"error": "not found"}')
            return
        user = body["messages"][-1]["content"]
        instruction = user.split("\n")[0].removeprefix("Instruction: ")
        content = ANSWERS.get(instruction, "")
        reply = {"id": "chatcmpl-1", "object": "chat.completion", "model": body["model"],
                 "choices": [{"index": 0, "finish_reason": "stop",
                              "message": {"role": "assistant", "content": content}}],
                 "usage": {"prompt_tokens": 10, "completion_tokens": 8, "total_tokens": 18}}
        data = json.dumps(reply).encode()
        self.send_response(200)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(data)))
        self.end_headers()
        self.wfile.write(data)


@pytest.fixture(scope="module")
def server():
    httpd = ThreadingHTTPServer(("127.0.0.1", 0), FakeChatServer)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}/v1"
    httpd.shutdown()


def test_request_follows_the_chat_completions_protocol(server):
    FakeChatServer.requests.clear()
    parser = OpenAIParser(base_url=server, model="falcon-7b-lora", api_key="secret")
    graph = parser.parse("Put a chilled bread on the counter", "kitchen")
    sent = FakeChatServer.requests[-1]
    assert sent["path"] == "/v1/chat/completions" and sent["model"] == "falcon-7b-lora"
    assert sent["auth"] == "Bearer secret" and sent["temperature"] == 0.0
    assert [m["role"] for m in sent["messages"]][:2] == ["system", "user"]
    assert sent["messages"][-1]["content"].startswith("Instruction: Put a chilled bread on the counter")
    assert graph.task_type == "pick_cool_then_place_in_recep" and graph.provenance.method == "openai"
    assert set(map(tuple, graph.relations)) == {("Bread", "cooled_in", "Fridge"), ("Bread", "placed_at", "CounterTop")}
    roles = {o.type: o.roles for o in graph.objects}
    assert roles["Fridge"] == ["inference"] and roles["CounterTop"] == ["key", "anchor"]


def test_loose_answers_are_snapped_to_catalogue_types(server):
    parser = OpenAIParser(base_url=server)
    graph = parser.parse("Throw the sliced apple away", "kitchen")
    assert ("Apple", "placed_at", "GarbageCan") in graph.relations and graph.sliced
    assert parser.parse("Read the book by the lamp", "bedroom").anchor.type == "DeskLamp"
    assert parser.parse("Put the mug in the sink", "kitchen").anchor.type == "CounterTop"


@pytest.mark.parametrize("instruction, problem", [
    ("Put the spoon in the drawer", "'Spaceship' is not an AI2-THOR type"),
    ("Say something", "could not be read"),
])
def test_unreadable_answers_are_clear_errors_never_invented_types(server, instruction, problem):
    with pytest.raises(InstructionError, match=problem):
        OpenAIParser(base_url=server).parse(instruction, "kitchen")


def test_unreachable_or_wrong_endpoint_is_a_clear_error(server):
    with pytest.raises(InstructionError, match="answered HTTP 404"):
        OpenAIParser(base_url=server.removesuffix("/v1") + "/nope").parse("Put the mug in the sink")
    with pytest.raises(InstructionError, match="cannot reach the chat endpoint"):
        OpenAIParser(base_url="http://127.0.0.1:9/v1", timeout=2).parse("Put the mug in the sink")
