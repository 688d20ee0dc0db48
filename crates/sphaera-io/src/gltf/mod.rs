//! glTF 2.0 reader: `.gltf` (JSON, with `data:` URIs or separate buffer files) and `.glb`
//! (binary container with the buffer in its binary chunk).
//!
//! **What is read.** Every triangle primitive (`TRIANGLES`, `TRIANGLE_STRIP`,
//! `TRIANGLE_FAN`) of every mesh that the nodes of the default scene draw (the first scene
//! when `scene` is not set), placed by the node's world transform (the product of the
//! `matrix` or translation × rotation × scale of the node and of its ancestors), all merged
//! into one mesh in depth-first node order, each primitive with its own vertices (a mesh
//! drawn by two nodes appears twice). A file without scenes gives every mesh once,
//! untransformed. Strips and fans become separate triangles with the glTF winding rules;
//! primitives without indices take their vertices in order. A transform that mirrors
//! (negative determinant) reverses the winding of its triangles, so outward faces stay
//! outward. When the world transform is exactly the identity, positions are copied
//! bit-exactly.
//!
//! **What is skipped.** Points and lines primitives (counted in
//! [`LoadReport::primitives_skipped`](super::LoadReport::primitives_skipped)), normals,
//! texture coordinates, materials, images, cameras, animations, skins and morph targets
//! (the base positions are placed by the node transforms, not posed by a skin).
//! Extensions that only change appearance (`KHR_materials_*`, `KHR_texture_*`,
//! `EXT_texture_*`, `KHR_lights_*`, `KHR_xmp*`) are ignored even when required.
//!
//! **Handled details.** Sparse accessors, interleaved buffer views, accessors without a
//! buffer view (zeros), and integer positions, normalized or not
//! (`KHR_mesh_quantization`). Every other *required* extension (Draco or meshopt
//! compression, GPU instancing...) is refused with
//! [`ParseReason::UnsupportedExtension`], since reading the file without it would give
//! wrong geometry.
//!
//! **Errors** name the glTF object at fault ([`GltfObject`]): a mesh primitive for its
//! accessors (out of bounds, wrong type, missing `POSITION`, vertex index out of range,
//! NaN or infinite position), a node for its transform, a buffer for its data (file
//! missing, shorter than its `byteLength`, bad `data:` URI), the byte offset for the GLB
//! container and the JSON line and column for malformed JSON. Nothing in the file is used
//! before it is checked, so no input makes the reader panic: the `gltf` crate provides the
//! JSON schema types only, and the reader follows every index and offset itself.

mod accessor;
mod buffers;
mod container;
#[cfg(test)]
mod error_tests;
#[cfg(test)]
pub(crate) mod test_writer;
#[cfg(test)]
mod tests;

use std::path::Path;

use ::gltf::json::{
    self,
    mesh::{Mode, Semantic},
    validation::Checked,
};
use glam::{DMat3, DMat4, DQuat, DVec3, DVec4};

use super::builder::{MeshBuilder, finite_point};
use super::{Format, GltfObject, LoadedMesh, Location, ParseReason};
use crate::{FilePolicy, IoError};
use buffers::Buffers;
use sphaera_mesh::TriMesh;

/// A glTF parse error at `location`.
pub(super) fn error(location: Location, reason: ParseReason) -> IoError {
    IoError::Parse {
        path: None,
        format: Format::Gltf,
        location,
        reason,
    }
}

/// Required extensions this reader implements.
const SUPPORTED_EXTENSIONS: &[&str] = &["KHR_mesh_quantization"];

/// Prefixes of extensions that change only how a mesh looks, never its geometry.
const APPEARANCE_EXTENSIONS: &[&str] = &[
    "KHR_materials_",
    "KHR_texture_",
    "EXT_texture_",
    "KHR_lights_",
    "KHR_xmp",
];

/// Reads glTF data; buffer files are resolved against `base` (the glTF file's folder), or
/// refused when `base` is `None`.
pub(crate) fn read_gltf(
    bytes: &[u8],
    base: Option<(&Path, &FilePolicy)>,
) -> Result<LoadedMesh, IoError> {
    let container = container::split(bytes)?;
    let root = container::parse_json(container.json)?;
    check_document(&root)?;
    let mut reader = Reader {
        root: &root,
        buffers: Buffers::new(&root, container.bin, base),
        meshes: (0..root.meshes.len()).map(|_| None).collect(),
        positions: Vec::new(),
        triangles: Vec::new(),
        primitives_read: 0,
        primitives_skipped: 0,
        mirrored_primitives: 0,
    };
    let instances = reader.instances()?;
    reader.check_vertex_count(&instances)?;
    for instance in instances {
        reader.place(instance.mesh, instance.world_from_mesh, instance.at)?;
    }
    reader.finish()
}

