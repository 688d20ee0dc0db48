//! `sphaera.Mesh` and `sphaera.load`.

use std::path::PathBuf;
use std::sync::OnceLock;

use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple, PyType};
use sphaera::io::FilePolicy;
use sphaera::mesh::closest::TriangleTree;
use sphaera::mesh::{TriMesh, topology};

use crate::arrays;
use crate::errors::IntoPy;

/// A triangle mesh: `vertices` (`(n, 3)` float64) and `faces` (`(m, 3)` vertex indices).
///
/// Built from arrays (`Mesh(vertices, faces)`, any real and integer dtypes, or nested
/// lists) or read from a file (`sphaera.load`). Immutable; pickles exactly.
#[pyclass(module = "sphaera", frozen)]
pub struct Mesh {
    pub(crate) inner: TriMesh,
    /// The exact closest-point tree, built on the first distance query and kept.
    tree: OnceLock<TriangleTree>,
}

impl Mesh {
    /// Wraps a mesh of the library.
    pub(crate) fn from_inner(inner: TriMesh) -> Self {
        Self {
            inner,
            tree: OnceLock::new(),
        }
    }

    /// The closest-point tree, built once.
    pub(crate) fn tree(&self) -> PyResult<&TriangleTree> {
        if let Some(tree) = self.tree.get() {
            return Ok(tree);
        }
        let tree = TriangleTree::new(&self.inner).py_err()?;
        Ok(self.tree.get_or_init(|| tree))
    }
}

#[pymethods]
impl Mesh {
    /// A mesh from an `(n, 3)` array of vertex positions and an `(m, 3)` array of
    /// vertex indices.
    ///
    /// Raises `ValueError` for another shape, a position that is not finite, or an index
    /// outside the vertices.
    #[new]
    fn new(vertices: &Bound<'_, PyAny>, faces: &Bound<'_, PyAny>) -> PyResult<Self> {
        let positions = arrays::points(vertices, "vertices", true)?;
        let triangles = arrays::triangles(faces, positions.len())?;
        Ok(Self::from_inner(
            TriMesh::new(positions, triangles).py_err()?,
        ))
    }

    /// The vertex positions, an `(n, 3)` float64 array (a copy).
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arrays::points_array(py, self.inner.positions())
    }

    /// The triangles, an `(m, 3)` uint32 array of vertex indices (a copy).
    #[getter]
    fn faces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<u32>> {
        let flat: Vec<u32> = self.inner.triangles().iter().flatten().copied().collect();
        arrays::rows(py, flat, 3)
    }

    /// The number of vertices.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.inner.positions().len()
    }

    /// The number of triangles.
    #[getter]
    fn triangle_count(&self) -> usize {
        self.inner.triangle_count()
    }

    /// The length of the bounding box's diagonal.
    #[getter]
    fn diagonal(&self) -> f64 {
        self.inner.bounding_box_diagonal()
    }

    /// The bounding box: `(minimum, maximum)` corners as `(x, y, z)` tuples.
    fn bounding_box(&self) -> ((f64, f64, f64), (f64, f64, f64)) {
        let b = self.inner.bounding_box();
        ((b.min.x, b.min.y, b.min.z), (b.max.x, b.max.y, b.max.z))
    }

    /// What `sphaera info` reports: counts, the bounding box, whether the mesh is closed,
    /// manifold and oriented, its genus, components and boundary, as a dict.
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let report = topology::analyze(&self.inner);
        let info = PyDict::new(py);
        info.set_item("vertices", self.inner.positions().len())?;
        info.set_item("triangles", self.inner.triangle_count())?;
        info.set_item("edges", report.edge_count)?;
        info.set_item("bounding_box", self.bounding_box())?;
        info.set_item("diagonal", self.inner.bounding_box_diagonal())?;
        info.set_item("surface_area", self.inner.surface_area())?;
        info.set_item("closed", report.is_closed)?;
        info.set_item("manifold", report.is_manifold)?;
        info.set_item("oriented", report.is_oriented)?;
        info.set_item("genus", report.genus)?;
        info.set_item("components", report.component_count)?;
        info.set_item("boundary_loops", report.boundary_loop_count)?;
        info.set_item("boundary_edges", report.boundary_edge_count)?;
        info.set_item("non_manifold_edges", report.non_manifold_edge_count)?;
        info.set_item("non_manifold_vertices", report.non_manifold_vertex_count)?;
        info.set_item("euler_characteristic", report.euler_characteristic)?;
        Ok(info)
    }

    /// Writes the mesh as OBJ or PLY (binary), from the extension, atomically.
    ///
    /// Raises `OSError` when the file cannot be written, `ValueError` for an unknown
    /// extension.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        py.detach(move || sphaera::mesh::io::save(&path, &self.inner))
            .py_err()
    }

    /// `{"vertices": array, "faces": array}`.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        dict.set_item("vertices", self.vertices(py))?;
        dict.set_item("faces", self.faces(py))?;
        Ok(dict)
    }

    /// Meshes are equal when their vertices and faces are, exactly.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<Mesh>()
            .is_ok_and(|o| o.get().inner == self.inner)
    }

    fn __repr__(&self) -> String {
        format!(
            "Mesh({} vertices, {} triangles)",
            self.inner.positions().len(),
            self.inner.triangle_count()
        )
    }

    /// Pickling: the class and its arrays (float64, so the copy is exact).
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyType>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let mesh = slf.get();
        let arguments = PyTuple::new(
            py,
            [mesh.vertices(py).into_any(), mesh.faces(py).into_any()],
        )?;
        Ok((slf.get_type(), arguments))
    }
}

/// Reads a mesh file: OBJ, PLY (ASCII or binary), STL (ASCII or binary), OFF, glTF or
/// GLB. Only regular files are read (a device, a named pipe or a folder is refused), of at
/// most `max_bytes` bytes (default 2 GiB); with `root`, only files inside that folder once
/// links and `..` are resolved (a service reading uploads). A glTF file's buffer files
/// must lie in its own folder.
///
/// Raises `PermissionError` (an `OSError`) for a file the policy refuses, `OSError` when
/// the file cannot be read, `ValueError` when it is malformed.
#[pyfunction]
#[pyo3(signature = (path, root=None, max_bytes=None))]
pub fn load(
    py: Python<'_>,
    path: PathBuf,
    root: Option<PathBuf>,
    max_bytes: Option<u64>,
) -> PyResult<Mesh> {
    let policy = file_policy(root, max_bytes);
    let loaded = py
        .detach(move || sphaera::io::read_with(&path, &policy))
        .py_err()?;
    Ok(Mesh::from_inner(loaded.mesh))
}

/// The file policy of a call's `root` and `max_bytes` arguments.
pub(crate) fn file_policy(root: Option<PathBuf>, max_bytes: Option<u64>) -> FilePolicy {
    let mut policy = FilePolicy::default();
    if let Some(root) = root {
        policy = policy.with_root(root);
    }
    if let Some(max_bytes) = max_bytes {
        policy = policy.with_max_bytes(max_bytes);
    }
    policy
}
