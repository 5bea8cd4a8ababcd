"""The constraint datasets that placers are trained and compared on (paper: LLaMA seen, Qwen and Mistral unseen)."""

from models.datasets.constraint_sets import ALL_SETS, DATASETS, PlanRecord, build_dataset, load_dataset

__all__ = ["ALL_SETS", "DATASETS", "PlanRecord", "build_dataset", "load_dataset"]
