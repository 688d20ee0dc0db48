//! Tests of the glTF reader's errors: each names the object at fault and the problem, and
//! no document makes the reader panic.

use proptest::prelude::*;
use serde_json::json;

use super::super::{Format, Location, ParseReason, read, read_from_bytes};
use super::test_writer::{
    F32, GltfWriter, TRIANGLE, U8, glb, glb_message, parse_error, triangle_in_node,
};
use crate::IoError;

#[test]
fn a_missing_buffer_file_names_the_file_and_the_buffer() {
    let writer = triangle_in_node(json!({}));
    let dir = tempfile::tempdir().unwrap();
    let gltf = dir.path().join("scene.gltf");
    std::fs::write(&gltf, writer.gltf_with_file("missing.bin")).unwrap();
    let err = read(&gltf).unwrap_err();
    let message = err.to_string();
    assert!(
        message.starts_with(&format!(
            "malformed glTF data in {} at buffer 0: cannot read buffer `missing.bin` (",
            gltf.display()
        )),
        "{message}"
    );
    assert!(
        message.contains(&dir.path().join("missing.bin").display().to_string()),
        "{message}"
    );
    assert!(matches!(
        err,
        IoError::Parse {
            reason: ParseReason::BufferFile {
                kind: std::io::ErrorKind::NotFound,
                ..
            },
            ..
        }
    ));
}

/// A file of a few hundred bytes whose nodes draw one mesh of 2²⁴ zeros five times would
/// place 84 million vertices (2 GB): it is refused before any data are read, with an
/// error naming the count and the limit.
#[test]
fn instancing_cannot_place_more_vertices_than_the_limit() {
    let mut writer = GltfWriter::default();
    let zeros = writer.accessor(json!({ "componentType": F32, "count": 1 << 24, "type": "VEC3" }));
    writer.mesh(json!([{ "attributes": { "POSITION": zeros } }]));
    for _ in 0..5 {
        writer.node(json!({ "mesh": 0 }));
    }
    let bytes = writer.glb();
    assert!(bytes.len() < 1_000, "{} bytes", bytes.len());
    let (location, reason) = parse_error(&bytes);
    assert_eq!(location, Location::Gltf(super::super::GltfObject::Node(4)));
    assert!(
        matches!(
            reason,
            ParseReason::TooManyPlacedVertices { count, limit }
                if count == 5 << 24 && limit == super::super::MAX_PLACED_VERTICES
        ),
        "{reason:?}"
    );
    assert_eq!(
        glb_message(&writer),
        "malformed glTF data at node 4: the scene places 83886080 vertices (its nodes draw their meshes that often); at most 67108864 are read"
    );
}

/// A buffer URI naming a folder, a named pipe or a device such as `/dev/zero` (which never ends) is
/// refused; a buffer file longer than its `byteLength` is read up to it.
#[test]
fn buffer_files_are_regular_files_read_up_to_their_length() {
    let writer = triangle_in_node(json!({}));
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("folder.bin")).unwrap();
    let gltf = dir.path().join("scene.gltf");
    std::fs::write(&gltf, writer.gltf_with_file("folder.bin")).unwrap();
    let message = read(&gltf).unwrap_err().to_string();
    assert_eq!(
        message,
        format!(
            "malformed glTF data in {} at buffer 0: refused to read buffer `folder.bin` ({}): it is a folder, not a regular file",
            gltf.display(),
            dir.path().join("folder.bin").display()
        )
    );
    // A named pipe is refused before it is opened (opening it would wait for a writer).
    #[cfg(unix)]
    {
        let pipe = dir.path().join("pipe.bin");
        let made = std::process::Command::new("mkfifo").arg(&pipe).status();
        assert!(
            made.is_ok_and(|s| s.success()),
            "mkfifo is part of coreutils"
        );
        std::fs::write(&gltf, writer.gltf_with_file("pipe.bin")).unwrap();
        let message = read(&gltf).unwrap_err().to_string();
        assert!(
            message.contains("it is a named pipe, not a regular file"),
            "{message}"
        );
    }
    let mut longer = writer.bin.clone();
    longer.extend_from_slice(&[0xff; 64]);
    std::fs::write(dir.path().join("longer.bin"), &longer).unwrap();
    std::fs::write(&gltf, writer.gltf_with_file("longer.bin")).unwrap();
    let mesh = read(&gltf).unwrap();
    assert_eq!(mesh, read_from_bytes(&writer.glb(), Format::Gltf).unwrap());
}

