//! A link's geometry in the link's own frame: its meshes (loaded, scaled and placed by
//! their `<origin>`, joined into one mesh) and its primitives.

use std::path::PathBuf;

use glam::{DAffine3, DVec3};
use sphaera_io::FilePolicy;
use sphaera_mesh::TriMesh;

use crate::RobotError;
use crate::primitive::{Primitive, Shape};
use crate::urdf::{Element, Geometry, Link, Urdf};

/// Which geometry of the links to use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum GeometrySource {
    /// The `<collision>` elements (the default: what planners check).
    #[default]
    Collision,
    /// The `<visual>` elements (finer meshes, when the collision meshes are too crude).
    Visual,
}

impl GeometrySource {
    /// The elements of `link` this source takes.
    #[must_use]
    pub fn elements(self, link: &Link) -> &[Element] {
        match self {
            Self::Collision => &link.collisions,
            Self::Visual => &link.visuals,
        }
    }

    /// `collision` or `visual`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Collision => "collision",
            Self::Visual => "visual",
        }
    }
}

/// Where `package://` mesh paths are looked for.
///
/// `package://NAME/REST` is tried, in order: under a folder given for `NAME`
/// ([`MeshResolver::with_package`]); as `NAME/REST` under the URDF's folder (robots
/// shipped with their meshes beside them, as `package://meshes/…`); as `REST` under the
/// URDF's folder; and as `REST` under every ancestor of the URDF's folder called `NAME`
/// (a ROS package the URDF lives in). `file://` paths are taken as they are; any other
/// path is relative to the URDF's folder. Every candidate is read by the resolver's
/// [`FilePolicy`] ([`MeshResolver::with_policy`]; by default regular files of any folder,
/// at most [`DEFAULT_MAX_FILE_BYTES`](sphaera_io::DEFAULT_MAX_FILE_BYTES) each): a service
/// gives it a root, outside which no candidate is read.
///
/// # Examples
///
/// ```
/// use std::path::Path;
/// use sphaera_robot::MeshResolver;
///
/// let resolver = MeshResolver::new("/robots/panda");
/// let tried = resolver.candidates("package://meshes/link0.obj");
/// assert_eq!(tried[0], Path::new("/robots/panda/meshes/link0.obj"));
/// assert_eq!(resolver.candidates("meshes/link0.stl")[0], Path::new("/robots/panda/meshes/link0.stl"));
/// ```
#[derive(Clone, Debug, Default)]
pub struct MeshResolver {
    folder: PathBuf,
    packages: Vec<(String, PathBuf)>,
    policy: FilePolicy,
}

impl MeshResolver {
    /// Resolves against the URDF folder `folder`.
    pub fn new(folder: impl Into<PathBuf>) -> Self {
        Self {
            folder: folder.into(),
            packages: Vec::new(),
            policy: FilePolicy::default(),
        }
    }

    /// Reads mesh files by `policy` only (a root for a service, a size cap).
    #[must_use]
    pub fn with_policy(mut self, policy: FilePolicy) -> Self {
        self.policy = policy;
        self
    }

    /// The policy mesh files are read by.
    #[must_use]
    pub fn policy(&self) -> &FilePolicy {
        &self.policy
    }

    /// Also looks for `package://name/…` under `folder`, first.
    #[must_use]
    pub fn with_package(mut self, name: impl Into<String>, folder: impl Into<PathBuf>) -> Self {
        self.packages.push((name.into(), folder.into()));
        self
    }

    /// The paths `uri` may name, in the order they are tried. A `package://` or
    /// `file://` URI with percent-escapes (`%20`) is tried as written, then decoded, as
    /// ROS's resource retriever reads it.
    #[must_use]
    pub fn candidates(&self, uri: &str) -> Vec<PathBuf> {
        let mut paths = self.candidates_as_written(uri);
        let is_uri = uri.starts_with("package://") || uri.starts_with("file://");
        let decoded = sphaera_io::percent_decode(uri).and_then(|d| String::from_utf8(d).ok());
        if let Some(decoded) = decoded.filter(|d| is_uri && d != uri) {
            for path in self.candidates_as_written(&decoded) {
                if !paths.contains(&path) {
                    paths.push(path);
                }
            }
        }
        paths
    }

