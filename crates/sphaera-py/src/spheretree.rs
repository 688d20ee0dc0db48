//! `sphaera.spheretree`: the main job, built to a depth, to a tolerance or as exactly N
//! spheres, each level's cut with its worst error certified.

use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple, PyType};
use sphaera::mesh::{Length, Surface};
use sphaera::spheretree::{
    Effort, EvaluationOptions, MAX_BRANCH, MAX_TREE_NODES, Method, SphereTreeError,
    SphereTreeOptions, build, evaluate_level,
};

use crate::arrays;
use crate::errors::{ToleranceUnreachableError, to_py, value_error};
use crate::mesh::Mesh;
use crate::simplify::length;

/// A sphere-tree: per level an `(n, 4)` array of spheres (`x, y, z, r`), each sphere's
/// parent in the level above and its certified error, and per level the certified worst
/// error of the level's cut (how far any of its spheres reaches beyond the surface:
/// `lower ≤ error ≤ upper`).
///
/// A tree built to a depth has every node above the deepest level divided, so each level
/// covers the surface. A tree built to a tolerance divides only the nodes above it: its
/// leaves end at different depths, and what covers the surface at the detail of level `l`
/// is the cut `cut(l)`, the level's spheres and the leaves above it.
#[pyclass(module = "sphaera", frozen, get_all)]
pub struct SphereTree {
    /// Per level, an `(n, 4)` float64 array: centre and radius.
    levels: Py<PyList>,
    /// Per level, an `(n,)` int64 array: each sphere's parent's row in the level above
    /// (`-1` at the root level).
    parents: Py<PyList>,
    /// Per level, `(lower, upper)` of the worst error of the level's cut (`cut(level)`), or
    /// `None` when not evaluated.
    errors: Py<PyList>,
    /// The method's name as asked (`"auto"`, `"expand"`, …).
    method: String,
    /// The most children a node may have.
    branch: usize,
    /// Per level, an `(n,)` float64 array: each sphere's certified error (an upper bound on
    /// how far it reaches beyond the surface), or `None` for a tree unpickled from a
    /// version without it.
    node_errors: Option<Py<PyList>>,
    /// `"solid"` for a mesh with an inside, `"shell"` for one without (a flat sheet, an
    /// open patch): a sphere's error is how far it reaches out of the solid, or away from
    /// the shell.
    surface: String,
    /// What the tree was built to: `"depth"`, `"tolerance"` or `"spheres"`.
    goal: String,
    /// The tolerance asked for, absolute (in the mesh's units), or `None`.
    tolerance: Option<f64>,
    /// With a tolerance, whether every leaf's certified error is within it (always `True`
    /// for a tree returned: one that cannot meet it raises `ToleranceUnreachableError`);
    /// `None` without a tolerance.
    met: Option<bool>,
    /// The minimax method's effort: `"quick"`, `"default"` or `"thorough"`.
    effort: String,
}

/// One level of a [`SphereTree`] as read back from its arrays.
struct LevelView {
    /// The spheres, `x, y, z, r` each.
    spheres: Vec<[f64; 4]>,
    /// Each sphere's parent's row in the level above (`-1` at the root).
    parents: Vec<i64>,
    /// Each sphere's certified error, when known.
    errors: Option<Vec<f64>>,
}

