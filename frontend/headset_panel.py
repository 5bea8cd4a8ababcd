"""The studio's Headset tab: the pairing token, paired headsets, "Send to headset" with the push's progress
(delivered, loaded, robot step n of m), and the live glove feedback (a stream and per-object counts).

`FeedbackView` holds what the feedback panel shows and is pure, so the bridge benchmark times events all
the way into it; `HeadsetPanel` renders it into viser at most every RENDER_S seconds.
"""

from __future__ import annotations

import threading
import time
import weakref
from collections import Counter, deque

from app.bridge import Progress, bridge_for

RENDER_S = 0.25  # the panel redraws at most this often (viser messages are not free)
STREAM_LINES = 12


class FeedbackView:
    """The feedback panel's content: the newest events and counts per object and kind."""

    def __init__(self, keep: int = STREAM_LINES):
        self.stream: deque[str] = deque(maxlen=keep)
        self.counts: Counter[tuple[str, str]] = Counter()
        self.total = 0
        self.version = 0  # bumps on every change, so a renderer knows when to redraw

    def add(self, messages: list[dict]) -> None:
        for m in messages:
            b = m["body"]
            self.counts[(b["object_id"], b["kind"])] += 1
            fingers = "+".join(b["fingers"]) or "-"
            self.stream.appendleft(f"`{b['t']:7.2f}s` {b['hand']} {fingers} **{b['kind']}** {b['object_type']} "
                                   f"({b['haptic_class']}, {b['intensity']})")
        self.total += len(messages)
        self.version += 1

    def markdown(self) -> str:
        if not self.total:
            return "No glove feedback yet."
        objects = sorted({o for o, _ in self.counts}, key=lambda o: -sum(self.counts[(o, k)] for k in KINDS))
        rows = "\n".join(f"| {o} | " + " | ".join(str(self.counts[(o, k)]) for k in KINDS) + " |" for o in objects)
        return (f"**{self.total} glove events stored**\n\n| object | " + " | ".join(KINDS) + " |\n|---|"
                + "---|" * len(KINDS) + f"\n{rows}\n\nNewest first:\n\n" + "  \n".join(self.stream))


KINDS = ("hover", "select", "unselect", "unhover")


class HeadsetPanel:
    def __init__(self, session, gui):
        self.session = session
        self.bridge = bridge_for(session.store)
        self.view = FeedbackView()
        self.pairing = gui.add_markdown("")
        self.headset = gui.add_dropdown("Paired headset", ("-",))
        gui.add_button("Send to headset", color="blue",
                       hint="Pushes the version selected in the Scenes tab").on_click(lambda _: self.send())
        gui.add_button("New pairing token").on_click(lambda _: (self.bridge.new_token(), self._render_pairing()))
        self.progress = gui.add_markdown("Nothing sent yet.")
        self.feedback = gui.add_markdown(self.view.markdown())
        self._push: str | None = None
        self._drawn = -1
        self._lock = threading.Lock()
        me = weakref.ref(self)

        def listener(kind: str, payload: object) -> None:
            panel = me()
            if panel is None:
                unsubscribe()
            else:
                panel._on(kind, payload)

        unsubscribe = self.bridge.subscribe(listener)
        self.unsubscribe = unsubscribe
        threading.Thread(target=_render_loop, args=(me,), daemon=True).start()
        self._render_pairing()

    def _on(self, kind: str, payload: object) -> None:
        with self._lock:
            if kind == "feedback":
                self.view.add(payload)
            elif kind == "progress" and isinstance(payload, Progress) and payload.push == self._push:
                self.progress.content = self._progress_text(payload)
            elif kind == "headsets":
                self._render_pairing()

    def _progress_text(self, p: Progress) -> str:
        return f"Scene {p.scene_id} v{p.version} → {p.session[:8]}: {p.text()}"

    def _render_pairing(self) -> None:
        where = self.bridge.address or "(the API server is not running)"
        self.pairing.content = (f"Pairing token **{self.bridge.token}** (expires in "
                                f"{int(self.bridge.token_expires_in() // 60) + 1} min)  \nHeadset address: `{where}`")
        options = tuple(f"{h.headset_id} · {h.device[:40]} · {'connected' if h.connected else 'offline'} · "
                        f"{h.session}" for h in self.bridge.paired())
        self.headset.options = options or ("-",)

    def closed(self) -> bool:
        """The browser tab is gone (viser's buffer for it is done; there is no public flag)."""
        try:
            return self.session.client._websock_connection.get_message_buffer().done
        except AttributeError:
            return False

    def render(self) -> None:
        with self._lock:
            if self.view.version != self._drawn:
                self._drawn = self.view.version
                self.feedback.content = self.view.markdown()

    def send(self) -> None:
        session = self.headset.value.rsplit(" · ", 1)[-1] if self.headset.value != "-" else None
        sid, number = self.session.scenes.selected()
        if session is None:
            self.progress.content = "**Error:** no paired headset; enter the pairing token on the headset first."
            return
        if sid is None or number is None:
            self.progress.content = "**Error:** select a stored scene and version in the Scenes tab first."
            return
        self.progress.content = f"Sending scene {sid} v{number}…"
        try:
            progress = self.bridge.push(session, sid, number)
        except Exception as e:  # noqa: BLE001 - shown to the designer as is
            self.progress.content = f"**Error:** {e}"
            return
        self._push = progress.push
        self.progress.content = self._progress_text(progress)


def _render_loop(ref: "weakref.ref[HeadsetPanel]") -> None:
    ticks = 0
    while (panel := ref()) is not None:
        if panel.closed():
            panel.unsubscribe()
            return
        try:
            panel.render()
            ticks += 1
            if ticks % int(5 / RENDER_S) == 0:
                panel._render_pairing()  # the token's countdown and a rotated token
        except Exception:  # the browser tab went away
            return
        del panel
        time.sleep(RENDER_S)