/// Buffer files are relative to the glTF file and may not leave its folder: an absolute
/// path, a `..` climbing out, a link leading out and a device are refused with the reason,
/// whatever the file outside holds; a file in a subfolder, or a link within the folder,
/// is read.
#[test]
fn buffer_files_stay_in_the_assets_folder() {
    let writer = triangle_in_node(json!({}));
    let outer = tempfile::tempdir().unwrap();
    let asset = outer.path().join("asset");
    std::fs::create_dir_all(asset.join("data")).unwrap();
    // A readable file outside the asset's folder, of the right size to pass as the buffer.
    let secret = outer.path().join("secret.bin");
    std::fs::write(&secret, &writer.bin).unwrap();
    std::fs::write(asset.join("data").join("inside.bin"), &writer.bin).unwrap();
    let gltf = asset.join("scene.gltf");
    let read_uri = |uri: &str| {
        std::fs::write(&gltf, writer.gltf_with_file(uri)).unwrap();
        read(&gltf)
    };
    let refused = |uri: &str, expected: &str| {
        let error = read_uri(uri).expect_err(uri);
        let message = error.to_string();
        assert!(message.contains(expected), "{uri}: {message}");
    };
    refused(
        &secret.display().to_string(),
        "an absolute path: glTF buffer files are named relative to the glTF file",
    );
    refused("../secret.bin", "outside the allowed folder");
    refused("data/../../secret.bin", "outside the allowed folder");
    refused("%2E%2E/secret.bin", "outside the allowed folder");
    refused("/dev/zero", "an absolute path");
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(&secret, asset.join("link.bin")).unwrap();
        refused("link.bin", "outside the allowed folder");
        std::os::unix::fs::symlink(asset.join("data").join("inside.bin"), asset.join("in.bin"))
            .unwrap();
        assert!(read_uri("in.bin").is_ok());
        std::os::unix::fs::symlink("/dev/zero", asset.join("zero.bin")).unwrap();
        refused("zero.bin", "outside the allowed folder");
    }
    let expected = read_from_bytes(&writer.glb(), Format::Gltf).unwrap();
    assert_eq!(read_uri("data/inside.bin").unwrap(), expected);
    assert_eq!(read_uri("./data/../data/inside.bin").unwrap(), expected);
    // The policy's cap applies to buffer files too (to the file, not to the buffer's part).
    let mut big = writer.bin.clone();
    big.resize(1 << 20, 0);
    std::fs::write(asset.join("big.bin"), &big).unwrap();
    std::fs::write(&gltf, writer.gltf_with_file("big.bin")).unwrap();
    let capped = crate::FilePolicy::default().with_max_bytes(1 << 16);
    let error = crate::read_with(&gltf, &capped).unwrap_err();
    assert!(
        matches!(
            &error,
            IoError::Parse {
                reason: ParseReason::BufferRefused { refusal, .. },
                ..
            } if **refusal == crate::FileRefusal::TooLarge { bytes: 1_048_576, cap: 65_536 }
        ),
        "{error}"
    );
    assert_eq!(
        crate::read_with(&gltf, &crate::FilePolicy::default()).unwrap(),
        expected
    );
    let message = error.to_string();
    assert!(message.contains("more than the cap"), "{message}");
}

