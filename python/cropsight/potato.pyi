from os import PathLike
from typing import Any, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import Box as Box, Camera, Frame
from ._config import ConfigMapping

class Config(ConfigMapping): ...

class HarvestTarget:
    frame: int
    timestamp: float
    detection: bool
    depth_ok: bool
    x: float
    y: float
    z: float
    height: float
    width: float
    angle: float
    angle_ok: bool
    cut: bool
    target_id: int
    score: float
    @property
    def state(self) -> str: ...
    @property
    def box(self) -> Optional[tuple[float, float, float, float]]: ...

class FrameResult:
    target: HarvestTarget
    detections: list[Box]
    @property
    def positions(self) -> list[npt.NDArray[np.float64]]: ...
    @property
    def ripe(self) -> list[bool]: ...
    @property
    def stage_ms(self) -> dict[str, float]: ...

class Pipeline:
    def __init__(self, *, config: str = "", sets: Union[dict[str, Any], Sequence[str], None] = None,
                 model: str = "") -> None: ...
    def process(self, frame: Optional[Frame] = None, *, depth: Optional[npt.NDArray[np.uint16]] = None,
                color: Optional[npt.NDArray[np.uint8]] = None, camera: Optional[Camera] = None) -> FrameResult: ...
    def reset(self) -> None: ...
    def evaluate(self, sequence: Union[str, PathLike], *, min_iou: float = 0.3) -> dict[str, Any]: ...
    @property
    def config(self) -> Config: ...
