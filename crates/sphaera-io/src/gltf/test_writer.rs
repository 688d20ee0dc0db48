//! Builds glTF documents by hand for the tests: JSON with `serde_json`, one binary buffer,
//! written as a `.glb`, as a `.gltf` with a `data:` URI, or as a `.gltf` naming a file.

use glam::DVec3;
use serde_json::{Value, json};

use super::super::{Format, Location, ParseReason, read_from_bytes};
use crate::IoError;
use sphaera_mesh::TriMesh;

/// `componentType` codes.
pub(crate) const I8: u32 = 5120;
pub(crate) const U8: u32 = 5121;
pub(crate) const I16: u32 = 5122;
pub(crate) const U16: u32 = 5123;
pub(crate) const U32: u32 = 5125;
pub(crate) const F32: u32 = 5126;

/// A glTF document under construction, with its one buffer.
#[derive(Default)]
pub(crate) struct GltfWriter {
    pub(crate) bin: Vec<u8>,
    pub(crate) views: Vec<Value>,
    pub(crate) accessors: Vec<Value>,
    pub(crate) meshes: Vec<Value>,
    pub(crate) nodes: Vec<Value>,
    /// `None`: one scene holding every node that is nobody's child. `Some(vec![])`: no
    /// `scenes` at all.
    pub(crate) scenes: Option<Vec<Value>>,
    /// Extra top-level members (`extensionsRequired`, `scene`...).
    pub(crate) top: serde_json::Map<String, Value>,
}