    fn candidates_as_written(&self, uri: &str) -> Vec<PathBuf> {
        if let Some(rest) = uri.strip_prefix("package://") {
            if rest.is_empty() {
                // `package://` alone names no file: nothing to try.
                return Vec::new();
            }
            let (package, inner) = rest.split_once('/').unwrap_or((rest, ""));
            let mut paths: Vec<PathBuf> = self
                .packages
                .iter()
                .filter(|(name, _)| name == package)
                .map(|(_, folder)| folder.join(inner))
                .collect();
            paths.push(self.folder.join(rest));
            if !inner.is_empty() {
                paths.push(self.folder.join(inner));
                paths.extend(
                    self.folder
                        .ancestors()
                        .filter(|a| a.file_name().is_some_and(|n| n == package))
                        .map(|a| a.join(inner)),
                );
            }
            paths.dedup();
            paths
        } else if let Some(path) = uri.strip_prefix("file://") {
            vec![PathBuf::from(path)]
        } else {
            vec![self.folder.join(uri)]
        }
    }

    /// The first candidate the policy reads.
    ///
    /// # Errors
    ///
    /// [`RobotError::MeshNotFound`] naming `link`, the URI and every path tried, when no
    /// candidate exists; [`RobotError::Mesh`] with the policy's refusal when candidates
    /// exist but none may be read (a folder, a device, outside the root, too large).
    pub fn resolve(&self, link: &str, uri: &str) -> Result<PathBuf, RobotError> {
        let candidates = self.candidates(uri);
        let mut refused = None;
        for path in &candidates {
            match self.policy.check_file(path) {
                Ok(_) => return Ok(path.clone()),
                Err(sphaera_io::IoError::Io { .. }) => {}
                Err(error) => {
                    refused.get_or_insert((path.clone(), error));
                }
            }
        }
        Err(match refused {
            Some((path, error)) => RobotError::Mesh {
                link: link.to_owned(),
                path,
                source: Box::new(error),
            },
            None => RobotError::MeshNotFound {
                link: link.to_owned(),
                uri: uri.to_owned(),
                tried: candidates,
            },
        })
    }
}

/// One link's geometry, in the link's frame.
#[derive(Clone, Debug)]
pub struct LinkGeometry {
    /// The link.
    pub link: String,
    /// Its mesh elements, scaled, placed and joined (`None` without any).
    pub mesh: Option<TriMesh>,
    /// The mesh files it was read from, in element order.
    pub files: Vec<PathBuf>,
    /// Its primitive elements (box, cylinder, sphere, capsule), placed.
    pub primitives: Vec<Primitive>,
}

