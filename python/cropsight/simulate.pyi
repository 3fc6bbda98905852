from os import PathLike
from typing import Any, Sequence, Union

def broccoli(out: Union[str, PathLike], *, variety: str = "uk", frames: int = 60, seed: int = 1,
             sets: Union[dict[str, Any], Sequence[str], None] = None, force: bool = False) -> dict[str, Any]: ...
