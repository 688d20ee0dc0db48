//! `sphaera.distance` (closest points, exact or certified intervals) and
//! `sphaera.hausdorff` (certified Hausdorff distances).

use numpy::{PyArray1, PyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple, PyType};
use sphaera::mesh::{DVec3, Length};
use sphaera::sweep::{Direction, HausdorffOptions, hausdorff as hausdorff_meshes};

use crate::arrays;
use crate::errors::{IntoPy, to_py};
use crate::mesh::Mesh;
use crate::simplify::length;

/// Distances from query points to a mesh: per point a certified interval
/// `lower ≤ d ≤ upper` (equal ends when exact), the nearest point found on the mesh and
/// its triangle.
#[pyclass(module = "sphaera", frozen, get_all)]
pub struct Distances {
    /// `(n,)` certified lower bounds.
    lower: Py<PyArray1<f64>>,
    /// `(n,)` certified upper bounds: the distance to `closest`.
    upper: Py<PyArray1<f64>>,
    /// `(n, 3)` the nearest point found on the mesh (the closest one when exact).
    closest: Py<PyArray2<f64>>,
    /// `(n,)` the triangle holding `closest`.
    triangle: Py<PyArray1<u32>>,
    /// The tolerance asked for (`None`: exact answers).
    tolerance: Option<f64>,
}

#[pymethods]
impl Distances {
    /// A result from its parts (what unpickling calls).
    #[new]
    fn new(
        lower: Py<PyArray1<f64>>,
        upper: Py<PyArray1<f64>>,
        closest: Py<PyArray2<f64>>,
        triangle: Py<PyArray1<u32>>,
        tolerance: Option<f64>,
    ) -> Self {
        Self {
            lower,
            upper,
            closest,
            triangle,
            tolerance,
        }
    }

    /// The distances: `upper`, exact when no tolerance was given.
    #[getter]
    fn distance(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        self.upper.clone_ref(py)
    }

    fn __len__(&self, py: Python<'_>) -> usize {
        PyUntypedArrayMethods::len(self.upper.bind(py))
    }

    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        dict.set_item("lower", &self.lower)?;
        dict.set_item("upper", &self.upper)?;
        dict.set_item("closest", &self.closest)?;
        dict.set_item("triangle", &self.triangle)?;
        dict.set_item("tolerance", self.tolerance)?;
        Ok(dict)
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let n = PyUntypedArrayMethods::len(self.upper.bind(py));
        match self.tolerance {
            None => format!("Distances({n} points, exact)"),
            Some(t) => format!("Distances({n} points, certified to {t:.3e})"),
        }
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyType>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let d = slf.get();
        let arguments = PyTuple::new(
            py,
            [
                d.lower.bind(py).clone().into_any(),
                d.upper.bind(py).clone().into_any(),
                d.closest.bind(py).clone().into_any(),
                d.triangle.bind(py).clone().into_any(),
                d.tolerance.into_pyobject(py)?.into_any(),
            ],
        )?;
        Ok((slf.get_type(), arguments))
    }
}

/// One query's answer: lower, upper, nearest point, its triangle.
type Answer = (f64, f64, DVec3, u32);

/// Distances from `points` (`(n, 3)`) to `mesh`: exact closest points, or with
/// `tolerance` (an absolute length or `"0.1%"` of the mesh's diagonal) certified
/// intervals at most that wide, found faster. Runs on every core with the GIL released.
///
/// Raises `ValueError` for points of another shape or not finite, or a mesh without
/// triangles.
#[pyfunction]
#[pyo3(signature = (mesh, points, tolerance=None))]
pub fn distance(
    py: Python<'_>,
    mesh: &Mesh,
    points: &Bound<'_, PyAny>,
    tolerance: Option<&Bound<'_, PyAny>>,
) -> PyResult<Distances> {
    let queries = arrays::points(points, "points", true)?;
    let tolerance = tolerance
        .map(|t| length(t).map(|l| l.resolve(mesh.inner.bounding_box_diagonal())))
        .transpose()?;
    let tree = mesh.tree()?;
    let answers: Vec<Answer> = py
        .detach(|| match tolerance {
            None => tree.closest_many(&queries).map(|closest| {
                closest
                    .into_iter()
                    .map(|c| (c.distance, c.distance, c.point, c.triangle))
                    .collect()
            }),
            Some(t) => tree.closest_approx_many(&queries, t).map(|answers| {
                answers
                    .into_iter()
                    .map(|a| (a.lower, a.upper, a.nearest.point, a.nearest.triangle))
                    .collect()
            }),
        })
        .map_err(|e| to_py(&e))?;
    let closest: Vec<DVec3> = answers.iter().map(|a| a.2).collect();
    Ok(Distances {
        lower: arrays::vector(py, answers.iter().map(|a| a.0).collect()).unbind(),
        upper: arrays::vector(py, answers.iter().map(|a| a.1).collect()).unbind(),
        closest: arrays::points_array(py, &closest).unbind(),
        triangle: arrays::vector(py, answers.iter().map(|a| a.3).collect()).unbind(),
        tolerance,
    })
}

