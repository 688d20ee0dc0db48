//! The other capabilities: HAL approximations, silhouette labels, and URDF robots
//! spherized link by link. Their results are plain dicts of numpy arrays and numbers
//! (they pickle as such).

use std::path::PathBuf;

use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use sphaera::hal::HalTree3;
use sphaera::robot::{GeometrySource, MeshResolver, SphereBudget, SpherizeOptions, Urdf};
use sphaera::silhouette::{Contours, LabelOptions, Labels, ViewSet};

use crate::arrays;
use crate::errors::{IntoPy, value_error};
use crate::mesh::Mesh;
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
#[pyfunction]
#[pyo3(signature = (mesh, step_degrees=30.0, resolution=128, outline_only=true))]
pub fn silhouette_labels<'py>(
    py: Python<'py>,
    mesh: &Mesh,
    step_degrees: f64,
    resolution: usize,
    outline_only: bool,
) -> PyResult<LabelArrays<'py>> {
    let contours = if outline_only {
        Contours::External
    } else {
        Contours::All
    };
    let (labels, directions, vertices) = py
        .detach(|| -> Result<_, sphaera::silhouette::SilhouetteError> {
            let views = ViewSet::regular(step_degrees)?;
            let labels = Labels::compute(
                &mesh.inner,
                &views,
                &LabelOptions::default()
                    .with_resolution(resolution)
                    .with_contours(contours),
            )?;
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

/// A URDF robot spherized link by link, each link's spheres in its own frame with
/// coverage of its surface certified: `spheres_per_link` each (default 16), or `budget`
/// for the whole robot, or `tolerance` (no sphere protruding more than it, a length or
/// `"2%"` of each link), with per-link overrides in `per_link`; `visual` for the visual
/// geometry instead of the collision one; `packages` maps `package://` names to folders.
///
/// Returns a dict: `robot`, `links` (per link name: `spheres` an `(n, 4)` array and the
/// report's figures), `links_without_geometry`.
///
/// With `root`, the URDF and every mesh it names are read only inside that folder (once
/// links and `..` are resolved; a service reading uploads); `max_file_bytes` caps each file
/// (default 2 GiB). Only regular files are read.
///
/// Raises `PermissionError` (an `OSError`) for a file the policy refuses, `OSError` for a
/// URDF or mesh that cannot be read, `ValueError` for a malformed one (the messages name
/// the link and the file).
#[pyfunction]
#[pyo3(signature = (path, spheres_per_link=None, budget=None, tolerance=None, per_link=None, visual=false, packages=None, root=None, max_file_bytes=None))]
#[allow(clippy::too_many_arguments)]
pub fn urdf<'py>(
    py: Python<'py>,
    path: PathBuf,
    spheres_per_link: Option<usize>,
    budget: Option<usize>,
    tolerance: Option<&Bound<'_, PyAny>>,
    per_link: Option<std::collections::BTreeMap<String, usize>>,
    visual: bool,
    packages: Option<std::collections::BTreeMap<String, PathBuf>>,
    root: Option<PathBuf>,
    max_file_bytes: Option<u64>,
) -> PyResult<Bound<'py, PyDict>> {
    let policy = crate::mesh::file_policy(root, max_file_bytes);
    let chosen = [
        spheres_per_link.is_some(),
        budget.is_some(),
        tolerance.is_some(),
    ]
    .into_iter()
    .filter(|&b| b)
    .count();
    if chosen > 1 {
        return Err(value_error(
            "give one of spheres_per_link, budget and tolerance",
        ));
    }
    let budget = match (spheres_per_link, budget, tolerance) {
        (_, Some(total), _) => SphereBudget::Total(total),
        (_, _, Some(t)) => SphereBudget::Tolerance(length(t)?),
        (n, _, _) => SphereBudget::PerLink(n.unwrap_or(16)),
    };
    let mut options = SpherizeOptions::default()
        .with_budget(budget)
        .with_source(if visual {
            GeometrySource::Visual
        } else {
            GeometrySource::Collision
        });
    for (name, count) in per_link.unwrap_or_default() {
        options = options.with_link(name, count);
    }
    let robot = py
        .detach(move || -> Result<_, sphaera::robot::RobotError> {
            let urdf = Urdf::read_with(&path, &policy)?;
            let mut resolver = MeshResolver::new(urdf.folder()).with_policy(policy);
            for (name, folder) in packages.unwrap_or_default() {
                resolver = resolver.with_package(name, folder);
            }
            sphaera::robot::spherize(&urdf, &resolver, &options)
        })
        .py_err()?;
    let links = PyDict::new(py);
    for link in &robot.links {
        let entry = PyDict::new(py);
        let flat: Vec<f64> = link
            .spheres
            .iter()
            .flat_map(|s| [s.center.x, s.center.y, s.center.z, s.radius])
            .collect();
        entry.set_item("spheres", arrays::rows(py, flat, 4))?;
        let r = &link.report;
        entry.set_item("triangles", r.triangles)?;
        entry.set_item("worst_protrusion", r.worst_protrusion)?;
        entry.set_item("p95_protrusion", r.p95_protrusion)?;
        entry.set_item("coverage", r.coverage)?;
        entry.set_item("coverage_certified", r.coverage_certified)?;
        entry.set_item("seconds", r.seconds)?;
        links.set_item(&link.link, entry)?;
    }
    let out = PyDict::new(py);
    out.set_item("robot", &robot.robot)?;
    out.set_item("links", links)?;
    out.set_item(
        "links_without_geometry",
        PyList::new(py, &robot.links_without_geometry)?,
    )?;
    Ok(out)
}
