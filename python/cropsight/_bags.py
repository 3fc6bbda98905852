"""cropsight.read_bag: a ROS bag as a Sequence, through a temporary sequence folder.

The library reads sequences from folders; a bag's frames are imported into a temporary one (as the
CLI's --data FILE.bag does), which is removed when the Sequence is garbage-collected or the
interpreter exits.
"""
import shutil
import tempfile
import weakref

from ._cropsight import _import_bag, read_sequence


def read_bag(path, depth_topic="/camera/depth/image_raw", info_topic="/camera/depth/camera_info",
             color_topic="/camera/color/image_raw"):
    """Reads a ROS bag's depth images, camera info and (when present) colour images as a
    cropsight.Sequence. Raises cropsight.Error naming the bag for a missing topic, inconsistent
    camera info, a wrong encoding or a truncated file; works without a ROS master."""
    root = tempfile.mkdtemp(prefix="cropsight-bag-")
    try:
        _import_bag(str(path), root + "/sequence", depth_topic, info_topic, color_topic)
        seq = read_sequence(root + "/sequence")
    except BaseException:
        shutil.rmtree(root, ignore_errors=True)
        raise
    weakref.finalize(seq, shutil.rmtree, root, True)
    return seq
