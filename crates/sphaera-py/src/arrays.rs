//! numpy arrays in and out: shapes and dtypes checked with messages that say what was
//! given.

use numpy::ndarray::Array2;
use numpy::{PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use sphaera::mesh::DVec3;
use sphaera::mesh::glam::DVec2;

use crate::errors::value_error;

/// `value` as a numpy array (`numpy.asarray`), with its dtype's kind (`f`, `i`, `u`, …).
fn as_array<'py>(value: &Bound<'py, PyAny>) -> PyResult<(Bound<'py, PyAny>, String)> {
    let array = value
        .py()
        .import("numpy")?
        .call_method1("asarray", (value,))?;
    let kind: String = array.getattr("dtype")?.getattr("kind")?.extract()?;
    Ok((array, kind))
}

/// The shape of a numpy array, for messages.
fn shape_of(array: &Bound<'_, PyAny>) -> String {
    array
        .getattr("shape")
        .and_then(|s| s.str().map(|s| s.to_string()))
        .unwrap_or_else(|_| "?".to_owned())
}

/// `value` (an array or nested lists) as an `(n, 3)` array of `T` (numpy's `dtype`),
/// when its dtype's kind is one of `kinds`; `None` when it is empty. `what` and `rows`
/// name it in messages (`vertices`, `n`).
fn three_columns<'py, T: numpy::Element>(
    value: &Bound<'py, PyAny>,
    kinds: &[&str],
    dtype: &str,
    what: &str,
    rows: &str,
) -> PyResult<Option<PyReadonlyArray2<'py, T>>> {
    columns(value, 3, kinds, dtype, what, rows)
}

/// [`three_columns`] with `count` columns.
fn columns<'py, T: numpy::Element>(
    value: &Bound<'py, PyAny>,
    count: usize,
    kinds: &[&str],
    dtype: &str,
    what: &str,
    rows: &str,
) -> PyResult<Option<PyReadonlyArray2<'py, T>>> {
    let (array, kind) = as_array(value)?;
    let size: usize = array.getattr("size")?.extract()?;
    if size == 0 {
        return Ok(None);
    }
    if !kinds.contains(&kind.as_str()) {
        let wanted = if dtype == "int64" {
            "integers"
        } else {
            "numbers"
        };
        return Err(value_error(format!(
            "{what} must be {wanted}, got dtype {}",
            array.getattr("dtype")?.str()?
        )));
    }
    let ndim: usize = array.getattr("ndim")?.extract()?;
    let array = array.call_method1("astype", (dtype,))?;
    match (ndim, array.extract::<PyReadonlyArray2<'py, T>>()) {
        (2, Ok(view)) if view.as_array().ncols() == count => Ok(Some(view)),
        _ => Err(value_error(format!(
            "{what} must have shape ({rows}, {count}), got {}",
            shape_of(&array)
        ))),
    }
}

/// An `(n, 3)` array of numbers (any real dtype, or nested lists) as points.
///
/// # Errors
///
/// `ValueError` naming `what` for another shape or dtype, or a coordinate that is not
/// finite (when `finite`).
pub fn points(value: &Bound<'_, PyAny>, what: &str, finite: bool) -> PyResult<Vec<DVec3>> {
    let Some(view) = three_columns::<f64>(value, &["f", "i", "u", "b"], "float64", what, "n")?
    else {
        return Ok(Vec::new());
    };
    let view = view.as_array();
    let mut out = Vec::with_capacity(view.nrows());
    for (i, row) in view.rows().into_iter().enumerate() {
        let p = DVec3::new(row[0], row[1], row[2]);
        if finite && !p.is_finite() {
            return Err(value_error(format!(
                "{what}: row {i} is not finite ({}, {}, {})",
                p.x, p.y, p.z
            )));
        }
        out.push(p);
    }
    Ok(out)
}

/// An `(n, 2)` array of numbers (any real dtype, or nested lists) as finite points of
/// the plane.
///
/// # Errors
///
/// `ValueError` naming `what` for another shape or dtype, or a coordinate that is not
/// finite.
pub fn points2(value: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<DVec2>> {
    let Some(view) = columns::<f64>(value, 2, &["f", "i", "u", "b"], "float64", what, "n")? else {
        return Ok(Vec::new());
    };
    let view = view.as_array();
    let mut out = Vec::with_capacity(view.nrows());
    for (i, row) in view.rows().into_iter().enumerate() {
        let p = DVec2::new(row[0], row[1]);
        if !p.is_finite() {
            return Err(value_error(format!(
                "{what}: row {i} is not finite ({}, {})",
                p.x, p.y
            )));
        }
        out.push(p);
    }
    Ok(out)
}

/// An `(m, 3)` array of integers (any integer dtype, or nested lists) as triangles of
/// `vertices` vertices.
///
/// # Errors
///
/// `ValueError` for another shape or dtype, a negative index or one past the vertices.
pub fn triangles(value: &Bound<'_, PyAny>, vertices: usize) -> PyResult<Vec<[u32; 3]>> {
    let Some(view) = three_columns::<i64>(value, &["i", "u"], "int64", "faces", "m")? else {
        return Ok(Vec::new());
    };
    let view = view.as_array();
    let mut out = Vec::with_capacity(view.nrows());
    for (t, row) in view.rows().into_iter().enumerate() {
        let mut triangle = [0_u32; 3];
        for (k, &index) in row.iter().enumerate() {
            match u32::try_from(index) {
                Ok(i) if (i as usize) < vertices => triangle[k] = i,
                _ => {
                    return Err(value_error(format!(
                        "face {t} has vertex index {index}, outside 0..{vertices}"
                    )));
                }
            }
        }
        out.push(triangle);
    }
    Ok(out)
}

/// Points as an `(n, 3)` `float64` array.
pub fn points_array<'py>(py: Python<'py>, points: &[DVec3]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = points.iter().flat_map(DVec3::to_array).collect();
    rows(py, flat, 3)
}

/// `flat` as an `(n, width)` array.
pub fn rows<'py, T: numpy::Element>(
    py: Python<'py>,
    flat: Vec<T>,
    width: usize,
) -> Bound<'py, PyArray2<T>> {
    let n = flat.len() / width.max(1);
    match Array2::from_shape_vec((n, width), flat) {
        Ok(array) => PyArray2::from_owned_array(py, array),
        // `n · width` is the length by construction.
        Err(_) => PyArray2::zeros(py, (0, width), false),
    }
}

/// A vector as a 1-D array.
pub fn vector<'py, T: numpy::Element>(py: Python<'py>, values: Vec<T>) -> Bound<'py, PyArray1<T>> {
    PyArray1::from_vec(py, values)
}
