//! Python bindings of Sphaera: the native module `sphaera._sphaera`, which the Python
//! package `sphaera` (`python/sphaera/__init__.py`) re-exports.
//!
//! ```python
//! import numpy as np
//! import sphaera
//!
//! mesh = sphaera.load("bunny.obj")            # or sphaera.Mesh(vertices, faces)
//! small = sphaera.simplify(mesh, ratio=0.1)   # certified: small.error_bound
//! d = sphaera.distance(mesh, np.random.rand(1000, 3))
//! h = sphaera.hausdorff(mesh, small.mesh)     # h.lower <= H(A, B) <= h.upper
//! tree = sphaera.spheretree(mesh, depth=3, branch=8)
//! tree.levels[2]                              # (n, 4) array: x, y, z, r
//! fine = sphaera.spheretree(mesh, tolerance="1%")   # every leaf within 1 % of the diagonal
//! fine.cut(2), fine.leaves, fine.leaf_errors  # what covers the surface, and how well
//! eight = sphaera.spheretree(mesh, spheres=8) # exactly 8 spheres: eight.cut(1)
//! coarse, depth = sphaera.hal(mesh, tolerance="1%")
//! labels, directions = sphaera.silhouette_labels(mesh, labels_file="bunny.labels")
//! robot = sphaera.urdf("panda.urdf", spheres_per_link=40)
//! pairs = robot["self_collision"]              # MoveIt's rules: which pairs to skip
//! poses = sphaera.link_poses("panda.urdf", {"panda_joint4": -1.5})
//! ```
//!
//! Arrays come in and go out as numpy arrays (`float64` coordinates, `uint32` or any
//! integer faces in). Long computations release the GIL and use every core. Every result
//! pickles (round-tripping exactly), has a readable `repr` and converts to plain data with
//! `to_dict()`. Errors raise `ValueError` for bad input (`ToleranceUnreachableError`, a
//! `ValueError`, for a sphere-tree tolerance that cannot be met) and `OSError` for files,
//! with the library's message.
//!
//! Built with maturin (`pip install ./crates/sphaera-py`); tested from Python
//! (`crates/sphaera-py/tests`, run by `cargo xtask test`).

mod arrays;
mod errors;
mod hal;
mod hal_multi;
mod mesh;
mod more;
mod queries;
mod robot;
mod simplify;
mod spheretree;

use pyo3::prelude::*;

/// The native module; `sphaera` re-exports everything in it.
#[pymodule]
fn _sphaera(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add_class::<mesh::Mesh>()?;
    module.add_class::<simplify::Simplified>()?;
    module.add_class::<queries::Distances>()?;
    module.add_class::<queries::Hausdorff>()?;
    module.add_class::<spheretree::SphereTree>()?;
    module.add_class::<hal::HalTree2>()?;
    module.add_class::<hal::HalTree3>()?;
    module.add_class::<hal_multi::HalMultiPolygon2>()?;
    module.add(
        "ToleranceUnreachableError",
        module.py().get_type::<errors::ToleranceUnreachableError>(),
    )?;
    module.add_function(wrap_pyfunction!(mesh::load, module)?)?;
    module.add_function(wrap_pyfunction!(simplify::simplify, module)?)?;
    module.add_function(wrap_pyfunction!(queries::distance, module)?)?;
    module.add_function(wrap_pyfunction!(queries::hausdorff, module)?)?;
    module.add_function(wrap_pyfunction!(spheretree::spheretree, module)?)?;
    module.add_function(wrap_pyfunction!(more::hal, module)?)?;
    module.add_function(wrap_pyfunction!(more::silhouette_labels, module)?)?;
    module.add_function(wrap_pyfunction!(robot::urdf, module)?)?;
    module.add_function(wrap_pyfunction!(robot::link_poses, module)?)?;
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