#[test]
fn errors_name_the_object_and_the_problem() {
    let message = |writer: &GltfWriter| glb_message(writer);
    // A vertex index past the end of POSITION.
    let mut writer = GltfWriter::default();
    writer.triangle_mesh(&TRIANGLE, &[[0, 1, 5]]);
    writer.node(json!({ "mesh": 0 }));
    assert_eq!(
        message(&writer),
        "malformed glTF data at mesh 0, primitive 0: vertex index 5 (entry 2 of the indices) is out of range: the primitive has 3 vertices"
    );
    // No POSITION.
    let mut writer = GltfWriter::default();
    writer.mesh(json!([{ "attributes": {} }]));
    writer.node(json!({ "mesh": 0 }));
    assert_eq!(
        message(&writer),
        "malformed glTF data at mesh 0, primitive 0: the primitive has no `POSITION` attribute"
    );
    // NaN and infinite positions, in the second primitive.
    for (value, text) in [(f32::NAN, "NaN"), (f32::INFINITY, "inf")] {
        let mut writer = GltfWriter::default();
        let good = writer.positions(&TRIANGLE);
        let bad = writer.positions(&[[0.0, 0.0, 0.0], [1.0, value, 0.0], [0.0, 1.0, 0.0]]);
        writer.mesh(
            json!([{ "attributes": { "POSITION": good } }, { "attributes": { "POSITION": bad } }]),
        );
        writer.node(json!({ "mesh": 0 }));
        assert_eq!(
            message(&writer),
            format!(
                "malformed glTF data at mesh 0, primitive 1: vertex 1 has a non-finite y coordinate ({text})"
            )
        );
    }
    // Nine nested scales of 10³⁸ overflow f64: the node drawing the mesh is named.
    let mut writer = triangle_in_node(json!({}));
    writer.nodes.clear();
    for k in 0..9 {
        let node = writer.node(json!({ "scale": [1e38, 1e38, 1e38] }));
        if k < 8 {
            writer.nodes[node]["children"] = json!([node + 1]);
        } else {
            writer.nodes[node]["mesh"] = json!(0);
        }
    }
    assert_eq!(
        message(&writer),
        "malformed glTF data at node 8: vertex 0 has a non-finite x coordinate (NaN)"
    );
    // Instancing past the limit on placed vertices is refused before any data are read
    // (2²⁴ zero vertices drawn 300 times: the fifth node passes it), and so is an
    // accessor of too many zeros.
    let mut writer = GltfWriter::default();
    let zeros = writer.accessor(json!({
        "componentType": F32, "count": 1 << 24, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0],
    }));
    writer.mesh(json!([{ "attributes": { "POSITION": zeros } }]));
    for _ in 0..300 {
        writer.node(json!({ "mesh": 0 }));
    }
    assert_eq!(
        message(&writer),
        "malformed glTF data at node 4: the scene places 83886080 vertices (its nodes draw their meshes that often); at most 67108864 are read"
    );
    writer.nodes.truncate(1);
    writer.accessors[0]["count"] = json!((1 << 24) + 3);
    assert_eq!(
        message(&writer),
        "malformed glTF data at mesh 0, primitive 0: invalid element count of an accessor without a buffer view 16777219"
    );
    // Node transforms.
    let transform = |node| message(&triangle_in_node(node));
    assert_eq!(
        transform(json!({ "rotation": [0.0, 0.0, 0.0, 0.0] })),
        "malformed glTF data at node 0: invalid node transform: the rotation quaternion is zero"
    );
    // Beyond f32: infinite after reading, or refused by the JSON reader when serde_json's
    // `float_roundtrip` is on (the workspace turns it on, a lone build of this crate not).
    let beyond = transform(json!({ "translation": [0.0, 1e39, 0.0] }));
    assert!(
        beyond
            == "malformed glTF data at node 0: invalid node transform: a value is NaN or infinite"
            || (beyond.starts_with("malformed glTF data at JSON line 1")
                && beyond.ends_with("number out of range")),
        "{beyond}"
    );
    assert_eq!(
        transform(json!({ "matrix": [1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] })),
        "malformed glTF data at node 0: invalid node transform: the matrix is not affine (its last row is not 0 0 0 1)"
    );
    // An accessor reading past its view, a view past its buffer.
    let mut writer = triangle_in_node(json!({}));
    writer.accessors[0]["count"] = json!(4);
    assert_eq!(
        message(&writer),
        "malformed glTF data at mesh 0, primitive 0: accessor 0 (elements) needs 48 bytes of buffer view 0, which has 36"
    );
    let mut writer = triangle_in_node(json!({}));
    writer.views[1]["byteLength"] = json!(100);
    assert_eq!(
        message(&writer),
        "malformed glTF data at mesh 0, primitive 0: buffer view 1 ends at byte 136, but buffer 0 has 48 bytes"
    );
    let mut writer = triangle_in_node(json!({}));
    writer.views[0]["byteStride"] = json!(8);
    assert_eq!(
        message(&writer),
        "malformed glTF data at mesh 0, primitive 0: buffer view 0 has a byte stride of 8, less than the 12-byte elements read through it"
    );
    // References to nothing.
    let mut writer = triangle_in_node(json!({}));
    writer.meshes[0]["primitives"][0]["indices"] = json!(7);
    assert_eq!(
        message(&writer),
        "malformed glTF data at mesh 0, primitive 0: accessor 7 does not exist (the file has 2)"
    );
    let mut writer = triangle_in_node(json!({}));
    writer.nodes[0]["mesh"] = json!(3);
    assert_eq!(
        message(&writer),
        "malformed glTF data at node 0: mesh 3 does not exist (the file has 1)"
    );
    let mut writer = triangle_in_node(json!({}));
    writer.scenes = Some(vec![json!({ "nodes": [0, 9] })]);
    assert_eq!(
        message(&writer),
        "malformed glTF data at scene 0: node 9 does not exist (the file has 1)"
    );
    // Wrong accessor types.
    let mut writer = triangle_in_node(json!({}));
    writer.accessors[0]["type"] = json!("VEC2");
    assert_eq!(
        message(&writer),
        "malformed glTF data at mesh 0, primitive 0: accessor 0 holds VEC2 of f32, expected VEC3 of f32, or of (normalized) 8- or 16-bit integers"
    );
    let mut writer = triangle_in_node(json!({}));
    writer.accessors[1]["componentType"] = json!(F32);
    assert_eq!(
        message(&writer),
        "malformed glTF data at mesh 0, primitive 0: accessor 1 holds SCALAR of f32, expected SCALAR of u8, u16 or u32"
    );
    let mut writer = triangle_in_node(json!({}));
    writer.meshes[0]["primitives"][0]["mode"] = json!(9);
    assert_eq!(
        message(&writer),
        "malformed glTF data at mesh 0, primitive 0: invalid primitive mode"
    );
    // A sparse index past the end.
    let mut writer = triangle_in_node(json!({}));
    let sparse_indices = writer.view(&[7u8], None);
    let sparse_values = writer.view(&[0u8; 12], None);
    writer.accessors[0]["sparse"] = json!({
        "count": 1,
        "indices": { "bufferView": sparse_indices, "componentType": U8 },
        "values": { "bufferView": sparse_values },
    });
    assert_eq!(
        message(&writer),
        "malformed glTF data at mesh 0, primitive 0: accessor 0 has a sparse index 7, but only 3 elements"
    );
    // A node hierarchy that is not a set of trees.
    let mut writer = triangle_in_node(json!({ "children": [0] }));
    writer.scenes = Some(vec![json!({ "nodes": [0] })]);
    assert_eq!(
        message(&writer),
        "malformed glTF data at scene 0: node 0 is reached twice: the node hierarchy must be disjoint trees (a cycle, a node with two parents, or a root listed twice)"
    );
    // Required extensions and versions.
    let mut writer = triangle_in_node(json!({}));
    writer.top.insert(
        "extensionsRequired".into(),
        json!(["KHR_materials_unlit", "KHR_draco_mesh_compression"]),
    );
    assert_eq!(
        message(&writer),
        "malformed glTF data at the top level: the required extension `KHR_draco_mesh_compression` is not supported"
    );
    let mut writer = triangle_in_node(json!({}));
    writer
        .top
        .insert("asset".into(), json!({ "version": "1.0" }));
    assert_eq!(
        message(&writer),
        "malformed glTF data at the top level: glTF version 1.0 is not supported (only 2.x is)"
    );
    // Buffer data.
    let writer = triangle_in_node(json!({}));
    let json = serde_json::to_vec(&writer.document(None)).unwrap();
    assert_eq!(
        read_from_bytes(&glb(&json, Some(&writer.bin[..40])), Format::Gltf)
            .unwrap_err()
            .to_string(),
        "malformed glTF data at buffer 0: the buffer declares 48 bytes, but its data have 40"
    );
    let no_bin = glb(&serde_json::to_vec(&writer.document(None)).unwrap(), None);
    assert_eq!(
        read_from_bytes(&no_bin, Format::Gltf)
            .unwrap_err()
            .to_string(),
        "malformed glTF data at buffer 0: the buffer has no `uri` and the file has no binary chunk for it"
    );
    let bad_uri =
        serde_json::to_vec(&writer.document(Some("data:application/octet-stream;base64,A$==")))
            .unwrap();
    assert_eq!(
        read_from_bytes(&bad_uri, Format::Gltf)
            .unwrap_err()
            .to_string(),
        "malformed glTF data at buffer 0: invalid buffer uri `data:application/octet-stream;base64,A$=…`: bad base64 data"
    );
    let remote =
        serde_json::to_vec(&writer.document(Some("https://example.invalid/a.bin"))).unwrap();
    assert!(
        read_from_bytes(&remote, Format::Gltf)
            .unwrap_err()
            .to_string()
            .ends_with("only `data:` URIs and paths relative to the glTF file are supported")
    );
}