impl GltfWriter {
    /// Appends `bytes` (4-aligned) as a buffer view; its index.
    pub(crate) fn view(&mut self, bytes: &[u8], stride: Option<usize>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut view = json!({
            "buffer": 0,
            "byteOffset": self.bin.len(),
            "byteLength": bytes.len(),
        });
        if let Some(stride) = stride {
            view["byteStride"] = json!(stride);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(view);
        self.views.len() - 1
    }

    /// Adds an accessor; its index.
    pub(crate) fn accessor(&mut self, accessor: Value) -> usize {
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    /// `f32` positions in their own view; the accessor's index.
    pub(crate) fn positions(&mut self, points: &[[f32; 3]]) -> usize {
        let bytes: Vec<u8> = points
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let view = self.view(&bytes, None);
        let (mut min, mut max) = ([f32::MAX; 3], [f32::MIN; 3]);
        for p in points {
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        self.accessor(json!({
            "bufferView": view, "componentType": F32, "count": points.len(), "type": "VEC3",
            "min": min, "max": max,
        }))
    }

    /// Indices of the given component type in their own view; the accessor's index.
    pub(crate) fn indices(&mut self, indices: &[u32], component: u32) -> usize {
        let bytes: Vec<u8> = match component {
            U8 => indices.iter().map(|&i| u8::try_from(i).unwrap()).collect(),
            U16 => indices
                .iter()
                .flat_map(|&i| u16::try_from(i).unwrap().to_le_bytes())
                .collect(),
            _ => indices.iter().flat_map(|i| i.to_le_bytes()).collect(),
        };
        let view = self.view(&bytes, None);
        self.accessor(json!({
            "bufferView": view, "componentType": component, "count": indices.len(),
            "type": "SCALAR",
        }))
    }

    /// Adds a mesh with these primitives; its index.
    pub(crate) fn mesh(&mut self, primitives: Value) -> usize {
        let mut mesh = serde_json::Map::new();
        mesh.insert("primitives".into(), primitives);
        self.meshes.push(Value::Object(mesh));
        self.meshes.len() - 1
    }

    /// Adds an indexed `TRIANGLES` mesh (`u32` indices); its index.
    pub(crate) fn triangle_mesh(&mut self, points: &[[f32; 3]], triangles: &[[u32; 3]]) -> usize {
        let positions = self.positions(points);
        let flat: Vec<u32> = triangles.iter().flatten().copied().collect();
        let indices = self.indices(&flat, U32);
        self.mesh(json!([{ "attributes": { "POSITION": positions }, "indices": indices }]))
    }

    /// Adds a node; its index.
    pub(crate) fn node(&mut self, node: Value) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    /// The JSON document, its buffer named by `uri` (`None`: the GLB binary chunk).
    pub(crate) fn document(&self, uri: Option<&str>) -> Value {
        let mut buffer = json!({ "byteLength": self.bin.len() });
        if let Some(uri) = uri {
            buffer["uri"] = json!(uri);
        }
        let mut doc = json!({
            "asset": { "version": "2.0", "generator": "sphaera tests" },
            "buffers": [buffer],
            "bufferViews": self.views,
            "accessors": self.accessors,
            "meshes": self.meshes,
            "nodes": self.nodes,
        });
        let scenes = self.scenes.clone().unwrap_or_else(|| {
            let children: Vec<u64> = self
                .nodes
                .iter()
                .filter_map(|n| n.get("children").and_then(Value::as_array))
                .flatten()
                .filter_map(Value::as_u64)
                .collect();
            let roots: Vec<usize> = (0..self.nodes.len())
                .filter(|&i| !children.contains(&(i as u64)))
                .collect();
            vec![json!({ "nodes": roots })]
        });
        if !scenes.is_empty() {
            doc["scenes"] = json!(scenes);
        }
        for (key, value) in &self.top {
            doc[key] = value.clone();
        }
        doc
    }

    /// The document as a `.glb`.
    pub(crate) fn glb(&self) -> Vec<u8> {
        let json = serde_json::to_vec(&self.document(None)).unwrap();
        glb(&json, Some(&self.bin))
    }

    /// The document as a `.gltf` with its buffer in a base64 `data:` URI.
    pub(crate) fn gltf_with_data_uri(&self) -> Vec<u8> {
        let uri = format!("data:application/octet-stream;base64,{}", base64(&self.bin));
        serde_json::to_vec_pretty(&self.document(Some(&uri))).unwrap()
    }

    /// The document as a `.gltf` naming its buffer file `uri` (write [`Self::bin`] there).
    pub(crate) fn gltf_with_file(&self, uri: &str) -> Vec<u8> {
        serde_json::to_vec_pretty(&self.document(Some(uri))).unwrap()
    }
}

/// A GLB container around a JSON chunk and an optional binary chunk (both padded to 4
/// bytes, JSON with spaces, binary with zeros).
pub(crate) fn glb(json: &[u8], bin: Option<&[u8]>) -> Vec<u8> {
    let mut chunks = Vec::new();
    for (data, kind, pad) in [(Some(json), b"JSON", b' '), (bin, b"BIN\0", 0)] {
        let Some(data) = data else { continue };
        let mut data = data.to_vec();
        while !data.len().is_multiple_of(4) {
            data.push(pad);
        }
        chunks.extend_from_slice(&u32::try_from(data.len()).unwrap().to_le_bytes());
        chunks.extend_from_slice(kind);
        chunks.extend_from_slice(&data);
    }
    let mut out = b"glTF".to_vec();
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&u32::try_from(12 + chunks.len()).unwrap().to_le_bytes());
    out.extend_from_slice(&chunks);
    out
}

/// Standard base64 with padding.
pub(crate) fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = u32::from(b[0]) << 16 | u32::from(b[1]) << 8 | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[(n >> (18 - 6 * k) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// `mesh`'s positions rounded to `f32`, as glTF stores them.
pub(crate) fn to_f32(p: DVec3) -> [f32; 3] {
    p.to_array().map(|v| v as f32)
}

/// `mesh` with its positions rounded to `f32` (what a glTF of it holds).
pub(crate) fn rounded(mesh: &TriMesh) -> TriMesh {
    let positions = mesh
        .positions()
        .iter()
        .map(|&p| DVec3::from_array(to_f32(p).map(f64::from)))
        .collect();
    TriMesh::new(positions, mesh.triangles().to_vec()).unwrap()
}

/// A `.glb` holding `mesh` drawn by one node (`node`'s members plus `"mesh": 0`).
pub(crate) fn mesh_glb(mesh: &TriMesh, mut node: Value) -> Vec<u8> {
    let mut writer = GltfWriter::default();
    let points: Vec<[f32; 3]> = mesh.positions().iter().map(|&p| to_f32(p)).collect();
    let mesh = writer.triangle_mesh(&points, mesh.triangles());
    node["mesh"] = json!(mesh);
    writer.node(node);
    writer.glb()
}

/// A right triangle in the plane z = 0.
pub(crate) const TRIANGLE: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

/// The location and reason of the error `bytes` must give.
pub(crate) fn parse_error(bytes: &[u8]) -> (Location, ParseReason) {
    match read_from_bytes(bytes, Format::Gltf) {
        Err(IoError::Parse {
            location, reason, ..
        }) => (location, reason),
        other => panic!("expected a parse error, got {other:?}"),
    }
}

/// The message of the error `writer`'s GLB must give.
pub(crate) fn glb_message(writer: &GltfWriter) -> String {
    read_from_bytes(&writer.glb(), Format::Gltf)
        .unwrap_err()
        .to_string()
}

/// One triangle mesh drawn by one node with the given members.
pub(crate) fn triangle_in_node(node: Value) -> GltfWriter {
    let mut writer = GltfWriter::default();
    let mesh = writer.triangle_mesh(&TRIANGLE, &[[0, 1, 2]]);
    let mut node = node;
    node["mesh"] = json!(mesh);
    writer.node(node);
    writer
}