impl SphereTree {
    /// The levels as read from the arrays (which Python code may have replaced: their
    /// shapes are checked).
    fn views(&self, py: Python<'_>) -> PyResult<Vec<LevelView>> {
        let levels = self.levels.bind(py);
        let parents = self.parents.bind(py);
        let node_errors = self.node_errors.as_ref().map(|e| e.bind(py));
        if parents.len() != levels.len()
            || node_errors.is_some_and(|errors| errors.len() != levels.len())
        {
            return Err(value_error(
                "inconsistent sphere-tree: levels, parents and node_errors differ in length",
            ));
        }
        let mut out = Vec::with_capacity(levels.len());
        for (l, level) in levels.iter().enumerate() {
            let spheres: PyReadonlyArray2<'_, f64> = level
                .extract()
                .map_err(|_| value_error(format!("levels[{l}] must be an (n, 4) float64 array")))?;
            let spheres = spheres.as_array();
            if spheres.ncols() != 4 {
                return Err(value_error(format!(
                    "levels[{l}] must be an (n, 4) float64 array"
                )));
            }
            let rows: PyReadonlyArray1<'_, i64> = parents
                .get_item(l)?
                .extract()
                .map_err(|_| value_error(format!("parents[{l}] must be an (n,) int64 array")))?;
            let rows = rows.as_array().to_vec();
            let errors = match node_errors {
                Some(errors) => {
                    let e: PyReadonlyArray1<'_, f64> =
                        errors.get_item(l)?.extract().map_err(|_| {
                            value_error(format!("node_errors[{l}] must be an (n,) float64 array"))
                        })?;
                    Some(e.as_array().to_vec())
                }
                None => None,
            };
            if rows.len() != spheres.nrows()
                || errors.as_ref().is_some_and(|e| e.len() != rows.len())
            {
                return Err(value_error(format!(
                    "inconsistent sphere-tree: level {l} has {} spheres and {} parents",
                    spheres.nrows(),
                    rows.len()
                )));
            }
            out.push(LevelView {
                spheres: spheres
                    .rows()
                    .into_iter()
                    .map(|r| [r[0], r[1], r[2], r[3]])
                    .collect(),
                parents: rows,
                errors,
            });
        }
        Ok(out)
    }

    /// The cut at depth `level` as `(level, row)` pairs, level by level (the order of the
    /// library's `SphereTree::cut_at`): the level's spheres and the leaves above it; beyond
    /// the deepest level, every leaf.
    fn cut_rows(views: &[LevelView], level: usize) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for (l, view) in views.iter().enumerate() {
            if l > level {
                break;
            }
            if l == level {
                out.extend((0..view.spheres.len()).map(|row| (l, row)));
                break;
            }
            let mut divided = vec![false; view.spheres.len()];
            if let Some(below) = views.get(l + 1) {
                for &p in &below.parents {
                    if let Some(d) = usize::try_from(p).ok().and_then(|p| divided.get_mut(p)) {
                        *d = true;
                    }
                }
            }
            out.extend(
                divided
                    .iter()
                    .enumerate()
                    .filter(|&(_, &d)| !d)
                    .map(|(row, _)| (l, row)),
            );
        }
        out
    }

    /// The spheres of `rows` as an `(n, 4)` array.
    fn spheres_of<'py>(
        py: Python<'py>,
        views: &[LevelView],
        rows: &[(usize, usize)],
    ) -> Bound<'py, PyArray2<f64>> {
        let flat: Vec<f64> = rows
            .iter()
            .flat_map(|&(l, r)| views[l].spheres[r])
            .collect();
        arrays::rows(py, flat, 4)
    }

    /// The certified errors of `rows` as an `(n,)` array.
    fn errors_of<'py>(
        py: Python<'py>,
        views: &[LevelView],
        rows: &[(usize, usize)],
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let mut out = Vec::with_capacity(rows.len());
        for &(l, r) in rows {
            let Some(errors) = &views[l].errors else {
                return Err(value_error(
                    "this sphere-tree has no node errors (it was pickled by an older version)",
                ));
            };
            out.push(errors[r]);
        }
        Ok(arrays::vector(py, out))
    }
}

/// A level argument: a whole number, not negative.
fn level_index(level: i64) -> PyResult<usize> {
    usize::try_from(level)
        .map_err(|_| value_error(format!("level must not be negative, got {level}")))
}

