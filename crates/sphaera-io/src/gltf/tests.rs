//! Tests of the glTF reader, on documents written by hand ([`super::test_writer`]).

use glam::{DMat4, DQuat, DVec3};
use proptest::prelude::*;
use serde_json::json;

use super::super::{Format, GltfObject, LoadedMesh, Location, load, read, read_from_bytes};
use super::test_writer::{
    F32, GltfWriter, I8, I16, TRIANGLE, U8, U16, U32, glb_message, mesh_glb, parse_error, rounded,
    triangle_in_node,
};
use sphaera_mesh::{TriMesh, shapes};

fn load_glb(writer: &GltfWriter) -> LoadedMesh {
    read_from_bytes(&writer.glb(), Format::Gltf).unwrap()
}

fn positions(mesh: &TriMesh) -> Vec<[f64; 3]> {
    mesh.positions().iter().map(DVec3::to_array).collect()
}

fn signed_volume(mesh: &TriMesh) -> f64 {
    mesh.triangle_iter()
        .map(|t| t.a.dot(t.b.cross(t.c)) / 6.0)
        .sum()
}

fn assert_close(actual: DVec3, expected: DVec3) {
    assert!(
        (actual - expected).length() <= 1e-6 * (1.0 + expected.length()),
        "{actual} != {expected}"
    );
}

#[test]
fn a_single_triangle() {
    let loaded = load_glb(&triangle_in_node(json!({})));
    assert_eq!(
        positions(&loaded.mesh),
        [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    );
    assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2]]);
    let report = loaded.report;
    assert_eq!(report.format, Format::Gltf);
    assert_eq!(report.vertex_records, 3);
    assert_eq!(report.faces_in_file, 1);
    assert_eq!(report.primitives_read, 1);
    assert_eq!(report.primitives_skipped, 0);
    assert_eq!(report.mirrored_primitives, 0);
    assert_eq!(report.polygons_triangulated, 0);
}

#[test]
fn a_mesh_instanced_by_two_nodes_with_translation_rotation_and_scale() {
    let mut writer = GltfWriter::default();
    let mesh = writer.triangle_mesh(&TRIANGLE, &[[0, 1, 2]]);
    // Half a turn about z (exact in f32), scale 2, then translation.
    writer.node(json!({
        "mesh": mesh, "translation": [10.0, 0.0, 0.0], "rotation": [0.0, 0.0, 1.0, 0.0],
        "scale": [2.0, 2.0, 2.0],
    }));
    // A quarter turn about x (rounded in f32), non-uniform scale.
    let h = std::f32::consts::FRAC_1_SQRT_2;
    writer.node(json!({
        "mesh": mesh, "translation": [0.0, 5.0, 0.0], "rotation": [h, 0.0, 0.0, h],
        "scale": [1.0, 2.0, 3.0],
    }));
    let loaded = load_glb(&writer);
    assert_eq!(loaded.mesh.vertex_count(), 6);
    assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2], [3, 4, 5]]);
    // (x, y, z) -> (10 - 2x, -2y, 2z): exact.
    assert_eq!(
        positions(&loaded.mesh)[..3],
        [[10.0, 0.0, 0.0], [8.0, 0.0, 0.0], [10.0, -2.0, 0.0]]
    );
    // (x, y, z) -> (x, 5 - 3z, 2y) after scaling by (1, 2, 3) and turning y into z.
    let p = loaded.mesh.positions();
    assert_close(p[3], DVec3::new(0.0, 5.0, 0.0));
    assert_close(p[4], DVec3::new(1.0, 5.0, 0.0));
    assert_close(p[5], DVec3::new(0.0, 5.0, 2.0));
    assert_eq!(loaded.report.primitives_read, 2);
    assert_eq!(loaded.report.vertex_records, 6);
    assert_eq!(loaded.report.faces_in_file, 2);
}

#[test]
fn a_matrix_transform_is_column_major() {
    let loaded = load_glb(&triangle_in_node(json!({
        "matrix": [2.0, 0.0, 0.0, 0.0, 0.0, 3.0, 0.0, 0.0, 0.0, 0.0, 4.0, 0.0, 1.0, 2.0, 3.0, 1.0],
    })));
    assert_eq!(
        positions(&loaded.mesh),
        [[1.0, 2.0, 3.0], [3.0, 2.0, 3.0], [1.0, 5.0, 3.0]]
    );
    assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2]]);
}

