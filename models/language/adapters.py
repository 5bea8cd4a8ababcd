"""Making LoRA models with peft (the language model's adapters, the role classifier's): quietly, where peft
itself is the one using a deprecated transformers name."""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def quiet_peft() -> Iterator[None]:
    """Around the making of a peft model: peft asks transformers 5.x whether gradient checkpointing is on under
    a deprecated name, and the FutureWarning is nothing a user can act on."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*is_gradient_checkpointing.*", category=FutureWarning)
        yield
