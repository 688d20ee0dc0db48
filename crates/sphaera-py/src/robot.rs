//! URDF robots: spherized link by link with their self-collision matrix and planner files,
//! and their forward kinematics. Results are plain dicts of numpy arrays, numbers and
//! strings (they pickle as such).

use std::collections::BTreeMap;
use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use sphaera::mesh::glam::DMat4;
use sphaera::robot::{
    DisableReason, GeometrySource, MeshResolver, MjcfOptions, PlannerFormat, SelfCollisionOptions,
    SphereBudget, SpherizeOptions, Urdf,
};

use crate::arrays;
use crate::errors::{IntoPy, value_error};
use crate::simplify::length;

/// A URDF robot spherized link by link, each link's spheres in its own frame with
/// coverage of its surface certified: `spheres_per_link` each (default 16), or `budget`
/// for the whole robot, or `tolerance` (no sphere protruding more than it, a length or
/// `"2%"` of each link), with per-link overrides in `per_link`; `visual` for the visual
/// geometry instead of the collision one; `packages` maps `package://` names to folders.
///
/// The self-collision matrix is computed over `self_collision_samples` random joint
/// configurations (default 10,000; 0 keeps only the adjacent and default rules) drawn from
/// `seed`. With `format` (`"urdf"`, `"srdf"`, `"curobo"`, `"curobo-spheres"`, `"mjcf"`,
/// `"json"`), the planner file's text is returned too; `mjcf_meshes` adds the links' meshes
/// to the MJCF as visual geoms.
///
/// Returns a dict: `robot`, `links` (per link name: `spheres` an `(n, 4)` array and the
/// report's figures), `links_without_geometry`, `self_collision` (one dict per pair of
/// links with spheres: `first`, `second`, `reason` — `"Adjacent"`, `"Default"`,
/// `"Always"`, `"Never"`, or `None` when a planner must check it — and `contacts`), and
/// `text` when a format was asked for.
///
/// With `root`, the URDF and every mesh it names are read only inside that folder (once
/// links and `..` are resolved; a service reading uploads); `max_file_bytes` caps each file
/// (default 2 GiB). Only regular files are read.
///
/// Raises `PermissionError` (an `OSError`) for a file the policy refuses, `OSError` for a
/// URDF or mesh that cannot be read, `ValueError` for a malformed one (the messages name
/// the link and the file).
#[pyfunction]
#[pyo3(signature = (path, spheres_per_link=None, budget=None, tolerance=None, per_link=None, visual=false, packages=None, root=None, max_file_bytes=None, self_collision_samples=10_000, seed=0, format=None, mjcf_meshes=false))]
#[allow(clippy::too_many_arguments)]
pub fn urdf<'py>(
    py: Python<'py>,
    path: PathBuf,
    spheres_per_link: Option<usize>,
    budget: Option<usize>,
    tolerance: Option<&Bound<'_, PyAny>>,
    per_link: Option<BTreeMap<String, usize>>,
    visual: bool,
    packages: Option<BTreeMap<String, PathBuf>>,
    root: Option<PathBuf>,
    max_file_bytes: Option<u64>,
    self_collision_samples: usize,
    seed: u64,
    format: Option<String>,
    mjcf_meshes: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let format: Option<PlannerFormat> = format
        .map(|f| f.parse())
        .transpose()
        .map_err(|e: sphaera::mesh::ParseNameError| value_error(e.to_string()))?;
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
    let options = options.with_self_collision(
        SelfCollisionOptions::default()
            .with_samples(self_collision_samples)
            .with_seed(seed),
    );
    let source = options.source;
    let (robot, text) = py
        .detach(move || -> Result<_, sphaera::robot::RobotError> {
            let urdf = Urdf::read_with(&path, &policy)?;
            let mut resolver = MeshResolver::new(urdf.folder()).with_policy(policy);
            for (name, folder) in packages.unwrap_or_default() {
                resolver = resolver.with_package(name, folder);
            }
            let robot = sphaera::robot::spherize(&urdf, &resolver, &options)?;
            let text = match (format, &robot.self_collision) {
                (Some(PlannerFormat::Mjcf), Some(matrix)) if mjcf_meshes => {
                    let meshes = MjcfOptions::default().with_meshes(source, resolver);
                    Some(sphaera::robot::mjcf(&urdf, &robot, matrix, &meshes)?)
                }
                (Some(format), _) => Some(format.render(&urdf, &robot)?),
                (None, _) => None,
            };
            Ok((robot, text))
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
    let pairs = PyList::empty(py);
    for pair in robot.self_collision.iter().flat_map(|m| &m.pairs) {
        let entry = PyDict::new(py);
        entry.set_item("first", &pair.first)?;
        entry.set_item("second", &pair.second)?;
        entry.set_item("reason", pair.reason.map(DisableReason::name))?;
        entry.set_item("contacts", pair.contacts)?;
        pairs.append(entry)?;
    }
    out.set_item("self_collision", pairs)?;
    if let Some(text) = text {
        out.set_item("text", text)?;
    }
    Ok(out)
}

/// The pose of every link's frame in the root link's frame, as a `(4, 4)` array per link
/// name, for the joint values in `joints` (radians or metres by joint name; a joint not
/// named is at 0; a mimic joint follows the joint it copies). `root` and `max_file_bytes`
/// as for [`urdf`].
///
/// Raises `ValueError` for a joint the robot does not have or a value that is not finite,
/// and as [`urdf`] for the file.
#[pyfunction]
#[pyo3(signature = (path, joints=None, root=None, max_file_bytes=None))]
pub fn link_poses<'py>(
    py: Python<'py>,
    path: PathBuf,
    joints: Option<BTreeMap<String, f64>>,
    root: Option<PathBuf>,
    max_file_bytes: Option<u64>,
) -> PyResult<Bound<'py, PyDict>> {
    let policy = crate::mesh::file_policy(root, max_file_bytes);
    let poses = py
        .detach(move || -> Result<_, sphaera::robot::RobotError> {
            Urdf::read_with(&path, &policy)?.link_poses(&joints.unwrap_or_default())
        })
        .py_err()?;
    let out = PyDict::new(py);
    for (link, pose) in poses {
        let matrix = DMat4::from(pose).transpose().to_cols_array().to_vec();
        out.set_item(link, arrays::rows(py, matrix, 4))?;
    }
    Ok(out)
}
