//! `sphaera.spheretree`: the main job, each level's worst error certified.

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple, PyType};
use sphaera::mesh::{Length, Surface};
use sphaera::spheretree::{EvaluationOptions, Method, SphereTreeOptions, build, evaluate_set};

use crate::arrays;
use crate::errors::{IntoPy, value_error};
use crate::mesh::Mesh;

/// A sphere-tree: per level an `(n, 4)` array of spheres (`x, y, z, r`), each sphere's
/// parent in the level above, and the level's certified worst error (how far any sphere
/// reaches beyond the surface: `lower ≤ error ≤ upper`).
#[pyclass(module = "sphaera", frozen, get_all)]
pub struct SphereTree {
    /// Per level, an `(n, 4)` float64 array: centre and radius.
    levels: Py<PyList>,
    /// Per level, an `(n,)` int64 array: each sphere's parent's row in the level above
    /// (`-1` at the root level).
    parents: Py<PyList>,
    /// Per level, `(lower, upper)` of the worst error, or `None` when not evaluated.
    errors: Py<PyList>,
    /// The method's name (`"auto"`, `"expand"`, …).
    method: String,
    /// The most children a node may have.
    branch: usize,
}

#[pymethods]
impl SphereTree {
    /// A tree from its parts (what unpickling calls).
    #[new]
    fn new(
        levels: Py<PyList>,
        parents: Py<PyList>,
        errors: Py<PyList>,
        method: String,
        branch: usize,
    ) -> Self {
        Self {
            levels,
            parents,
            errors,
            method,
            branch,
        }
    }

    /// The number of levels (the root level counts).
    #[getter]
    fn depth(&self, py: Python<'_>) -> usize {
        self.levels.bind(py).len()
    }

    fn __len__(&self, py: Python<'_>) -> usize {
        self.levels.bind(py).len()
    }

    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        dict.set_item("levels", &self.levels)?;
        dict.set_item("parents", &self.parents)?;
        dict.set_item("errors", &self.errors)?;
        dict.set_item("method", &self.method)?;
        dict.set_item("branch", self.branch)?;
        Ok(dict)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let counts: Vec<String> = self
            .levels
            .bind(py)
            .iter()
            .map(|level| level.len().map(|n| n.to_string()))
            .collect::<PyResult<_>>()?;
        Ok(format!(
            "SphereTree(method={:?}, branch={}, spheres per level [{}])",
            self.method,
            self.branch,
            counts.join(", ")
        ))
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyType>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let t = slf.get();
        let arguments = PyTuple::new(
            py,
            [
                t.levels.bind(py).clone().into_any(),
                t.parents.bind(py).clone().into_any(),
                t.errors.bind(py).clone().into_any(),
                t.method.clone().into_pyobject(py)?.into_any(),
                t.branch.into_pyobject(py)?.into_any(),
            ],
        )?;
        Ok((slf.get_type(), arguments))
    }
}

/// A level's spheres, parents (rows of the level above) and certified error.
struct Level {
    spheres: Vec<f64>,
    parents: Vec<i64>,
    error: Option<(f64, f64)>,
}

/// Builds the sphere-tree of a closed (or nearly closed) mesh, as `sphaera spheretree`
/// does: `depth` levels below the root, at most `branch` children per node, the reducer
/// `method` (`"auto"`, `"merge"`, `"burst"`, `"expand"`, `"combined"`, `"octree"`,
/// `"grid"`, `"hubbard"`); `samples` surface samples and `seed` (defaults as the CLI's).
/// With `evaluate` (the default) each level's worst error is certified to 0.1 % of the
/// diagonal. Deterministic for a seed; runs on every core with the GIL released.
///
/// Raises `ValueError` for an unknown method, a mesh that encloses no volume, or bad
/// parameters.
#[pyfunction]
#[pyo3(signature = (mesh, depth=3, branch=8, method="auto", samples=None, seed=None, evaluate=true))]
#[allow(clippy::too_many_arguments)]
pub fn spheretree(
    py: Python<'_>,
    mesh: &Mesh,
    depth: usize,
    branch: usize,
    method: &str,
    samples: Option<usize>,
    seed: Option<u64>,
    evaluate: bool,
) -> PyResult<SphereTree> {
    let Some(chosen) = Method::from_name(method) else {
        let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        return Err(value_error(format!(
            "unknown method {method:?}: one of {}",
            names.join(", ")
        )));
    };
    let mut options = SphereTreeOptions::default()
        .with_method(chosen)
        .with_depth(depth)
        .with_branch(branch);
    if let Some(samples) = samples {
        options = options.with_samples(samples);
    }
    if let Some(seed) = seed {
        options = options.with_seed(seed);
    }
    let levels: Vec<Level> = py
        .detach(|| -> Result<Vec<Level>, sphaera::Error> {
            let surface = Surface::new(&mesh.inner)?;
            let tree = build(&surface, &options)?;
            let evaluation = EvaluationOptions::default()
                .with_tolerance(Length::RelativeToDiagonal(1e-3))
                .with_screening(true);
            // Nodes are stored level by level: a node's index less its level's first
            // index is its row.
            let mut first = 0_usize;
            let mut previous_first = 0_usize;
            let mut out = Vec::with_capacity(tree.level_count());
            for l in 0..tree.level_count() {
                let nodes = tree.level(l);
                let spheres = tree.level_spheres(l);
                let error = if evaluate && !spheres.is_empty() {
                    let fit = evaluate_set(&surface, &spheres, &evaluation)?;
                    Some((fit.worst_lower, fit.worst_upper))
                } else {
                    None
                };
                out.push(Level {
                    spheres: spheres
                        .iter()
                        .flat_map(|s| [s.center.x, s.center.y, s.center.z, s.radius])
                        .collect(),
                    parents: nodes
                        .iter()
                        .map(|n| {
                            n.parent.map_or(-1, |p| {
                                i64::from(p) - i64::try_from(previous_first).unwrap_or(0)
                            })
                        })
                        .collect(),
                    error,
                });
                previous_first = first;
                first += nodes.len();
            }
            Ok(out)
        })
        .py_err()?;
    let spheres = PyList::empty(py);
    let parents = PyList::empty(py);
    let errors = PyList::empty(py);
    for level in levels {
        let array: Bound<'_, PyArray2<f64>> = arrays::rows(py, level.spheres, 4);
        spheres.append(array)?;
        let rows: Bound<'_, PyArray1<i64>> = arrays::vector(py, level.parents);
        parents.append(rows)?;
        errors.append(level.error)?;
    }
    Ok(SphereTree {
        levels: spheres.unbind(),
        parents: parents.unbind(),
        errors: errors.unbind(),
        method: chosen.name().to_owned(),
        branch,
    })
}
