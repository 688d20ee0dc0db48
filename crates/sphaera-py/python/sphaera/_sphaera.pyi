"""Type stubs of the native module `sphaera._sphaera` (re-exported by `sphaera`)."""

import os
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union

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
    """A sphere-tree: per level the spheres ``(n, 4)``, their parents and certified errors,
    and the certified worst error of each level's cut.

    A tree built to a depth has every level cover the surface. A tree built to a
    tolerance divides only the nodes above it, so its leaves end at different depths:
    ``cut(level)`` (the level's spheres and the leaves above it) is what covers the
    surface at that detail, and ``errors[level]`` is that cut's.
    """

    levels: list[npt.NDArray[np.float64]]
    """Per level, an ``(n, 4)`` array: ``x, y, z, r``."""
    parents: list[npt.NDArray[np.int64]]
    """Per level, each sphere's parent's row in the level above (``-1`` at the root)."""
    errors: list[Optional[Tuple[float, float]]]
    """Per level, ``(lower, upper)`` of the worst error of ``cut(level)`` (how far a sphere
    reaches beyond the surface), certified; ``None`` when not evaluated."""
    method: str
    branch: int
    node_errors: Optional[list[npt.NDArray[np.float64]]]
    """Per level, each sphere's certified error (an upper bound)."""
    surface: Literal["solid", "shell"]
    """``"shell"`` for a mesh without inside (a flat sheet, an open patch)."""
    goal: Literal["depth", "tolerance", "spheres"]
    tolerance: Optional[float]
    """The tolerance asked for, absolute (in the mesh's units)."""
    met: Optional[bool]
    """Whether every leaf's certified error is within ``tolerance`` (``None`` without)."""
    effort: Literal["quick", "default", "thorough"]
    @property
    def depth(self) -> int:
        """The number of levels, the root's included."""
    @property
    def leaves(self) -> npt.NDArray[np.float64]:
        """The spheres without children, ``(n, 4)``, level by level: they cover the surface."""
    @property
    def leaf_errors(self) -> npt.NDArray[np.float64]:
        """Each leaf's certified error (an upper bound), in the order of ``leaves``."""
    def cut(self, level: int) -> npt.NDArray[np.float64]:
        """The spheres covering the surface at ``level``: its spheres and the leaves above."""
    def cut_errors(self, level: int) -> npt.NDArray[np.float64]:
        """Each sphere of ``cut(level)``'s certified error (an upper bound)."""
    def __init__(
        self,
        levels: Sequence[npt.NDArray[np.float64]],
        parents: Sequence[npt.NDArray[np.int64]],
        errors: Sequence[Optional[Tuple[float, float]]],
        method: str,
        branch: int,
        node_errors: Optional[Sequence[npt.NDArray[np.float64]]] = None,
        surface: str = "solid",
        goal: str = "depth",
        tolerance: Optional[float] = None,
        met: Optional[bool] = None,
        effort: str = "default",
    ) -> None: ...
    def __len__(self) -> int: ...
    def to_dict(self) -> dict[str, Any]: ...

class ToleranceUnreachableError(ValueError):
    """A sphere-tree cannot meet the tolerance asked for within the library's limits."""

    tolerance: float
    """The tolerance asked for (in the mesh's units)."""
    worst: float
    """The worst certified leaf error reached."""
    spheres: int
    """Spheres built when the construction stopped."""
    levels: int
    """Levels built."""

def load(
    path: Union[str, os.PathLike[str]],
    root: Optional[Union[str, os.PathLike[str]]] = None,
    max_bytes: Optional[int] = None,
) -> Mesh: ...
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
    depth: Optional[int] = None,
    branch: Optional[int] = None,
    method: str = "auto",
    samples: Optional[int] = None,
    seed: Optional[int] = None,
    evaluate: bool = True,
    *,
    tolerance: Optional[Length] = None,
    spheres: Optional[int] = None,
    effort: Literal["quick", "default", "thorough"] = "default",
    max_nodes: Optional[int] = None,
) -> SphereTree:
    """A sphere-tree of ``mesh``: to ``depth`` (default 3) with ``branch`` (default 8)
    children per node, or to a ``tolerance`` (every leaf within it, in at most
    ``max_nodes`` nodes), or ``spheres=N`` (exactly N in one level)."""
def hal(
    mesh: Mesh, tolerance: Optional[Length] = None, level: int = 0
) -> Tuple[Mesh, int]: ...