impl LinkGeometry {
    /// Whether the link has no geometry of the chosen kind.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.mesh.is_none() && self.primitives.is_empty()
    }

    /// The total surface area: the meshes' and the primitives'.
    #[must_use]
    pub fn area(&self) -> f64 {
        self.mesh.as_ref().map_or(0.0, TriMesh::surface_area)
            + self.primitives.iter().map(Primitive::area).sum::<f64>()
    }

    /// Triangles of the meshes (a primitive counts as 12: the simplest mesh).
    #[must_use]
    pub fn triangles(&self) -> usize {
        self.mesh.as_ref().map_or(0, TriMesh::triangle_count) + 12 * self.primitives.len()
    }

    /// The diagonal of the box around the whole geometry.
    #[must_use]
    pub fn diagonal(&self) -> f64 {
        let mut points: Vec<DVec3> = self
            .mesh
            .as_ref()
            .map(|m| m.positions().to_vec())
            .unwrap_or_default();
        for p in &self.primitives {
            points.extend(p.box_corners());
        }
        let (lo, hi) = points.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        if points.is_empty() {
            0.0
        } else {
            (hi - lo).length()
        }
    }

    /// Loads the geometry of `link` from `source`: every mesh element resolved, loaded,
    /// scaled and placed by its origin (a mirroring scale flips the triangles, so the
    /// inside stays inside), joined into one mesh; every primitive placed.
    ///
    /// # Errors
    ///
    /// [`RobotError::MeshNotFound`] for a file found nowhere, [`RobotError::Mesh`] for a
    /// file that cannot be loaded (an unknown format, malformed, no triangles), naming
    /// the link and the file.
    pub fn load(
        link: &Link,
        source: GeometrySource,
        resolver: &MeshResolver,
    ) -> Result<Self, RobotError> {
        let mut positions: Vec<DVec3> = Vec::new();
        let mut triangles: Vec<[u32; 3]> = Vec::new();
        let mut files = Vec::new();
        let mut primitives = Vec::new();
        for element in source.elements(link) {
            let pose = element.origin.affine();
            let shape = match &element.geometry {
                Geometry::Mesh { filename, scale } => {
                    let path = resolver.resolve(&link.name, filename)?;
                    let mesh = sphaera_io::read_with(&path, resolver.policy())
                        .map(|loaded| loaded.mesh)
                        .map_err(|source| RobotError::Mesh {
                            link: link.name.clone(),
                            path: path.clone(),
                            source: Box::new(source),
                        })?;
                    // A file of no triangles (an STL of only its header) must not drop
                    // the link silently: a planner would never see it.
                    if mesh.triangle_count() == 0 {
                        return Err(RobotError::Mesh {
                            link: link.name.clone(),
                            path,
                            source: Box::new(sphaera_mesh::MeshError::EmptyMesh.into()),
                        });
                    }
                    append(&mut positions, &mut triangles, &mesh, pose, *scale).map_err(
                        |source| RobotError::Mesh {
                            link: link.name.clone(),
                            path: path.clone(),
                            source: Box::new(source.into()),
                        },
                    )?;
                    files.push(path);
                    continue;
                }
                Geometry::Box { size } => Shape::Box { half: 0.5 * *size },
                Geometry::Cylinder { radius, length } => Shape::Cylinder {
                    radius: *radius,
                    half_length: 0.5 * length,
                },
                Geometry::Capsule { radius, length } => Shape::Capsule {
                    radius: *radius,
                    half_length: 0.5 * length,
                },
                Geometry::Sphere { radius } => Shape::Sphere { radius: *radius },
            };
            primitives.push(Primitive::new(shape, pose));
        }
        let mesh = if triangles.is_empty() {
            None
        } else {
            Some(
                TriMesh::new(positions, triangles).map_err(|source| RobotError::Mesh {
                    link: link.name.clone(),
                    path: files.last().cloned().unwrap_or_default(),
                    source: Box::new(source.into()),
                })?,
            )
        };
        Ok(Self {
            link: link.name.clone(),
            mesh,
            files,
            primitives,
        })
    }

    /// The geometry of every link of `urdf` from `source`, in link order (empty for a
    /// link without any), mesh paths resolved from the URDF's folder.
    ///
    /// # Errors
    ///
    /// As [`LinkGeometry::load`], for the first link in file order that fails.
    pub fn load_all(
        urdf: &Urdf,
        source: GeometrySource,
        resolver: &MeshResolver,
    ) -> Result<Vec<Self>, RobotError> {
        urdf.links
            .iter()
            .map(|link| Self::load(link, source, resolver))
            .collect()
    }
}

/// Appends `mesh` mapped by `pose · scale` to the joined mesh.
fn append(
    positions: &mut Vec<DVec3>,
    triangles: &mut Vec<[u32; 3]>,
    mesh: &TriMesh,
    pose: DAffine3,
    scale: DVec3,
) -> Result<(), sphaera_mesh::MeshError> {
    let map = pose * DAffine3::from_scale(scale);
    let mirrored = scale.x * scale.y * scale.z < 0.0;
    let offset =
        u32::try_from(positions.len()).map_err(|_| sphaera_mesh::MeshError::TooManyVertices {
            count: positions.len(),
        })?;
    positions.extend(mesh.positions().iter().map(|&p| map.transform_point3(p)));
    triangles.extend(mesh.triangles().iter().map(|&[a, b, c]| {
        let t = [a + offset, b + offset, c + offset];
        if mirrored { [t[0], t[2], t[1]] } else { t }
    }));
    Ok(())
}