#[test]
fn a_mirroring_node_keeps_a_closed_cube_outward() {
    let cube = shapes::cube(2.0, 1).unwrap();
    let original = signed_volume(&cube);
    assert!(original > 0.0);
    for (node, mirrored) in [
        (json!({ "scale": [-1.0, 1.0, 1.0] }), true),
        (
            json!({ "matrix": [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -3.0, 0.0, 0.0, 0.0, 0.0, 1.0] }),
            true,
        ),
        // Two mirrors make a rotation: nothing to flip.
        (json!({ "scale": [-1.0, -1.0, 1.0] }), false),
    ] {
        let loaded = read_from_bytes(&mesh_glb(&cube, node.clone()), Format::Gltf).unwrap();
        let volume = signed_volume(&loaded.mesh);
        assert!(volume > 0.0, "{node}: {volume}");
        assert_eq!(
            loaded.report.mirrored_primitives,
            usize::from(mirrored),
            "{node}"
        );
        let expected: Vec<[u32; 3]> = cube
            .triangles()
            .iter()
            .map(|&[a, b, c]| if mirrored { [a, c, b] } else { [a, b, c] })
            .collect();
        assert_eq!(loaded.mesh.triangles(), expected, "{node}");
    }
}

#[test]
fn nested_nodes_compose_from_the_root() {
    let mut writer = GltfWriter::default();
    let mesh = writer.triangle_mesh(&TRIANGLE, &[[0, 1, 2]]);
    // Document order: grandchild, root, child; the walk is depth first from the root.
    writer.node(json!({ "mesh": mesh, "translation": [0.0, 0.0, 1.0] }));
    writer.node(json!({ "mesh": mesh, "translation": [1.0, 0.0, 0.0], "scale": [2.0, 2.0, 2.0], "children": [2] }));
    writer.node(json!({ "translation": [0.0, 1.0, 0.0], "children": [0] }));
    let loaded = load_glb(&writer);
    let p = positions(&loaded.mesh);
    // Root: 2p + (1, 0, 0).
    assert_eq!(p[..3], [[1.0, 0.0, 0.0], [3.0, 0.0, 0.0], [1.0, 2.0, 0.0]]);
    // Grandchild: 2 (p + (0, 1, 0) + (0, 0, 1)) + (1, 0, 0).
    assert_eq!(p[3..], [[1.0, 2.0, 2.0], [3.0, 2.0, 2.0], [1.0, 4.0, 2.0]]);
    assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2], [3, 4, 5]]);
}

#[test]
fn the_default_scene_is_read_and_a_file_without_scenes_gives_every_mesh() {
    let mut writer = GltfWriter::default();
    let a = writer.triangle_mesh(&TRIANGLE, &[[0, 1, 2]]);
    let b = writer.triangle_mesh(&TRIANGLE, &[[0, 2, 1]]);
    writer.node(json!({ "mesh": a, "translation": [5.0, 0.0, 0.0] }));
    writer.node(json!({ "mesh": b }));
    writer.scenes = Some(vec![json!({ "nodes": [0] }), json!({ "nodes": [1] })]);
    // No `scene`: the first one.
    assert_eq!(
        load_glb(&writer).mesh.positions()[0],
        DVec3::new(5.0, 0.0, 0.0)
    );
    writer.top.insert("scene".into(), json!(1));
    assert_eq!(load_glb(&writer).mesh.triangles(), &[[0, 2, 1]]);
    // No scenes: every mesh once, untransformed, nodes ignored.
    writer.top.clear();
    writer.scenes = Some(Vec::new());
    let loaded = load_glb(&writer);
    assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2], [3, 5, 4]]);
    assert_eq!(loaded.mesh.positions()[0], DVec3::ZERO);
}

#[test]
fn a_primitive_without_indices_takes_consecutive_triples() {
    let mut writer = GltfWriter::default();
    let mut points = TRIANGLE.to_vec();
    points.extend(TRIANGLE.iter().map(|p| [p[0], p[1], 1.0]));
    let positions = writer.positions(&points);
    writer.mesh(json!([{ "attributes": { "POSITION": positions } }]));
    writer.node(json!({ "mesh": 0 }));
    let loaded = load_glb(&writer);
    assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2], [3, 4, 5]]);
    // Without indices, TRIANGLES still needs whole triangles.
    let mut writer = GltfWriter::default();
    let positions = writer.positions(&points[..4]);
    writer.mesh(json!([{ "attributes": { "POSITION": positions } }]));
    writer.node(json!({ "mesh": 0 }));
    assert_eq!(
        glb_message(&writer),
        "malformed glTF data at mesh 0, primitive 0: 4 vertex indices do not make whole triangles (not a multiple of 3)"
    );
}