class HalTree2:
    """A 2D HAL tree over ``points`` ``(n, 2)``: a closed outline (``closed=True``) or an
    open polyline. ``contains`` answers exactly, ``int8``: 1 inside, 0 on the boundary,
    -1 outside; the GIL is released."""

    def __init__(self, points: npt.ArrayLike, closed: bool = True) -> None: ...
    @property
    def closed(self) -> bool: ...
    @property
    def depth(self) -> int: ...
    def points(self) -> npt.NDArray[np.float64]: ...
    def contains(self, points: npt.ArrayLike) -> npt.NDArray[np.int8]: ...
    def intersects(self, other: HalTree2) -> bool: ...
    def intersecting_edges(self, other: HalTree2) -> npt.NDArray[np.int64]: ...
    def nearest_edge(
        self, points: npt.ArrayLike
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], npt.NDArray[np.float64]]: ...
    def __len__(self) -> int: ...

class HalMultiPolygon2:
    """HAL trees over every ring of polygons with holes (a country with its islands):
    ``polygons`` is a list of polygons, each a list of ``(n, 2)`` rings, the exterior
    first (GeoJSON's layout). ``contains`` answers ``int8`` (1 inside, 0 on a ring, -1
    outside), ``locate`` adds the ring holding each point, ``nearest_edge`` the nearest
    edge and its distance; the GIL is released. Rings of fewer than three distinct
    points are dropped and listed in ``dropped_rings``."""

    def __init__(self, polygons: Sequence[Sequence[npt.ArrayLike]]) -> None: ...
    @staticmethod
    def from_geojson(text: str) -> HalMultiPolygon2: ...
    @staticmethod
    def from_wkt(text: str) -> HalMultiPolygon2: ...
    @property
    def polygon_count(self) -> int: ...
    @property
    def dropped_rings(self) -> List[Tuple[int, int]]: ...
    def polygons(self) -> List[List[npt.NDArray[np.float64]]]: ...
    def contains(self, points: npt.ArrayLike) -> npt.NDArray[np.int8]: ...
    def locate(self, points: npt.ArrayLike) -> Dict[str, npt.NDArray[Any]]: ...
    def nearest_edge(self, points: npt.ArrayLike) -> Dict[str, npt.NDArray[Any]]: ...
    def intersects(self, other: Union[HalMultiPolygon2, HalTree2]) -> bool: ...
    def intersecting_edges(
        self, other: Union[HalMultiPolygon2, HalTree2]
    ) -> npt.NDArray[np.int64]: ...
    def __len__(self) -> int: ...

class HalTree3:
    """A 3D HAL tree over a closed, manifold, genus-0 ``mesh``. ``contains`` answers
    exactly, ``int8``: 1 inside, 0 on the surface, -1 outside; the GIL is released."""

    def __init__(self, mesh: Mesh) -> None: ...
    @property
    def mesh(self) -> Mesh: ...
    @property
    def depth(self) -> int: ...
    def contains(self, points: npt.ArrayLike) -> npt.NDArray[np.int8]: ...
    def intersects(self, other: HalTree3) -> bool: ...
    def intersecting_faces(self, other: HalTree3) -> npt.NDArray[np.int64]: ...
    def nearest_face(
        self, points: npt.ArrayLike
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], npt.NDArray[np.float64]]: ...
def silhouette_labels(
    mesh: Mesh,
    step_degrees: float = 30.0,
    resolution: int = 128,
    outline_only: bool = True,
    labels_file: Optional[Union[str, os.PathLike[str]]] = None,
    root: Optional[Union[str, os.PathLike[str]]] = None,
    max_bytes: Optional[int] = None,
) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.float64]]: ...
def urdf(
    path: Union[str, os.PathLike[str]],
    spheres_per_link: Optional[int] = None,
    budget: Optional[int] = None,
    tolerance: Optional[Length] = None,
    per_link: Optional[dict[str, int]] = None,
    visual: bool = False,
    packages: Optional[dict[str, Union[str, os.PathLike[str]]]] = None,
    root: Optional[Union[str, os.PathLike[str]]] = None,
    max_file_bytes: Optional[int] = None,
    self_collision_samples: int = 10_000,
    seed: int = 0,
    format: Optional[str] = None,
    mjcf_meshes: bool = False,
) -> dict[str, Any]: ...
def link_poses(
    path: Union[str, os.PathLike[str]],
    joints: Optional[dict[str, float]] = None,
    root: Optional[Union[str, os.PathLike[str]]] = None,
    max_file_bytes: Optional[int] = None,
) -> dict[str, npt.NDArray[np.float64]]: ...
