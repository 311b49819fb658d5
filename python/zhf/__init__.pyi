# Type stubs for zhf: shapes in the comments, N the SH order (N*N coefficients).
from os import PathLike
from typing import Literal, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

QuaternionOrder = Literal["wxyz", "xyzw"]
conventions: list[str]

def isa() -> str: ...  # the instruction-set path rotations take ("sse2", "avx2", "avx512", "neon")
def isas() -> list[str]: ...  # the paths this CPU runs, fastest first
def use_isa(name: str) -> None: ...  # forces one of isas() for the rotations that follow
def kernels(order: int, dtype: npt.DTypeLike = ...) -> str: ...  # "scalar", "lanes", "band_rows", "bands01" or "zxzxz"

class LobeTable:
    order: int
    lobe_sharing: bool
    zeros: int
    entries: int
    directions: npt.NDArray[np.float64]  # (lobes, 3) unit vectors
    bands: list[dict]  # per band l >= 2: l, lobes, inverse (2l+1, 2l+1), zeros, condition
    worst_condition: float
    command: str

def order_of(coeffs: npt.ArrayLike) -> int: ...
def matrix_from_quaternion(quaternions: npt.ArrayLike, order: QuaternionOrder) -> npt.NDArray[np.float64]:
    """(..., 4) -> (..., 3, 3)"""
def rotate(
    coeffs: npt.ArrayLike,  # (..., N*N)
    rotation: npt.ArrayLike,  # (3, 3), (4,), (..., 3, 3) or (..., 4)
    *,
    quaternion_order: Optional[QuaternionOrder] = ...,
    convention: str = ...,
    table: Optional[LobeTable] = ...,
    threads: int = ...,
    out: Optional[np.ndarray] = ...,
) -> np.ndarray:  # the broadcast shape (..., N*N), float32 or float64 (out, when given)
    ...
def band_matrices(
    rotation: npt.ArrayLike,  # (3, 3) or (4,)
    order: int,
    *,
    quaternion_order: Optional[QuaternionOrder] = ...,
    convention: str = ...,
    table: Optional[LobeTable] = ...,
) -> list[npt.NDArray[np.float64]]:  # D_l: (2l+1, 2l+1), l = 0..order-1
    ...
def convert(coeffs: npt.ArrayLike, source: str, target: str = ..., *, threads: int = ...) -> np.ndarray:
    """(..., N*N) -> (..., N*N)"""
def analyze(coeffs: npt.ArrayLike, tolerance: float = ...) -> dict: ...
def read_lobe_table(path: Union[str, PathLike], order: int = ...) -> LobeTable: ...
def write_lobe_table(table: LobeTable, path: Union[str, PathLike]) -> None: ...