#[test]
fn u8_u16_and_u32_indices_give_the_same_mesh() {
    let quad = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    for component in [U8, U16, U32] {
        let mut writer = GltfWriter::default();
        let positions = writer.positions(&quad);
        let indices = writer.indices(&[0, 1, 2, 0, 2, 3], component);
        writer.mesh(
            json!([{ "attributes": { "POSITION": positions }, "indices": indices, "mode": 4 }]),
        );
        writer.node(json!({ "mesh": 0 }));
        let loaded = load_glb(&writer);
        assert_eq!(
            loaded.mesh.triangles(),
            &[[0, 1, 2], [0, 2, 3]],
            "{component}"
        );
    }
}

#[test]
fn strips_and_fans_become_consistently_oriented_triangles() {
    // A zigzag strip along x and a fan around the origin, all in the plane z = 0, facing +z.
    let strip = [
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],
    ];
    let fan = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ];
    let mut writer = GltfWriter::default();
    let strip_positions = writer.positions(&strip);
    let fan_positions = writer.positions(&fan);
    let strip_indices = writer.indices(&[0, 1, 2, 3, 4], U16);
    writer.mesh(json!([
        { "attributes": { "POSITION": strip_positions }, "indices": strip_indices, "mode": 5 },
        { "attributes": { "POSITION": fan_positions }, "mode": 6 },
    ]));
    writer.node(json!({ "mesh": 0 }));
    let loaded = load_glb(&writer);
    assert_eq!(
        loaded.mesh.triangles(),
        &[
            [0, 1, 2],
            [1, 3, 2],
            [2, 3, 4],
            [5, 6, 7],
            [5, 7, 8],
            [5, 8, 9]
        ]
    );
    let normals: Vec<f64> = loaded
        .mesh
        .triangle_iter()
        .map(|t| (t.b - t.a).cross(t.c - t.a).z.signum())
        .collect();
    // The strip's first triangle (0, 1, 2) winds clockwise seen from +z, and every other
    // triangle of the strip follows it; the fan winds counter-clockwise.
    assert_eq!(normals, [-1.0, -1.0, -1.0, 1.0, 1.0, 1.0]);
    assert_eq!(loaded.report.faces_in_file, 6);
}

#[test]
fn points_and_lines_primitives_are_skipped_and_counted() {
    let mut writer = GltfWriter::default();
    let positions = writer.positions(&TRIANGLE);
    writer.mesh(json!([
        { "attributes": { "POSITION": positions }, "mode": 0 },
        { "attributes": { "POSITION": positions } },
        { "attributes": { "POSITION": positions }, "mode": 1 },
        { "attributes": { "POSITION": positions }, "mode": 3 },
    ]));
    writer.node(json!({ "mesh": 0 }));
    writer.node(json!({ "mesh": 0, "translation": [0.0, 0.0, 1.0] }));
    let loaded = load_glb(&writer);
    assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2], [3, 4, 5]]);
    assert_eq!(loaded.report.primitives_read, 2);
    assert_eq!(loaded.report.primitives_skipped, 6);
}

#[test]
fn buffers_in_a_separate_file_or_a_data_uri() {
    let writer = triangle_in_node(json!({ "translation": [0.0, 0.0, 2.0] }));
    let expected = load_glb(&writer).mesh;
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("data")).unwrap();
    std::fs::write(dir.path().join("data").join("tri angle.bin"), &writer.bin).unwrap();
    let gltf = dir.path().join("scene.GLTF");
    std::fs::write(&gltf, writer.gltf_with_file("data/tri%20angle.bin")).unwrap();
    let loaded = read(&gltf).unwrap();
    assert_eq!(loaded.mesh, expected);
    assert_eq!(loaded.report.format, Format::Gltf);
    // The same JSON from bytes has no folder to look in.
    let (location, reason) = parse_error(&writer.gltf_with_file("data/tri%20angle.bin"));
    assert_eq!(location, Location::Gltf(GltfObject::Buffer(0)));
    assert_eq!(
        reason.to_string(),
        "buffer `data/tri%20angle.bin` is a separate file, which only reading the glTF from its path can resolve (use `io::read`)"
    );
    // A data URI works both ways, and so does a .glb file.
    let data_uri = writer.gltf_with_data_uri();
    assert_eq!(
        read_from_bytes(&data_uri, Format::Gltf).unwrap().mesh,
        expected
    );
    let embedded = dir.path().join("embedded.gltf");
    std::fs::write(&embedded, &data_uri).unwrap();
    assert_eq!(load(&embedded).unwrap(), expected);
    let binary = dir.path().join("scene.glb");
    std::fs::write(&binary, writer.glb()).unwrap();
    assert_eq!(load(&binary).unwrap(), expected);
    // Sniffed without a known extension, both JSON and binary.
    let unnamed = dir.path().join("scene.model");
    std::fs::write(&unnamed, &data_uri).unwrap();
    assert_eq!(load(&unnamed).unwrap(), expected);
    std::fs::write(&unnamed, writer.glb()).unwrap();
    assert_eq!(load(&unnamed).unwrap(), expected);
    // A percent-encoded data URI (not base64).
    let escaped: String = writer.bin.iter().map(|b| format!("%{b:02X}")).collect();
    let doc = serde_json::to_vec(
        &writer.document(Some(&format!("data:application/octet-stream,{escaped}"))),
    )
    .unwrap();
    assert_eq!(read_from_bytes(&doc, Format::Gltf).unwrap().mesh, expected);
}

