"""The studio's side of the headset link (protocol: unity-bridge/protocol/)."""

from app.bridge.hub import Bridge, Progress, bridge_for
from app.bridge.routes import HEADSET_PATH, mount

__all__ = ["Bridge", "bridge_for", "HEADSET_PATH", "Progress", "mount"]