#[pymethods]
impl SphereTree {
    /// A tree from its parts (what unpickling calls).
    #[new]
    #[pyo3(signature = (levels, parents, errors, method, branch, node_errors=None, surface="solid".to_owned(), goal="depth".to_owned(), tolerance=None, met=None, effort="default".to_owned()))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        levels: Py<PyList>,
        parents: Py<PyList>,
        errors: Py<PyList>,
        method: String,
        branch: usize,
        node_errors: Option<Py<PyList>>,
        surface: String,
        goal: String,
        tolerance: Option<f64>,
        met: Option<bool>,
        effort: String,
    ) -> Self {
        Self {
            levels,
            parents,
            errors,
            method,
            branch,
            node_errors,
            surface,
            goal,
            tolerance,
            met,
            effort,
        }
    }

    /// The number of levels (the root level counts).
    #[getter]
    fn depth(&self, py: Python<'_>) -> usize {
        self.levels.bind(py).len()
    }

    /// The spheres that cover the surface at the detail of `level`, an `(n, 4)` array: the
    /// level's spheres and the leaves above it (in a tree built to a depth, the level
    /// itself); beyond the deepest level, the leaves. Level by level, in each by row.
    ///
    /// Raises `ValueError` for a negative level.
    fn cut<'py>(&self, py: Python<'py>, level: i64) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let level = level_index(level)?;
        let views = self.views(py)?;
        Ok(Self::spheres_of(py, &views, &Self::cut_rows(&views, level)))
    }

    /// The certified error of each sphere of `cut(level)`, an `(n,)` array (upper bounds on
    /// how far each reaches beyond the surface).
    ///
    /// Raises `ValueError` for a negative level.
    fn cut_errors<'py>(&self, py: Python<'py>, level: i64) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let level = level_index(level)?;
        let views = self.views(py)?;
        Self::errors_of(py, &views, &Self::cut_rows(&views, level))
    }

    /// The leaves (spheres without children), an `(n, 4)` array, level by level: the finest
    /// spheres of every part of the surface, which together cover it. In a tree built to a
    /// tolerance, each is within it (`leaf_errors`).
    #[getter]
    fn leaves<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let views = self.views(py)?;
        Ok(Self::spheres_of(
            py,
            &views,
            &Self::cut_rows(&views, usize::MAX),
        ))
    }

    /// The certified error of each leaf (an upper bound on how far it reaches beyond the
    /// surface), an `(n,)` array in the order of `leaves`.
    #[getter]
    fn leaf_errors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let views = self.views(py)?;
        Self::errors_of(py, &views, &Self::cut_rows(&views, usize::MAX))
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
        dict.set_item("node_errors", &self.node_errors)?;
        dict.set_item("surface", &self.surface)?;
        dict.set_item("goal", &self.goal)?;
        dict.set_item("tolerance", self.tolerance)?;
        dict.set_item("met", self.met)?;
        dict.set_item("effort", &self.effort)?;
        Ok(dict)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let counts: Vec<String> = self
            .levels
            .bind(py)
            .iter()
            .map(|level| level.len().map(|n| n.to_string()))
            .collect::<PyResult<_>>()?;
        let tolerance = match (self.tolerance, self.met) {
            (Some(t), Some(met)) => {
                format!(", tolerance={t:e} {}", if met { "met" } else { "NOT met" })
            }
            _ => String::new(),
        };
        Ok(format!(
            "SphereTree(method={:?}, surface={:?}, goal={:?}, branch={}{tolerance}, spheres per level [{}])",
            self.method,
            self.surface,
            self.goal,
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
                t.node_errors
                    .clone_ref_opt(py)
                    .into_pyobject(py)?
                    .into_any(),
                t.surface.clone().into_pyobject(py)?.into_any(),
                t.goal.clone().into_pyobject(py)?.into_any(),
                t.tolerance.into_pyobject(py)?.into_any(),
                t.met.into_pyobject(py)?.into_any(),
                t.effort.clone().into_pyobject(py)?.into_any(),
            ],
        )?;
        Ok((slf.get_type(), arguments))
    }
}

/// `clone_ref` through an `Option`.
trait CloneRefOpt<T> {
    /// A new reference to the same object, or `None`.
    fn clone_ref_opt(&self, py: Python<'_>) -> Option<Py<T>>;
}

impl<T> CloneRefOpt<T> for Option<Py<T>> {
    fn clone_ref_opt(&self, py: Python<'_>) -> Option<Py<T>> {
        self.as_ref().map(|p| p.clone_ref(py))
    }
}

/// A level's spheres, parents (rows of the level above), node errors and the certified
/// error of its cut.
struct Level {
    spheres: Vec<f64>,
    parents: Vec<i64>,
    node_errors: Vec<f64>,
    error: Option<(f64, f64)>,
}

/// What the tree is built to.
#[derive(Debug, Clone, Copy)]
enum Goal {
    /// Every node divided, to this many levels below the root.
    Depth(usize),
    /// Nodes divided until every leaf's certified error meets it (minimax).
    Tolerance(Length),
    /// Exactly this many spheres in one level (minimax).
    Spheres(usize),
}

impl Goal {
    fn name(self) -> &'static str {
        match self {
            Self::Depth(_) => "depth",
            Self::Tolerance(_) => "tolerance",
            Self::Spheres(_) => "spheres",
        }
    }
}

