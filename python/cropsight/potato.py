"""Potatoes on an aeroponic rig: per RGB-D frame the harvest target message (detection, 3D
position, size, orientation) and the boxes that led to it. help(Config) lists the keys."""
from ._cropsight import Box
from ._cropsight.potato import Config, FrameResult, HarvestTarget, Pipeline

__all__ = ["Box", "Config", "FrameResult", "HarvestTarget", "Pipeline"]
