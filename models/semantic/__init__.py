"""Semantic scorers of a layout (the paper's SFF input): a feature vector h_vl and a realism score r_vlm.

The paper asks a frozen VLM (Qwen2-VL) about a rendered layout. No VLM runs here, so the default is
`LearnedScorer`, a logistic regression on eight arrangement statistics, trained on the 120 hand-built
iTHOR rooms (human layouts) against perturbed copies of them; `VLMScorer` sends a rendered top view to
any OpenAI-compatible chat endpoint (vLLM, Ollama, llama.cpp server) and reads the score it answers.
"""

from models.semantic.base import LayoutItem, SemanticScore, SemanticScorer, items_of
from models.semantic.learned import LearnedScorer, default_scorer

__all__ = ["LayoutItem", "LearnedScorer", "SemanticScore", "SemanticScorer", "default_scorer", "items_of"]