/// Refuses glTF 1.x and required extensions that change the geometry.
fn check_document(root: &json::Root) -> Result<(), IoError> {
    let at = Location::Gltf(GltfObject::Document);
    let version = &root.asset.version;
    if version.split('.').next() != Some("2") {
        return Err(error(
            at,
            ParseReason::UnsupportedVersion {
                version: super::parse_error::token_text(version.as_bytes()),
            },
        ));
    }
    for name in &root.extensions_required {
        let known = SUPPORTED_EXTENSIONS.contains(&name.as_str())
            || APPEARANCE_EXTENSIONS
                .iter()
                .any(|prefix| name.starts_with(prefix));
        if !known {
            return Err(error(
                at,
                ParseReason::UnsupportedExtension {
                    name: super::parse_error::token_text(name.as_bytes()),
                },
            ));
        }
    }
    Ok(())
}

/// One primitive of a mesh, read once and placed by every node that draws the mesh.
enum Geometry {
    /// A triangle primitive: its positions and triangles (indices into its positions).
    Triangles {
        positions: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
    },
    /// A points or lines primitive.
    Skipped,
}

/// A mesh drawn by a node.
struct Instance {
    mesh: usize,
    world_from_mesh: DMat4,
    /// The node that draws it (or the top level), where errors point.
    at: Location,
}

/// The state of one read: the document, its buffers, the meshes read so far and the
/// merged output.
struct Reader<'r, 'a> {
    root: &'r json::Root,
    buffers: Buffers<'a>,
    /// Each mesh's primitives, once read.
    meshes: Vec<Option<Vec<Geometry>>>,
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    primitives_read: usize,
    primitives_skipped: usize,
    mirrored_primitives: usize,
}

impl Reader<'_, '_> {
    /// The meshes drawn by the default (or first) scene, in depth-first node order with
    /// their world transforms, or every mesh once when the file has no scene.
    fn instances(&self) -> Result<Vec<Instance>, IoError> {
        let root = self.root;
        let document = Location::Gltf(GltfObject::Document);
        let scene = match root.scene {
            Some(scene) => Some(scene.value()),
            None => (!root.scenes.is_empty()).then_some(0),
        };
        let Some(scene) = scene else {
            return Ok((0..root.meshes.len())
                .map(|mesh| Instance {
                    mesh,
                    world_from_mesh: DMat4::IDENTITY,
                    at: document,
                })
                .collect());
        };
        let roots = &root
            .scenes
            .get(scene)
            .ok_or_else(|| {
                error(
                    document,
                    ParseReason::DanglingReference {
                        kind: "scene",
                        index: scene,
                        available: root.scenes.len(),
                    },
                )
            })?
            .nodes;
        let at_scene = Location::Gltf(GltfObject::Scene(scene));
        let mut reached = vec![false; root.nodes.len()];
        let mut instances = Vec::new();
        // Depth first, in document order: (node, world_from_parent, who refers to it).
        let mut stack: Vec<(usize, DMat4, Location)> = roots
            .iter()
            .rev()
            .map(|node| (node.value(), DMat4::IDENTITY, at_scene))
            .collect();
        while let Some((index, world_from_parent, referrer)) = stack.pop() {
            let dangling = || {
                error(
                    referrer,
                    ParseReason::DanglingReference {
                        kind: "node",
                        index,
                        available: root.nodes.len(),
                    },
                )
            };
            let node = root.nodes.get(index).ok_or_else(dangling)?;
            let seen = reached.get_mut(index).ok_or_else(dangling)?;
            if *seen {
                return Err(error(
                    at_scene,
                    ParseReason::NodeReachedTwice { node: index },
                ));
            }
            *seen = true;
            let at_node = Location::Gltf(GltfObject::Node(index));
            let parent_from_node =
                local_transform(node).map_err(|reason| error(at_node, reason))?;
            let world_from_node = world_from_parent * parent_from_node;
            if let Some(mesh) = node.mesh {
                instances.push(Instance {
                    mesh: mesh.value(),
                    world_from_mesh: world_from_node,
                    at: at_node,
                });
            }
            for child in node.children.iter().flatten().rev() {
                stack.push((child.value(), world_from_node, at_node));
            }
        }
        Ok(instances)
    }

