"""The bundled Hugging Face models are read from site-packages and the user cache, never from a hub: `offline()` says
so to huggingface_hub and transformers, and turns off their per-load progress bars ("Loading weights", a few
hundredths of a second on stderr of every `h3ds generate`). It must run before transformers is imported."""

from __future__ import annotations

import os

SETTINGS = {"HF_HUB_OFFLINE": "1", "TRANSFORMERS_OFFLINE": "1", "HF_HUB_DISABLE_PROGRESS_BARS": "1"}


def offline() -> None:
    """Set `SETTINGS` where the user has not set them otherwise."""
    for name, value in SETTINGS.items():
        os.environ.setdefault(name, value)
