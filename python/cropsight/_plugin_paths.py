"""Where the extension finds the libtorch plugin and the data folder (configs/, models/).

The CLI finds them beside its program (PREFIX/bin/cropsight: PREFIX/lib/libcropsight_nn_torch.so and
PREFIX/share/cropsight); the library reads $CROPSIGHT_NN_BACKEND and $CROPSIGHT_DATA_DIR first
(core/install_paths.hpp, nn/point_segmenter.cpp). Python's program is the interpreter, so the
package sets those two variables, when the user has not, to the same files of the prefix it was
built or installed in. _layout.py (written by CMake) says where that prefix is relative to the
package: the build tree and an install differ.
"""
import os

from . import _layout


def prefix() -> str:
    here = os.path.dirname(os.path.abspath(__file__))
    return os.path.normpath(os.path.join(here, _layout.PREFIX_FROM_PACKAGE))


def point_library_at_prefix() -> None:
    root = prefix()
    plugin = os.path.join(root, "lib", "libcropsight_nn_torch.so")
    data = os.path.join(root, "share", "cropsight")
    if not os.environ.get("CROPSIGHT_NN_BACKEND") and os.path.isfile(plugin):
        os.environ["CROPSIGHT_NN_BACKEND"] = plugin
    if not os.environ.get("CROPSIGHT_DATA_DIR") and os.path.isdir(data):
        os.environ["CROPSIGHT_DATA_DIR"] = data
