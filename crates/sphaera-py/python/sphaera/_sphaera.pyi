"""Type stubs of the native module `sphaera._sphaera` (re-exported by `sphaera`)."""

import os
from typing import Any, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

Length = Union[float, str]
"""An absolute length (``0.01``) or a percentage of the bounding-box diagonal (``"1%"``)."""

Point = Tuple[float, float, float]

__version__: str

class Mesh:
    """A triangle mesh: ``vertices`` ``(n, 3)`` float64 and ``faces`` ``(m, 3)`` indices."""

    def __init__(self, vertices: npt.ArrayLike, faces: npt.ArrayLike) -> None: ...
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...
    @property
    def faces(self) -> npt.NDArray[np.uint32]: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def diagonal(self) -> float: ...
    def bounding_box(self) -> Tuple[Point, Point]: ...
    def info(self) -> dict[str, Any]: ...
    def save(self, path: Union[str, os.PathLike[str]]) -> None: ...
    def to_dict(self) -> dict[str, Any]: ...
    def __eq__(self, other: object) -> bool: ...

class Simplified:
    """A simplified mesh and its certified error bound (both ways)."""

    mesh: Mesh
    error_bound: float
    collapses: int
    def __init__(self, mesh: Mesh, error_bound: float, collapses: int) -> None: ...
    def to_dict(self) -> dict[str, Any]: ...

class Distances:
    """Per query point a certified interval ``lower <= d <= upper`` and the nearest point."""

    lower: npt.NDArray[np.float64]
    upper: npt.NDArray[np.float64]
    closest: npt.NDArray[np.float64]
    triangle: npt.NDArray[np.uint32]
    tolerance: Optional[float]
    @property
    def distance(self) -> npt.NDArray[np.float64]: ...
    def __init__(
        self,
        lower: npt.NDArray[np.float64],
        upper: npt.NDArray[np.float64],
        closest: npt.NDArray[np.float64],
        triangle: npt.NDArray[np.uint32],
        tolerance: Optional[float],
    ) -> None: ...
    def __len__(self) -> int: ...
    def to_dict(self) -> dict[str, Any]: ...

class Hausdorff:
    """A certified Hausdorff distance: ``lower <= H <= upper``."""

    lower: float
    upper: float
    farthest: Point
    closest: Point
    dominating: str
    a_to_b: Tuple[float, float]
    b_to_a: Optional[Tuple[float, float]]
    converged: bool
    def __init__(
        self,
        lower: float,
        upper: float,
        farthest: Point,
        closest: Point,
        dominating: str,
        a_to_b: Tuple[float, float],
        b_to_a: Optional[Tuple[float, float]],
        converged: bool,
    ) -> None: ...
    def to_dict(self) -> dict[str, Any]: ...

class SphereTree:
    """Per level the spheres ``(n, 4)``, their parents and the certified worst error."""

    levels: list[npt.NDArray[np.float64]]
    parents: list[npt.NDArray[np.int64]]
    errors: list[Optional[Tuple[float, float]]]
    method: str
    branch: int
    @property
    def depth(self) -> int: ...
    def __init__(
        self,
        levels: Sequence[npt.NDArray[np.float64]],
        parents: Sequence[npt.NDArray[np.int64]],
        errors: Sequence[Optional[Tuple[float, float]]],
        method: str,
        branch: int,
    ) -> None: ...
    def __len__(self) -> int: ...
    def to_dict(self) -> dict[str, Any]: ...

def load(path: Union[str, os.PathLike[str]]) -> Mesh: ...
def simplify(
    mesh: Mesh, ratio: Optional[float] = None, max_error: Optional[Length] = None
) -> Simplified: ...
def distance(
    mesh: Mesh, points: npt.ArrayLike, tolerance: Optional[Length] = None
) -> Distances: ...
def hausdorff(
    a: Mesh,
    b: Mesh,
    tolerance: Optional[Length] = None,
    symmetric: bool = True,
    max_samples: Optional[int] = None,
) -> Hausdorff: ...
def spheretree(
    mesh: Mesh,
    depth: int = 3,
    branch: int = 8,
    method: str = "auto",
    samples: Optional[int] = None,
    seed: Optional[int] = None,
    evaluate: bool = True,
) -> SphereTree: ...
def hal(
    mesh: Mesh, tolerance: Optional[Length] = None, level: int = 0
) -> Tuple[Mesh, int]: ...
def silhouette_labels(
    mesh: Mesh, step_degrees: float = 30.0, resolution: int = 128, outline_only: bool = True
) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.float64]]: ...
def urdf(
    path: Union[str, os.PathLike[str]],
    spheres_per_link: Optional[int] = None,
    budget: Optional[int] = None,
    tolerance: Optional[Length] = None,
    per_link: Optional[dict[str, int]] = None,
    visual: bool = False,
    packages: Optional[dict[str, Union[str, os.PathLike[str]]]] = None,
) -> dict[str, Any]: ...
