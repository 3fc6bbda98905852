"""Grape bunches: the point segmenter (PointResNet / GBDT ensembles) on N×9 clouds, and the
dataset's cloud reader. help(Config) lists the keys."""
from ._cropsight.grape import Config, Pipeline, read_cloud

__all__ = ["Config", "Pipeline", "read_cloud"]
