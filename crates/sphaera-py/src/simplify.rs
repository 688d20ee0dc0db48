//! `sphaera.simplify`: edge collapses with error spheres, the bound certified.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple, PyType};
use sphaera::mesh::Length;
use sphaera::simplify::{SimplifyOptions, simplify as simplify_mesh};

use crate::errors::{IntoPy, value_error};
use crate::mesh::Mesh;

/// A simplified mesh and its certified error bound: every point of either surface lies
/// within `error_bound` of the other.
#[pyclass(module = "sphaera", frozen, get_all)]
pub struct Simplified {
    /// The simplified mesh.
    mesh: Py<Mesh>,
    /// The certified bound, in the mesh's units.
    error_bound: f64,
    /// Edge collapses made.
    collapses: usize,
}

#[pymethods]
impl Simplified {
    /// A result from its parts (what unpickling calls).
    #[new]
    fn new(mesh: Py<Mesh>, error_bound: f64, collapses: usize) -> Self {
        Self {
            mesh,
            error_bound,
            collapses,
        }
    }

    /// `{"mesh": {...}, "error_bound": ..., "collapses": ...}`.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        dict.set_item("mesh", self.mesh.bind(py).call_method0("to_dict")?)?;
        dict.set_item("error_bound", self.error_bound)?;
        dict.set_item("collapses", self.collapses)?;
        Ok(dict)
    }

    fn __repr__(&self) -> String {
        format!(
            "Simplified({} triangles, error_bound={:.6e}, collapses={})",
            self.mesh.get().inner.triangle_count(),
            self.error_bound,
            self.collapses
        )
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyType>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let s = slf.get();
        let arguments = PyTuple::new(
            py,
            [
                s.mesh.clone_ref(py).into_any().into_bound(py),
                s.error_bound.into_pyobject(py)?.into_any(),
                s.collapses.into_pyobject(py)?.into_any(),
            ],
        )?;
        Ok((slf.get_type(), arguments))
    }
}

/// Simplifies `mesh` by edge collapses until `ratio` of its triangles remain (default
/// 0.1), or, with `max_error`, as far as the certified bound stays within it (an
/// absolute length, or a string such as `"1%"` of the bounding-box diagonal). Both may
/// be given: the first reached stops. The GIL is released while it runs.
///
/// Raises `ValueError` for a ratio outside (0, 1] or a mesh the simplifier refuses.
#[pyfunction]
#[pyo3(signature = (mesh, ratio=None, max_error=None))]
pub fn simplify(
    py: Python<'_>,
    mesh: &Mesh,
    ratio: Option<f64>,
    max_error: Option<&Bound<'_, PyAny>>,
) -> PyResult<Simplified> {
    let mut options = SimplifyOptions::default();
    if let Some(ratio) = ratio {
        if !(ratio > 0.0 && ratio <= 1.0) {
            return Err(value_error(format!(
                "ratio must lie in (0, 1], got {ratio}"
            )));
        }
        options = options.with_target_ratio(ratio);
    } else if max_error.is_none() {
        options = options.with_target_ratio(0.1);
    }
    if let Some(bound) = max_error {
        options = options.with_max_error(length(bound)?);
        if ratio.is_none() {
            options = options.with_target_triangles(1);
        }
    }
    let result = py
        .detach(|| simplify_mesh(&mesh.inner, &options))
        .py_err()?;
    Ok(Simplified {
        mesh: Py::new(py, Mesh::from_inner(result.mesh))?,
        error_bound: result.error_bound,
        collapses: result.collapses,
    })
}

/// A length argument: a number (absolute) or a string `"2%"` (of the diagonal) or
/// `"0.01"`.
pub fn length(value: &Bound<'_, PyAny>) -> PyResult<Length> {
    if let Ok(number) = value.extract::<f64>() {
        return if number.is_finite() && number >= 0.0 {
            Ok(Length::Absolute(number))
        } else {
            Err(value_error(format!(
                "a length must be finite and not negative, got {number}"
            )))
        };
    }
    let text: String = value.extract().map_err(|_| {
        value_error("a length is a number or a string such as \"1%\" of the diagonal")
    })?;
    text.parse()
        .map_err(|e: sphaera::mesh::ParseLengthError| value_error(e.to_string()))
}
