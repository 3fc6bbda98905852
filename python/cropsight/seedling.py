"""Broccoli seedlings from stereo pairs (SGM disparity, soil plane, GMM, envelope). help(Config)
lists the keys."""
from ._cropsight.seedling import Config, FrameResult, Pipeline, read_pair

__all__ = ["Config", "FrameResult", "Pipeline", "read_pair"]
