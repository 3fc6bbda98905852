"""cropsight: 3D crop perception (broccoli heads, potatoes, grape bunches, broccoli seedlings).

A thin front-end over the C++ library: every pipeline is built by the library's make_pipeline from a
model, a preset and sets, exactly as the CLI builds it, so that the same data gives the same
results. numpy arrays in and out; the GIL is released while a pipeline runs. docs/python.md.

    import cropsight as cs
    seq = cs.read_sequence("SEQ")            # or cs.read_bag("FILE.bag")
    pipe = cs.broccoli.Pipeline(model="broccoli-oes-general", sets={"tracking.use_poses": True})
    for frame in seq:
        result = pipe.process(frame)
    heads = pipe.field_map()
"""
from . import _plugin_paths

_plugin_paths.point_library_at_prefix()

from ._cropsight import (Box, Camera, Detection, Detector, Error, Frame, Sequence, read_image,  # noqa: E402
                         read_sequence)
from ._bags import read_bag  # noqa: E402
from . import broccoli, grape, potato, seedling, simulate  # noqa: E402


def _frames(self):
    """The frames in order, each read when reached (Python's index protocol, stated for editors)."""
    for i in range(len(self)):
        yield self[i]


Sequence.__iter__ = _frames

__all__ = ["Box", "Camera", "Detection", "Detector", "Error", "Frame", "Sequence", "read_bag", "read_image", "read_sequence",
           "broccoli", "grape", "potato", "seedling", "simulate"]