    /// Refuses, before any data are read, instances whose vertices (by their accessors'
    /// counts) are more than [`super::MAX_PLACED_VERTICES`]: instancing multiplies a
    /// file's vertices.
    fn check_vertex_count(&self, instances: &[Instance]) -> Result<(), IoError> {
        let root = self.root;
        let mut total = 0u64;
        for instance in instances {
            let Some(mesh) = root.meshes.get(instance.mesh) else {
                continue;
            };
            for primitive in &mesh.primitives {
                let triangles = matches!(
                    primitive.mode,
                    Checked::Valid(Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan)
                );
                let count = primitive
                    .attributes
                    .get(&Checked::Valid(Semantic::Positions))
                    .and_then(|accessor| root.accessors.get(accessor.value()))
                    .map_or(0, |accessor| accessor.count.0);
                if triangles {
                    total = total.saturating_add(count);
                }
            }
            if total > super::MAX_PLACED_VERTICES {
                return Err(error(
                    instance.at,
                    ParseReason::TooManyPlacedVertices {
                        count: total,
                        limit: super::MAX_PLACED_VERTICES,
                    },
                ));
            }
        }
        Ok(())
    }

    /// Appends every primitive of mesh `mesh`, placed by `world_from_mesh`; `at` is the
    /// node that draws it (or the top level), where errors point.
    fn place(&mut self, mesh: usize, world_from_mesh: DMat4, at: Location) -> Result<(), IoError> {
        self.read_mesh(mesh, at)?;
        let identity = world_from_mesh == DMat4::IDENTITY;
        let mirrored = DMat3::from_mat4(world_from_mesh).determinant() < 0.0;
        let Some(Some(geometry)) = self.meshes.get(mesh) else {
            return Ok(());
        };
        for primitive in geometry {
            let Geometry::Triangles {
                positions,
                triangles,
            } = primitive
            else {
                self.primitives_skipped += 1;
                continue;
            };
            let first = self.positions.len();
            let total = first + positions.len();
            let Some(offset) = u32::try_from(first)
                .ok()
                .filter(|_| total <= u32::MAX as usize)
            else {
                return Err(error(
                    at,
                    ParseReason::TooManyVertices {
                        count: total as u64,
                    },
                ));
            };
            if identity {
                self.positions.extend_from_slice(positions);
            } else {
                for (vertex, &p) in positions.iter().enumerate() {
                    let placed = world_from_mesh.transform_point3(p);
                    let placed = finite_point(placed.to_array(), vertex)
                        .map_err(|reason| error(at, reason))?;
                    self.positions.push(placed);
                }
            }
            self.triangles.extend(triangles.iter().map(|&[a, b, c]| {
                if mirrored {
                    [a + offset, c + offset, b + offset]
                } else {
                    [a + offset, b + offset, c + offset]
                }
            }));
            self.primitives_read += 1;
            self.mirrored_primitives += usize::from(mirrored);
        }
        Ok(())
    }

    /// Reads the primitives of mesh `mesh` unless they are read already; `at` is where a
    /// missing mesh is reported.
    fn read_mesh(&mut self, mesh: usize, at: Location) -> Result<(), IoError> {
        let root = self.root;
        let json_mesh = root.meshes.get(mesh).ok_or_else(|| {
            error(
                at,
                ParseReason::DanglingReference {
                    kind: "mesh",
                    index: mesh,
                    available: root.meshes.len(),
                },
            )
        })?;
        if matches!(self.meshes.get(mesh), Some(Some(_))) {
            return Ok(());
        }
        let mut geometry = Vec::with_capacity(json_mesh.primitives.len());
        for (index, primitive) in json_mesh.primitives.iter().enumerate() {
            let at = Location::Gltf(GltfObject::Primitive {
                mesh,
                primitive: index,
            });
            geometry.push(self.read_primitive(primitive, at)?);
        }
        if let Some(slot) = self.meshes.get_mut(mesh) {
            *slot = Some(geometry);
        }
        Ok(())
    }