/// A count argument (`depth`, `branch`, `spheres`, `samples`): a whole number, not negative.
fn count(value: &Bound<'_, PyAny>, name: &str) -> PyResult<usize> {
    let n: i64 = value.extract().map_err(|_| {
        value_error(format!(
            "{name} must be a whole number, got {}",
            value
                .repr()
                .map_or_else(|_| "?".to_owned(), |r| r.to_string())
        ))
    })?;
    usize::try_from(n).map_err(|_| value_error(format!("{name} must not be negative, got {n}")))
}

/// The goal of a call from its arguments, checked against the method before any work.
fn goal_of(
    method: Method,
    depth: Option<usize>,
    branch: Option<usize>,
    tolerance: Option<&Bound<'_, PyAny>>,
    spheres: Option<usize>,
) -> PyResult<Goal> {
    let minimax = method.resolved() == Method::Minimax;
    let goal = match (spheres, tolerance) {
        (Some(_), Some(_)) => {
            return Err(value_error(
                "give spheres (exactly N spheres in one level) or tolerance (a tree as deep \
                 as it needs), not both",
            ));
        }
        (Some(n), None) => {
            if depth.is_some() || branch.is_some() {
                return Err(value_error(format!(
                    "spheres={n} builds one level of exactly {n} spheres: depth and branch do \
                     not apply"
                )));
            }
            if n == 0 || n > MAX_BRANCH {
                return Err(value_error(format!(
                    "spheres must be between 1 and {MAX_BRANCH} (the most spheres of one \
                     level), got {n}"
                )));
            }
            Goal::Spheres(n)
        }
        (None, Some(t)) => {
            if depth.is_some() {
                return Err(value_error(
                    "a tree built to a tolerance is as deep as it needs: depth does not apply",
                ));
            }
            let t =
                length(t).map_err(|e| value_error(format!("tolerance: {}", e.value(t.py()))))?;
            if t.value() <= 0.0 {
                return Err(value_error(
                    "tolerance must be positive (an absolute length, or a percentage of the \
                     diagonal such as \"1%\")",
                ));
            }
            Goal::Tolerance(t)
        }
        (None, None) => Goal::Depth(depth.unwrap_or(3)),
    };
    if !minimax && !matches!(goal, Goal::Depth(_)) {
        return Err(value_error(format!(
            "{} only the minimax method does (method=\"minimax\" or \"auto\"); method={:?} \
             builds to a depth",
            match goal {
                Goal::Tolerance(_) => "a tree built to a tolerance is what",
                _ => "exactly N spheres in one level is what",
            },
            method.name()
        )));
    }
    Ok(goal)
}

/// The error a build failed with, as a Python exception: [`ToleranceUnreachableError`]
/// with the figures for a tolerance that cannot be met, else as every other error.
fn build_error(py: Python<'_>, error: &sphaera::Error) -> PyErr {
    if let sphaera::Error::SphereTree(inner) = error
        && let SphereTreeError::ToleranceUnreachable {
            tolerance,
            worst,
            spheres,
            levels,
            ..
        } = **inner
    {
        let err = ToleranceUnreachableError::new_err(error.to_string());
        let value = err.value(py);
        let set = || -> PyResult<()> {
            value.setattr("tolerance", tolerance)?;
            value.setattr("worst", worst)?;
            value.setattr("spheres", spheres)?;
            value.setattr("levels", levels)?;
            Ok(())
        };
        return match set() {
            Ok(()) => err,
            Err(e) => e,
        };
    }
    to_py(error)
}

