"""Sphaera: meshes approximated by spheres, hierarchically.

Certified simplification, exact and certified closest-point distances, certified
Hausdorff distances and sphere-trees, with numpy arrays in and out. Long computations
release the GIL and use every core; every result pickles exactly.

>>> import sphaera
>>> mesh = sphaera.load("bunny.obj")                  # doctest: +SKIP
>>> tree = sphaera.spheretree(mesh, depth=3)          # doctest: +SKIP
>>> tree.levels[3].shape, tree.errors[3]              # doctest: +SKIP
>>> fine = sphaera.spheretree(mesh, tolerance="1%")   # doctest: +SKIP
>>> fine.leaves, fine.leaf_errors, fine.met           # doctest: +SKIP
>>> eight = sphaera.spheretree(mesh, spheres=8)       # doctest: +SKIP
>>> eight.cut(1).shape                                # (8, 4)  # doctest: +SKIP
"""

from ._sphaera import (
    Distances,
    HalMultiPolygon2,
    HalTree2,
    HalTree3,
    Hausdorff,
    Mesh,
    SphereTree,
    Simplified,
    ToleranceUnreachableError,
    __version__,
    distance,
    hal,
    hausdorff,
    link_poses,
    load,
    silhouette_labels,
    simplify,
    spheretree,
    urdf,
)

__all__ = [
    "Distances",
    "HalMultiPolygon2",
    "HalTree2",
    "HalTree3",
    "Hausdorff",
    "Mesh",
    "Simplified",
    "SphereTree",
    "ToleranceUnreachableError",
    "__version__",
    "distance",
    "hal",
    "hausdorff",
    "link_poses",
    "load",
    "silhouette_labels",
    "simplify",
    "spheretree",
    "urdf",
]
