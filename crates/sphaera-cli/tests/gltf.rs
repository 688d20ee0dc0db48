//! End-to-end tests of glTF input: `.glb` and `.gltf` files given to the subcommands.

mod common;

use std::path::Path;

use common::{json, sphaera};
use serde_json::{Value, json};
use sphaera::mesh::{TriMesh, shapes};

/// The glTF JSON of `mesh` (f32 positions, u32 indices) drawn by one node with `node`'s
/// members, its buffer at `uri` (`None`: the GLB binary chunk), and the buffer's bytes.
fn document(mesh: &TriMesh, mut node: Value, uri: Option<&str>) -> (Value, Vec<u8>) {
    let mut bin: Vec<u8> = mesh
        .positions()
        .iter()
        .flat_map(sphaera::mesh::DVec3::to_array)
        .flat_map(|v| (v as f32).to_le_bytes())
        .collect();
    let positions_length = bin.len();
    bin.extend(
        mesh.triangles()
            .iter()
            .flatten()
            .flat_map(|i| i.to_le_bytes()),
    );
    let mut buffer = json!({ "byteLength": bin.len() });
    if let Some(uri) = uri {
        buffer["uri"] = json!(uri);
    }
    node["mesh"] = json!(0);
    let bbox = mesh.bounding_box();
    let doc = json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [node],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": mesh.vertex_count(), "type": "VEC3",
              "min": bbox.min.to_array(), "max": bbox.max.to_array() },
            { "bufferView": 1, "componentType": 5125, "count": 3 * mesh.triangle_count(), "type": "SCALAR" },
        ],
        "bufferViews": [
            { "buffer": 0, "byteLength": positions_length },
            { "buffer": 0, "byteOffset": positions_length, "byteLength": bin.len() - positions_length },
        ],
        "buffers": [buffer],
    });
    (doc, bin)
}

/// A GLB file of `mesh` drawn by one node with `node`'s members.
fn write_glb(path: &Path, mesh: &TriMesh, node: Value) {
    let (doc, bin) = document(mesh, node, None);
    let mut json = serde_json::to_vec(&doc).unwrap();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let mut out = b"glTF".to_vec();
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(
        &u32::try_from(12 + 8 + json.len() + 8 + bin.len())
            .unwrap()
            .to_le_bytes(),
    );
    out.extend_from_slice(&u32::try_from(json.len()).unwrap().to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&u32::try_from(bin.len()).unwrap().to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    std::fs::write(path, out).unwrap();
}

#[test]
fn info_reads_glb_and_gltf_with_a_buffer_file() {
    let sphere = shapes::sphere(1.0, 12).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("sphere.GLB");
    write_glb(&glb, &sphere, json!({ "translation": [10.0, 0.0, 0.0] }));
    let report = json(&sphaera(&[
        "info",
        "--quiet",
        "--json",
        glb.to_str().unwrap(),
    ]));
    assert_eq!(report["format"], "gltf");
    assert_eq!(report["triangles"], sphere.triangle_count());
    assert_eq!(report["primitives_read"], 1);
    assert_eq!(report["topology"]["closed"], true);
    assert_eq!(report["topology"]["genus"], 0);
    let min_x = report["bounding_box"]["min"][0].as_f64().unwrap();
    assert!((min_x - 9.0).abs() < 1e-6, "{min_x}");

    // A .gltf beside its .bin, mirrored by its node: still closed and oriented.
    let (doc, bin) = document(
        &sphere,
        json!({ "scale": [-1.0, 1.0, 1.0] }),
        Some("sphere.bin"),
    );
    std::fs::write(dir.path().join("sphere.bin"), bin).unwrap();
    let gltf = dir.path().join("sphere.gltf");
    std::fs::write(&gltf, serde_json::to_vec_pretty(&doc).unwrap()).unwrap();
    let report = json(&sphaera(&[
        "info",
        "--quiet",
        "--json",
        gltf.to_str().unwrap(),
    ]));
    assert_eq!(report["mirrored_primitives"], 1);
    assert_eq!(report["topology"]["oriented"], true);
    let output = sphaera(&["info", "--quiet", gltf.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.contains(
            "glTF primitives 1 triangle primitives read (1 mirrored), 0 points or lines skipped"
        ),
        "{text}"
    );
}

#[test]
fn a_missing_buffer_file_is_an_error_naming_both_files() {
    let sphere = shapes::sphere(1.0, 8).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let (doc, _) = document(&sphere, json!({}), Some("gone.bin"));
    let gltf = dir.path().join("scene.gltf");
    std::fs::write(&gltf, serde_json::to_vec(&doc).unwrap()).unwrap();
    let output = sphaera(&["info", gltf.to_str().unwrap()]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.starts_with("error:"), "{message}");
    assert!(message.contains("scene.gltf at buffer 0"), "{message}");
    assert!(message.contains("gone.bin"), "{message}");
}

#[test]
fn hal_takes_a_glb_as_a_mesh() {
    let sphere = shapes::sphere(1.0, 12).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("sphere.glb");
    write_glb(&glb, &sphere, json!({}));
    let report = json(&sphaera(&[
        "hal",
        glb.to_str().unwrap(),
        "--tolerance",
        "5%",
        "--json",
    ]));
    assert_eq!(report["triangles"], sphere.triangle_count());
}