/// Builds the sphere-tree of a mesh, as `sphaera spheretree` does, to one of three goals:
///
/// - a depth (the default): `depth` levels below the root (default 3), at most `branch`
///   children per node (default 8);
/// - `tolerance`: as deep as needed until every leaf's certified error (how far it reaches
///   beyond the surface) is within it, dividing only the nodes above it, each into the
///   fewest children (at most `branch`) that meet it; an absolute length, or a string such
///   as `"2%"` of the bounding-box diagonal;
/// - `spheres=N`: one level of exactly `N` spheres (1 to 10,000).
///
/// `method` is the reducer (`"auto"`, which is `"minimax"`, or the paper's `"merge"`,
/// `"burst"`, `"expand"`, `"combined"`, or a baseline `"octree"`, `"grid"`, `"hubbard"`);
/// tolerances and sphere counts need minimax. `effort` (`"quick"`, `"default"`,
/// `"thorough"`) trades the minimax method's time for tighter spheres. `max_nodes` (with
/// `tolerance` only) is the most nodes the tree may have, spheres of every level
/// together (1 to 2^21, the default): the tolerance is met within it or refused, never
/// exceeded. `samples` and
/// `seed` are the other methods' surface samples and seed (defaults as the CLI's).
///
/// A mesh with an inside is a solid; one without (a flat sheet, an open patch) is a shell,
/// which minimax covers (the other methods need a solid). With `evaluate` (the default)
/// each level's cut (`cut(level)`) has its worst error certified to 0.1 % of the diagonal
/// (with the spheres' own certified errors as bounds). Deterministic for a seed; runs on
/// every core with the GIL released.
///
/// Raises `ValueError` for an unknown method or effort, bad parameters (a NaN, zero or
/// negative tolerance, `spheres=0`, `spheres` with `tolerance`, `depth` or `branch`,
/// `max_nodes` without `tolerance` or out of range), a
/// mesh without triangles or facing inward; `ToleranceUnreachableError` (a `ValueError`)
/// when the tolerance cannot be met within the library's limits.
#[pyfunction]
#[pyo3(signature = (mesh, depth=None, branch=None, method="auto", samples=None, seed=None, evaluate=true, *, tolerance=None, spheres=None, effort="default", max_nodes=None))]
#[allow(clippy::too_many_arguments)]
pub fn spheretree(
    py: Python<'_>,
    mesh: &Mesh,
    depth: Option<&Bound<'_, PyAny>>,
    branch: Option<&Bound<'_, PyAny>>,
    method: &str,
    samples: Option<&Bound<'_, PyAny>>,
    seed: Option<u64>,
    evaluate: bool,
    tolerance: Option<&Bound<'_, PyAny>>,
    spheres: Option<&Bound<'_, PyAny>>,
    effort: &str,
    max_nodes: Option<&Bound<'_, PyAny>>,
) -> PyResult<SphereTree> {
    let Some(chosen) = Method::from_name(method) else {
        let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        return Err(value_error(format!(
            "unknown method {method:?}: one of {}",
            names.join(", ")
        )));
    };
    let Ok(effort_level) = effort.parse::<Effort>() else {
        let names: Vec<&str> = Effort::ALL.iter().map(|e| e.name()).collect();
        return Err(value_error(format!(
            "unknown effort {effort:?}: one of {}",
            names.join(", ")
        )));
    };
    let minimax = chosen.resolved() == Method::Minimax;
    if effort_level != Effort::Default && !minimax {
        return Err(value_error(format!(
            "effort applies to the minimax method (method=\"minimax\" or \"auto\"), not \
             method={:?}",
            chosen.name()
        )));
    }
    let depth = depth.map(|d| count(d, "depth")).transpose()?;
    let branch = branch.map(|b| count(b, "branch")).transpose()?;
    let samples = samples.map(|s| count(s, "samples")).transpose()?;
    let spheres = spheres.map(|s| count(s, "spheres")).transpose()?;
    let goal = goal_of(chosen, depth, branch, tolerance, spheres)?;
    let max_nodes = max_nodes.map(|n| count(n, "max_nodes")).transpose()?;
    if let Some(n) = max_nodes {
        if !matches!(goal, Goal::Tolerance(_)) {
            return Err(value_error(
                "max_nodes bounds a tree built to a tolerance: give tolerance as well",
            ));
        }
        if !(1..=MAX_TREE_NODES).contains(&n) {
            return Err(value_error(format!(
                "max_nodes must be between 1 and {MAX_TREE_NODES} (a tree's most nodes), got {n}"
            )));
        }
    }

    let mut options = SphereTreeOptions::default()
        .with_method(chosen)
        .with_effort(effort_level)
        .with_branch(branch.unwrap_or(8));
    options = match goal {
        Goal::Depth(depth) => options.with_depth(depth),
        Goal::Tolerance(t) => options
            .with_tolerance(t)
            .with_max_nodes(max_nodes.unwrap_or(MAX_TREE_NODES)),
        Goal::Spheres(n) => options.with_depth(1).with_branch(n),
    };
    if let Some(samples) = samples {
        options = options.with_samples(samples);
    }
    if let Some(seed) = seed {
        options = options.with_seed(seed);
    }
    let built = py.detach(|| -> Result<_, sphaera::Error> {
        let surface = Surface::solid_or_shell(&mesh.inner)?;
        let tree = build(&surface, &options)?;
        let evaluation = EvaluationOptions::level_report();
        // Nodes are stored level by level: a node's index less its level's first
        // index is its row.
        let mut first = 0_usize;
        let mut previous_first = 0_usize;
        let mut out = Vec::with_capacity(tree.level_count());
        for l in 0..tree.level_count() {
            let nodes = tree.level(l);
            let error = if evaluate && !nodes.is_empty() {
                // The level's cut certified as the CLI reports it.
                let level = evaluate_level(&surface, &tree, l, &evaluation)?;
                Some((level.worst_lower, level.worst_upper))
            } else {
                None
            };
            out.push(Level {
                spheres: nodes
                    .iter()
                    .flat_map(|n| {
                        let s = n.sphere;
                        [s.center.x, s.center.y, s.center.z, s.radius]
                    })
                    .collect(),
                parents: nodes
                    .iter()
                    .map(|n| {
                        n.parent.map_or(-1, |p| {
                            i64::from(p) - i64::try_from(previous_first).unwrap_or(0)
                        })
                    })
                    .collect(),
                node_errors: nodes.iter().map(|n| n.error).collect(),
                error,
            });
            previous_first = first;
            first += nodes.len();
        }
        let worst_leaf = tree
            .leaves()
            .iter()
            .map(|&i| tree.nodes()[i].error)
            .fold(0.0, f64::max);
        let tolerance = match goal {
            Goal::Tolerance(t) => Some(t.resolve(surface.diagonal())),
            _ => None,
        };
        Ok((
            out,
            surface.has_inside(),
            tree.branch(),
            tolerance,
            tolerance.map(|t| worst_leaf <= t),
        ))
    });
    let (levels, solid, tree_branch, tolerance, met) = built.map_err(|e| build_error(py, &e))?;
    let spheres = PyList::empty(py);
    let parents = PyList::empty(py);
    let node_errors = PyList::empty(py);
    let errors = PyList::empty(py);
    for level in levels {
        let array: Bound<'_, PyArray2<f64>> = arrays::rows(py, level.spheres, 4);
        spheres.append(array)?;
        let rows: Bound<'_, PyArray1<i64>> = arrays::vector(py, level.parents);
        parents.append(rows)?;
        let bounds: Bound<'_, PyArray1<f64>> = arrays::vector(py, level.node_errors);
        node_errors.append(bounds)?;
        errors.append(level.error)?;
    }
    Ok(SphereTree {
        levels: spheres.unbind(),
        parents: parents.unbind(),
        errors: errors.unbind(),
        method: chosen.name().to_owned(),
        branch: tree_branch,
        node_errors: Some(node_errors.unbind()),
        surface: if solid { "solid" } else { "shell" }.to_owned(),
        goal: goal.name().to_owned(),
        tolerance,
        met,
        effort: effort_level.name().to_owned(),
    })
}