    /// Reads one primitive; `at` names it in errors.
    fn read_primitive(
        &mut self,
        primitive: &json::mesh::Primitive,
        at: Location,
    ) -> Result<Geometry, IoError> {
        let root = self.root;
        let here = |reason| error(at, reason);
        let Checked::Valid(mode) = primitive.mode else {
            return Err(here(ParseReason::InvalidValue {
                what: "primitive mode",
            }));
        };
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            return Ok(Geometry::Skipped);
        }
        let positions = primitive
            .attributes
            .get(&Checked::Valid(Semantic::Positions))
            .ok_or_else(|| {
                here(ParseReason::MissingAttribute {
                    attribute: "POSITION",
                })
            })?
            .value();
        self.buffers.load_for_accessor(root, positions)?;
        let positions = accessor::read_positions(root, &self.buffers, positions).map_err(here)?;
        let indices = match primitive.indices {
            Some(indices) => {
                self.buffers.load_for_accessor(root, indices.value())?;
                accessor::read_indices(root, &self.buffers, indices.value()).map_err(here)?
            }
            // At most u32::MAX positions (accessor counts are checked).
            None => (0..u32::try_from(positions.len()).unwrap_or(u32::MAX)).collect(),
        };
        if let Some((position, &index)) = indices
            .iter()
            .enumerate()
            .find(|&(_, &index)| index as usize >= positions.len())
        {
            return Err(here(ParseReason::PrimitiveIndexOutOfRange {
                position,
                index,
                vertex_count: positions.len(),
            }));
        }
        let triangles = assemble(mode, &indices).map_err(here)?;
        Ok(Geometry::Triangles {
            positions,
            triangles,
        })
    }

    /// The merged mesh and its report.
    fn finish(self) -> Result<LoadedMesh, IoError> {
        let mut report = MeshBuilder::report(Format::Gltf, self.positions.len());
        report.faces_in_file = self.triangles.len();
        report.primitives_read = self.primitives_read;
        report.primitives_skipped = self.primitives_skipped;
        report.mirrored_primitives = self.mirrored_primitives;
        let mesh = TriMesh::new(self.positions, self.triangles)?;
        Ok(LoadedMesh { mesh, report })
    }
}

/// The transform of a node relative to its parent: its `matrix`, or translation ×
/// rotation × scale (the rotation normalized).
fn local_transform(node: &json::Node) -> Result<DMat4, ParseReason> {
    let non_finite = ParseReason::InvalidTransform {
        problem: "a value is NaN or infinite",
    };
    if let Some(matrix) = node.matrix {
        let columns = matrix.map(f64::from);
        if !columns.iter().all(|v| v.is_finite()) {
            return Err(non_finite);
        }
        let matrix = DMat4::from_cols_array(&columns);
        if matrix.row(3) != DVec4::W {
            return Err(ParseReason::InvalidTransform {
                problem: "the matrix is not affine (its last row is not 0 0 0 1)",
            });
        }
        return Ok(matrix);
    }
    let translation = node.translation.unwrap_or([0.0; 3]).map(f64::from);
    let rotation = node
        .rotation
        .map_or([0.0, 0.0, 0.0, 1.0], |q| q.0)
        .map(f64::from);
    let scale = node.scale.unwrap_or([1.0; 3]).map(f64::from);
    if !translation
        .iter()
        .chain(&rotation)
        .chain(&scale)
        .all(|v| v.is_finite())
    {
        return Err(non_finite);
    }
    let rotation = DQuat::from_array(rotation);
    let length = rotation.length();
    if length <= 0.0 {
        return Err(ParseReason::InvalidTransform {
            problem: "the rotation quaternion is zero",
        });
    }
    // Dividing by a length of exactly 1 changes nothing, so unit rotations stay exact.
    Ok(DMat4::from_scale_rotation_translation(
        DVec3::from_array(scale),
        rotation / length,
        DVec3::from_array(translation),
    ))
}

/// The triangles of a primitive from its vertex indices, by the glTF rules: triples for
/// `TRIANGLES`; `{v_i, v_i+1, v_i+2}` for even `i` and `{v_i, v_i+2, v_i+1}` for odd `i`
/// for `TRIANGLE_STRIP`; `{v_0, v_i+1, v_i+2}` for `TRIANGLE_FAN`.
fn assemble(mode: Mode, indices: &[u32]) -> Result<Vec<[u32; 3]>, ParseReason> {
    Ok(match mode {
        Mode::TriangleStrip => indices
            .windows(3)
            .enumerate()
            .filter_map(|(i, w)| match *w {
                [a, b, c] if i % 2 == 0 => Some([a, b, c]),
                [a, b, c] => Some([a, c, b]),
                _ => None,
            })
            .collect(),
        Mode::TriangleFan => match indices.split_first() {
            Some((&center, rest)) => rest
                .windows(2)
                .filter_map(|w| match *w {
                    [b, c] => Some([center, b, c]),
                    _ => None,
                })
                .collect(),
            None => Vec::new(),
        },
        _ => {
            if !indices.len().is_multiple_of(3) {
                return Err(ParseReason::IncompleteTriangles {
                    count: indices.len(),
                });
            }
            indices
                .chunks_exact(3)
                .filter_map(|t| match *t {
                    [a, b, c] => Some([a, b, c]),
                    _ => None,
                })
                .collect()
        }
    })
}
