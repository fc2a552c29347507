# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
# Type stubs of the comap package (its functions are documented in __init__.py).

from os import PathLike
from typing import Any, Callable, Dict, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, PathLike]
_Map = npt.NDArray[np.int64]
_Info = Dict[str, Any]
_SettingValue = Union[bool, float, str, Sequence[float], Sequence[Sequence[float]]]
_Progress = Callable[[str, float], Optional[bool]]

has_tbb: bool

class Stopped(RuntimeError): ...

def settings() -> Dict[str, Dict[str, str]]: ...
def check_settings(settings: Dict[str, _SettingValue]) -> None: ...
def read_settings(file: _Path) -> Dict[str, _SettingValue]: ...
def match(
    V1: npt.ArrayLike,
    F1: npt.ArrayLike,
    V2: npt.ArrayLike,
    F2: npt.ArrayLike,
    init: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = None,
    landmarks: Optional[npt.ArrayLike] = None,
    settings: Optional[Dict[str, _SettingValue]] = None,
    threads: Optional[int] = None,
    progress: Optional[_Progress] = None,
) -> Tuple[_Map, _Map, _Info]: ...

class Shape:
    V: npt.NDArray[np.float64]
    F: npt.NDArray[np.int64]
    name: str
    def __init__(
        self,
        V: npt.ArrayLike,
        F: npt.ArrayLike,
        name: str = "mesh",
        settings: Optional[Dict[str, _SettingValue]] = None,
        threads: Optional[int] = None,
    ) -> None: ...
    @property
    def number_of_vertices(self) -> int: ...
    @property
    def preparation_seconds(self) -> Dict[str, float]: ...

def match_shapes(
    shape_1: Shape,
    shape_2: Shape,
    init: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = None,
    landmarks: Optional[npt.ArrayLike] = None,
    settings: Optional[Dict[str, _SettingValue]] = None,
    threads: Optional[int] = None,
    progress: Optional[_Progress] = None,
) -> Tuple[_Map, _Map, _Info]: ...
def read_mesh(file: _Path) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...
def read_map(file: _Path, index_base: int = 1) -> _Map: ...
def write_map(file: _Path, map: npt.ArrayLike, index_base: int = 1) -> None: ...
def geodesic_errors(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    map: npt.ArrayLike,
    gt_source: npt.ArrayLike,
    gt_target: npt.ArrayLike,
    gt_target_symmetric: Optional[npt.ArrayLike] = None,
) -> npt.NDArray[np.float64]: ...
def cycle_errors(V1: npt.ArrayLike, F1: npt.ArrayLike, map_12: npt.ArrayLike, map_21: npt.ArrayLike) -> npt.NDArray[np.float64]: ...
def coverage(map: npt.ArrayLike, target_vertices: int) -> float: ...
def inconsistent_vertices(map_12: npt.ArrayLike, map_21: npt.ArrayLike) -> int: ...