#[test]
fn sparse_accessors_and_quantized_positions() {
    let mut writer = GltfWriter::default();
    // Base positions over zeros, with vertices 1 and 2 replaced.
    let sparse_indices = writer.view(&[1u8, 2], None);
    let values: Vec<u8> = [[1.0f32, 0.0, 0.0], [0.0, 1.0, 0.0]]
        .iter()
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let sparse_values = writer.view(&values, None);
    let sparse = writer.accessor(json!({
        "componentType": F32, "count": 3, "type": "VEC3",
        "min": [0, 0, 0], "max": [1, 1, 0],
        "sparse": {
            "count": 2,
            "indices": { "bufferView": sparse_indices, "componentType": U8 },
            "values": { "bufferView": sparse_values },
        },
    }));
    // Normalized u16, normalized i8 (with -128 clamped to -1), plain i16, interleaved with
    // a stride of 8 bytes.
    let u16s: Vec<u8> = [0u16, 0, 0, 65535, 0, 0, 0, 65535, 0]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let u16_view = writer.view(&u16s, None);
    let normalized_u16 = writer.accessor(json!({
        "bufferView": u16_view, "componentType": U16, "normalized": true, "count": 3,
        "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0],
    }));
    let i8_view = writer.view(&[0, 0, 0, 0, 127, 0, 0, 0, 0x80, 0, 0, 0], Some(4));
    let normalized_i8 = writer.accessor(json!({
        "bufferView": i8_view, "componentType": I8, "normalized": true, "count": 3,
        "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0],
    }));
    let mut interleaved = Vec::new();
    for p in [[0i16, 0, 0], [300, 0, 0], [0, -7, 2]] {
        for v in p {
            interleaved.extend_from_slice(&v.to_le_bytes());
        }
        interleaved.extend_from_slice(&[0xee, 0xee]);
    }
    let i16_view = writer.view(&interleaved, Some(8));
    let plain_i16 = writer.accessor(json!({
        "bufferView": i16_view, "componentType": I16, "count": 3, "type": "VEC3",
        "min": [0, -7, 0], "max": [300, 0, 2],
    }));
    writer.mesh(json!([
        { "attributes": { "POSITION": sparse } },
        { "attributes": { "POSITION": normalized_u16 } },
        { "attributes": { "POSITION": normalized_i8 } },
        { "attributes": { "POSITION": plain_i16 } },
    ]));
    writer.node(json!({ "mesh": 0 }));
    writer
        .top
        .insert("extensionsUsed".into(), json!(["KHR_mesh_quantization"]));
    writer.top.insert(
        "extensionsRequired".into(),
        json!(["KHR_mesh_quantization"]),
    );
    let p = positions(&load_glb(&writer).mesh);
    assert_eq!(p[0..3], [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    assert_eq!(p[3..6], [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    assert_eq!(
        p[6..9],
        [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]]
    );
    assert_eq!(
        p[9..12],
        [[0.0, 0.0, 0.0], [300.0, 0.0, 0.0], [0.0, -7.0, 2.0]]
    );
}

/// The embedded low-resolution bunny of the CLI, as OBJ and as GLB, loads the same.
#[test]
fn the_embedded_bunny_as_glb_loads_like_the_obj() {
    let obj = include_bytes!("../../../sphaera-cli/assets/bunny_lowres.obj");
    let from_obj = read_from_bytes(obj, Format::Obj).unwrap().mesh;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bunny.glb");
    std::fs::write(&path, mesh_glb(&from_obj, json!({}))).unwrap();
    let loaded = read(&path).unwrap();
    // glTF stores f32: the same mesh, rounded.
    assert_eq!(loaded.mesh, rounded(&from_obj));
    assert_eq!(loaded.report.vertex_records, from_obj.vertex_count());
    assert_eq!(loaded.report.faces_in_file, from_obj.triangle_count());
    let scale = from_obj.bounding_box_diagonal();
    for (a, b) in loaded.mesh.positions().iter().zip(from_obj.positions()) {
        assert!((*a - *b).length() <= 1e-7 * scale);
    }
}

/// Scale, rotation (x, y, z, w), translation and whether x is mirrored.
type Similarity = (f32, [f32; 4], [f32; 3], bool);

/// A random closed shape drawn by a node with a random similarity transform (possibly
/// mirrored), as glTF would hold it: positions and transform in f32.
fn transformed_shape() -> impl Strategy<Value = (TriMesh, Option<Similarity>)> {
    let shape = (0..shapes::DEFAULT_SHAPES.len(), 0usize..4).prop_map(|(k, extra)| {
        let shape = shapes::DEFAULT_SHAPES[k];
        shape.build(shape.min_resolution() + extra).unwrap()
    });
    let transform = (
        0.1f32..10.0,
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0, 0.05f32..1.0),
        [-100.0f32..100.0, -100.0f32..100.0, -100.0f32..100.0],
        any::<bool>(),
    )
        .prop_map(|(s, (x, y, z, w), t, mirror)| (s, [x, y, z, w], t, mirror));
    (shape, prop::option::of(transform))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(48)))]

    #[test]
    fn a_shape_written_as_glb_loads_transformed(
        (mesh, transform) in transformed_shape(),
    ) {
        let node = match transform {
            None => json!({}),
            Some((s, r, t, mirror)) => json!({
                "scale": [if mirror { -s } else { s }, s, s], "rotation": r, "translation": t,
            }),
        };
        let loaded = read_from_bytes(&mesh_glb(&mesh, node), Format::Gltf).unwrap();
        let stored = rounded(&mesh);
        let Some((s, r, t, mirror)) = transform else {
            // Under the identity, exactly the stored mesh.
            prop_assert_eq!(&loaded.mesh, &stored);
            prop_assert_eq!(loaded.report.mirrored_primitives, 0);
            return Ok(());
        };
        let scale = DVec3::new(if mirror { -f64::from(s) } else { f64::from(s) }, f64::from(s), f64::from(s));
        let rotation = DQuat::from_array(r.map(f64::from)).normalize();
        let world_from_mesh = DMat4::from_scale_rotation_translation(scale, rotation, DVec3::from_array(t.map(f64::from)));
        let size = f64::from(s) * stored.bounding_box_diagonal() + DVec3::from_array(t.map(f64::from)).length();
        prop_assert_eq!(loaded.mesh.vertex_count(), stored.vertex_count());
        for (a, p) in loaded.mesh.positions().iter().zip(stored.positions()) {
            let expected = world_from_mesh.transform_point3(*p);
            prop_assert!((*a - expected).length() <= 1e-12 * size, "{} != {}", a, expected);
        }
        let expected: Vec<[u32; 3]> = stored
            .triangles()
            .iter()
            .map(|&[a, b, c]| if mirror { [a, c, b] } else { [a, b, c] })
            .collect();
        prop_assert_eq!(loaded.mesh.triangles(), &expected[..]);
        prop_assert_eq!(loaded.report.mirrored_primitives, usize::from(mirror));
        // Still outward: the volume is the stored one scaled by s³.
        let volume = signed_volume(&loaded.mesh);
        let expected_volume = signed_volume(&stored) * f64::from(s).powi(3);
        prop_assert!(volume > 0.0);
        prop_assert!((volume - expected_volume).abs() <= 1e-6 * expected_volume, "{} != {}", volume, expected_volume);
    }
}

#[test]
fn an_empty_scene_gives_an_empty_mesh() {
    let loaded = read_from_bytes(
        br#"{"asset": {"version": "2.0"}, "scenes": [{"nodes": []}]}"#,
        Format::Gltf,
    )
    .unwrap();
    assert!(loaded.mesh.is_empty());
    assert_eq!(loaded.mesh.vertex_count(), 0);
    assert_eq!(loaded.report.primitives_read, 0);
}
