"""`h3ds studio`: the viser studio on one port and the HTTP API on the next, over one store."""

from __future__ import annotations

import socket
import threading

import uvicorn
import viser

from app.api import create_app
from app.pipeline import Pipeline
from frontend.session import StudioSession
from studio_db import Store


class Studio:
    """A running studio: every browser tab that connects gets its own StudioSession."""

    def __init__(self, host: str = "127.0.0.1", port: int = 8080, store: Store | None = None,
                 pipeline: Pipeline | None = None):
        self.store = store or Store()
        self.pipeline = pipeline or Pipeline()
        self.server = viser.ViserServer(host=host, port=port, label="H3DS Studio", verbose=False)
        self.sessions: dict[int, StudioSession] = {}
        self.server.on_client_connect(self._connect)
        self.server.on_client_disconnect(self._disconnect)

    def _connect(self, client: viser.ClientHandle) -> None:
        self.sessions[client.client_id] = StudioSession(client, self.pipeline, self.store)

    def _disconnect(self, client: viser.ClientHandle) -> None:
        session = self.sessions.pop(client.client_id, None)
        if session is not None:
            session.close()

    @property
    def port(self) -> int:
        return self.server.get_port()

    def stop(self) -> None:
        self.server.stop()


def free_port(host: str, start: int, tries: int = 50) -> int:
    """The first port from `start` on that can be bound (as viser does for the studio's port)."""
    for port in range(start, start + tries):
        with socket.socket() as s:
            try:
                s.bind((host, port))
                return port
            except OSError:
                continue
    raise OSError(f"no free port in {start}-{start + tries - 1} on {host}")


def serve_api(store: Store, pipeline: Pipeline, host: str, port: int) -> tuple[uvicorn.Server, int]:
    """Start the HTTP API in a background thread on `port` or the next free one; returns (server, port)."""
    from app.bridge import HEADSET_PATH, bridge_for
    from app.bridge.protocol import MAX_FRAME_BYTES

    port = free_port(host, port)
    server = uvicorn.Server(uvicorn.Config(create_app(store, pipeline), host=host, port=port, log_level="warning",
                                           ws_max_size=MAX_FRAME_BYTES))
    bridge_for(store).address = f"ws://{host}:{port}{HEADSET_PATH}"
    threading.Thread(target=server.run, daemon=True).start()
    return server, port