#[test]
fn malformed_json_and_containers_point_at_the_place() {
    assert_eq!(
        parse_error(b"{\n  \"asset\": {\"version\": \"2.0\"},\n  \"meshes\": [}\n"),
        (
            Location::Json {
                line: 3,
                column: 14
            },
            ParseReason::InvalidJson {
                message: "expected value".into()
            }
        )
    );
    let (location, reason) = parse_error(b"{\"meshes\": []}");
    assert_eq!(
        location,
        Location::Json {
            line: 1,
            column: 14
        }
    );
    assert_eq!(
        reason.to_string(),
        "not a valid glTF JSON document: missing field `asset`"
    );
    assert_eq!(
        parse_error(b" \n"),
        (Location::Byte(0), ParseReason::EmptyFile)
    );
    let glb_bytes = triangle_in_node(json!({})).glb();
    // Cut short, and with a declared length that is too short.
    let (location, reason) = parse_error(&glb_bytes[..glb_bytes.len() - 4]);
    assert_eq!(location, Location::Byte(glb_bytes.len() as u64 - 4));
    assert_eq!(
        reason,
        ParseReason::SizeMismatch {
            expected: glb_bytes.len() as u64,
            found: glb_bytes.len() as u64 - 4
        }
    );
    let mut version_1 = glb_bytes.clone();
    version_1[4] = 1;
    assert_eq!(
        parse_error(&version_1),
        (
            Location::Byte(4),
            ParseReason::UnsupportedVersion {
                version: "1".into()
            }
        )
    );
    let mut bin_first = glb_bytes.clone();
    bin_first[16..20].copy_from_slice(b"BIN\0");
    assert_eq!(parse_error(&bin_first).0, Location::Byte(16));
    let mut long_chunk = glb_bytes;
    long_chunk[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    assert_eq!(
        parse_error(&long_chunk),
        (
            Location::Byte(long_chunk.len() as u64),
            ParseReason::UnexpectedEnd {
                expected: "a GLB chunk"
            }
        )
    );
}

#[test]
fn errors_from_files_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.glb");
    let mut writer = triangle_in_node(json!({}));
    writer.accessors[0]["count"] = json!(4);
    std::fs::write(&path, writer.glb()).unwrap();
    let message = read(&path).unwrap_err().to_string();
    assert_eq!(
        message,
        format!(
            "malformed glTF data in {} at mesh 0, primitive 0: accessor 0 (elements) needs 48 bytes of buffer view 0, which has 36",
            path.display()
        )
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(256)))]

    /// Random values in the places a file controls (counts, offsets, strides, indices,
    /// modes, URIs) give a mesh or an error, never a panic.
    #[test]
    fn corrupted_documents_never_panic(
        edits in prop::collection::vec((0usize..16, prop::sample::select(vec![
            json!(0), json!(1), json!(2), json!(3), json!(7), json!(255), json!(4096),
            json!(u32::MAX), json!(u64::MAX), json!(-1), json!(1.5), json!(null), json!("x"),
            json!([]), json!({}), json!(1e300), json!("data:,"), json!("../x.bin"),
        ])), 1..4),
    ) {
        let mut writer = triangle_in_node(json!({ "translation": [1.0, 2.0, 3.0] }));
        let sparse_indices = writer.view(&[1u8, 2], None);
        let sparse_values = writer.view(&[0u8; 24], None);
        writer.accessors[0]["sparse"] = json!({
            "count": 2,
            "indices": { "bufferView": sparse_indices, "componentType": U8 },
            "values": { "bufferView": sparse_values },
        });
        let mut doc = writer.document(None);
        for (place, value) in edits {
            let target = match place {
                0 => &mut doc["accessors"][0]["count"],
                1 => &mut doc["accessors"][0]["byteOffset"],
                2 => &mut doc["accessors"][0]["bufferView"],
                3 => &mut doc["accessors"][1]["componentType"],
                4 => &mut doc["accessors"][0]["sparse"]["count"],
                5 => &mut doc["accessors"][0]["sparse"]["indices"]["byteOffset"],
                6 => &mut doc["bufferViews"][0]["byteStride"],
                7 => &mut doc["bufferViews"][1]["byteOffset"],
                8 => &mut doc["bufferViews"][0]["byteLength"],
                9 => &mut doc["buffers"][0]["byteLength"],
                10 => &mut doc["buffers"][0]["uri"],
                11 => &mut doc["meshes"][0]["primitives"][0]["mode"],
                12 => &mut doc["nodes"][0]["children"],
                13 => &mut doc["nodes"][0]["mesh"],
                14 => &mut doc["scenes"][0]["nodes"],
                _ => &mut doc["scene"],
            };
            *target = value;
        }
        let bytes = glb(&serde_json::to_vec(&doc).unwrap(), Some(&writer.bin));
        let _ = read_from_bytes(&bytes, Format::Gltf);
    }
}