/// A certified Hausdorff distance: `lower ≤ H ≤ upper`, where it is reached and per
/// direction the one-sided bounds.
#[pyclass(module = "sphaera", frozen, get_all)]
pub struct Hausdorff {
    /// A certified lower bound (the largest exact distance found at a sample).
    lower: f64,
    /// A certified upper bound.
    upper: f64,
    /// Where `lower` is reached, on the dominating direction's source mesh.
    farthest: (f64, f64, f64),
    /// Its closest point on the other mesh.
    closest: (f64, f64, f64),
    /// `"a_to_b"` or `"b_to_a"`: the direction where the maximum is reached.
    dominating: String,
    /// `(lower, upper)` of `h(A → B)`.
    a_to_b: (f64, f64),
    /// `(lower, upper)` of `h(B → A)`; `None` when one-sided.
    b_to_a: Option<(f64, f64)>,
    /// `False` when `max_samples` stopped the refinement first (the bounds still hold).
    converged: bool,
}

#[pymethods]
impl Hausdorff {
    /// A result from its parts (what unpickling calls).
    #[new]
    #[allow(clippy::too_many_arguments)]
    fn new(
        lower: f64,
        upper: f64,
        farthest: (f64, f64, f64),
        closest: (f64, f64, f64),
        dominating: String,
        a_to_b: (f64, f64),
        b_to_a: Option<(f64, f64)>,
        converged: bool,
    ) -> Self {
        Self {
            lower,
            upper,
            farthest,
            closest,
            dominating,
            a_to_b,
            b_to_a,
            converged,
        }
    }

    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        dict.set_item("lower", self.lower)?;
        dict.set_item("upper", self.upper)?;
        dict.set_item("farthest", self.farthest)?;
        dict.set_item("closest", self.closest)?;
        dict.set_item("dominating", &self.dominating)?;
        dict.set_item("a_to_b", self.a_to_b)?;
        dict.set_item("b_to_a", self.b_to_a)?;
        dict.set_item("converged", self.converged)?;
        Ok(dict)
    }

    fn __repr__(&self) -> String {
        format!(
            "Hausdorff(lower={:.9e}, upper={:.9e}, dominating={:?})",
            self.lower, self.upper, self.dominating
        )
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyType>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let h = slf.get();
        let arguments = PyTuple::new(
            py,
            [
                h.lower.into_pyobject(py)?.into_any(),
                h.upper.into_pyobject(py)?.into_any(),
                h.farthest.into_pyobject(py)?.into_any(),
                h.closest.into_pyobject(py)?.into_any(),
                h.dominating.clone().into_pyobject(py)?.into_any(),
                h.a_to_b.into_pyobject(py)?.into_any(),
                h.b_to_a.into_pyobject(py)?.into_any(),
                h.converged.into_pyobject(py)?.to_owned().into_any(),
            ],
        )?;
        Ok((slf.get_type(), arguments))
    }
}

fn tuple(p: DVec3) -> (f64, f64, f64) {
    (p.x, p.y, p.z)
}

/// The certified Hausdorff distance between meshes `a` and `b` (symmetric, or
/// `h(A → B)` with `symmetric=False`), refined until `upper − lower ≤ tolerance` (an
/// absolute length, or a string such as `"0.001%"` of both meshes' diagonal, the
/// default) or `max_samples` samples. Runs on every core with the GIL released.
///
/// Raises `ValueError` for a mesh without triangles or a bad tolerance.
#[pyfunction]
#[pyo3(signature = (a, b, tolerance=None, symmetric=true, max_samples=None))]
pub fn hausdorff(
    py: Python<'_>,
    a: &Mesh,
    b: &Mesh,
    tolerance: Option<&Bound<'_, PyAny>>,
    symmetric: bool,
    max_samples: Option<usize>,
) -> PyResult<Hausdorff> {
    let tolerance = match tolerance {
        Some(t) => length(t)?,
        None => Length::RelativeToDiagonal(1e-5),
    };
    let mut options = HausdorffOptions::default()
        .with_tolerance(tolerance)
        .with_symmetric(symmetric);
    if let Some(n) = max_samples {
        options = options.with_max_samples(n);
    }
    let result = py
        .detach(|| hausdorff_meshes(&a.inner, &b.inner, &options))
        .py_err()?;
    let side = result.dominating_side();
    Ok(Hausdorff {
        lower: result.lower,
        upper: result.upper,
        farthest: tuple(side.farthest),
        closest: tuple(side.closest),
        dominating: match result.dominating {
            Direction::AToB => "a_to_b",
            Direction::BToA => "b_to_a",
        }
        .to_owned(),
        a_to_b: (result.a_to_b.lower, result.a_to_b.upper),
        b_to_a: result.b_to_a.as_ref().map(|s| (s.lower, s.upper)),
        converged: result.converged,
    })
}
