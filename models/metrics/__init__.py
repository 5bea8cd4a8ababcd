"""The paper's placement metrics, computed on a plan and its layout."""

from models.metrics.placement import SceneMetrics, scene_metrics, task_targets

__all__ = ["SceneMetrics", "scene_metrics", "task_targets"]
