//! The other capabilities: HAL approximations and silhouette labels. Their results are
//! numpy arrays and numbers (they pickle as such).

use std::path::PathBuf;

use numpy::PyArray2;
use pyo3::prelude::*;
use sphaera::hal::HalTree3;
use sphaera::silhouette::{Contours, LabelOptions, Labels, ViewSet};

use crate::arrays;
use crate::errors::IntoPy;
use crate::mesh::{Mesh, file_policy};
use crate::simplify::length;

/// The HAL tree's approximation of a closed genus-0 mesh (Veltkamp): with `tolerance`
/// (an absolute width or `"1%"` of the diagonal) the adaptive one whose lenses are at
/// most that wide, else `level`'s (default: the root level). Returns `(mesh, depth)`,
/// the tree's depth beside the approximation.
///
/// Raises `ValueError` for a mesh that is not closed, manifold, one piece and genus 0.
#[pyfunction]
#[pyo3(signature = (mesh, tolerance=None, level=0))]
pub fn hal(
    py: Python<'_>,
    mesh: &Mesh,
    tolerance: Option<&Bound<'_, PyAny>>,
    level: u32,
) -> PyResult<(Mesh, u32)> {
    let width = tolerance
        .map(|t| length(t).map(|l| l.resolve(mesh.inner.bounding_box_diagonal())))
        .transpose()?;
    let (approximation, depth) = py
        .detach(|| -> Result<_, sphaera::hal::HalError> {
            let tree = HalTree3::build(&mesh.inner)?;
            let approximation = match width {
                Some(w) => tree.approximate(w)?,
                None => tree.level(level)?,
            };
            Ok((approximation, tree.depth()))
        })
        .py_err()?;
    Ok((Mesh::from_inner(approximation), depth))
}

/// The labels `(views, vertices)` and the views' directions `(views, 3)`.
type LabelArrays<'py> = (Bound<'py, PyArray2<f32>>, Bound<'py, PyArray2<f64>>);

/// Silhouette labels (Mata, Pastor, Rodríguez) of every view of the regular set every
/// `step_degrees` (which must divide 180): per view and vertex, the distance in cells of a
/// `resolution²` grid from the outline that view sees (`outline_only`, the default) or
/// from every silhouette. Returns `(labels, directions)`: a `(views, vertices)` float32
/// array and a `(views, 3)` array of unit directions toward each camera.
///
/// With `labels_file`, the labels are kept in that label file: when it exists it is read
/// instead of labelling (only a regular file of at most `max_bytes` bytes, default 2 GiB,
/// and with `root` only inside that folder), and it must hold this mesh's labels computed
/// with these settings; when it does not, the labels are computed and written to it
/// (atomically) for the next call.
///
/// Raises `ValueError` for bad settings, a label file of another mesh or of other settings
/// (the message names the setting), or a damaged one; `PermissionError` (an `OSError`)
/// for a file the policy refuses; `OSError` when it cannot be read or written.
#[pyfunction]
#[pyo3(signature = (
    mesh,
    step_degrees=30.0,
    resolution=128,
    outline_only=true,
    labels_file=None,
    root=None,
    max_bytes=None,
))]
#[allow(clippy::too_many_arguments)]
pub fn silhouette_labels<'py>(
    py: Python<'py>,
    mesh: &Mesh,
    step_degrees: f64,
    resolution: usize,
    outline_only: bool,
    labels_file: Option<PathBuf>,
    root: Option<PathBuf>,
    max_bytes: Option<u64>,
) -> PyResult<LabelArrays<'py>> {
    let contours = if outline_only {
        Contours::External
    } else {
        Contours::All
    };
    let (labels, directions, vertices) = py
        .detach(move || -> Result<_, sphaera::silhouette::SilhouetteError> {
            let views = ViewSet::regular(step_degrees)?;
            let options = LabelOptions::default()
                .with_resolution(resolution)
                .with_contours(contours);
            let labels = match &labels_file {
                Some(path) if path.exists() => {
                    let policy = file_policy(root, max_bytes);
                    let labels = Labels::load_with(path, &mesh.inner, &policy)?;
                    labels.check_settings(&views, &options)?;
                    labels
                }
                _ => {
                    let labels = Labels::compute(&mesh.inner, &views, &options)?;
                    if let Some(path) = &labels_file {
                        labels.save(&mesh.inner, path)?;
                    }
                    labels
                }
            };
            let flat: Vec<f32> = (0..views.len()).flat_map(|k| labels.view(k)).collect();
            let directions: Vec<_> = (0..views.len())
                .map(|k| views.direction(k).normalize())
                .collect();
            Ok((flat, directions, labels.vertex_count()))
        })
        .py_err()?;
    Ok((
        arrays::rows(py, labels, vertices),
        arrays::points_array(py, &directions),
    ))
}
