//! Cross-format tests: PLY variants, round trips, sniffing, error locations, fuzzing.

use glam::DVec3;
use proptest::prelude::*;

use super::*;

/// The location and reason of the parse error `bytes` must give as `format` (also used by
/// the readers' own tests).
pub(super) fn parse_error(bytes: &[u8], format: Format) -> (Location, ParseReason) {
    match read_from_bytes(bytes, format) {
        Err(IoError::Parse {
            location, reason, ..
        }) => (location, reason),
        other => panic!("expected a parse error, got {other:?}"),
    }
}

/// Every format read.
const ALL_FORMATS: [Format; 5] = [
    Format::Obj,
    Format::Ply,
    Format::Stl,
    Format::Off,
    Format::Gltf,
];

fn tetrahedron() -> TriMesh {
    TriMesh::new(
        vec![
            DVec3::new(0.1, -0.2, 1e-300),
            DVec3::new(1.0 / 3.0, 0.0, 12_345.678_901_234_5),
            DVec3::new(-0.0, 1e17, 2.5e-8),
            DVec3::new(f64::MIN_POSITIVE, -7.0, 0.3),
        ],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
    .unwrap()
}

/// A PLY with a header of the given body encoding, extra properties and elements.
fn rich_ply_header(format: &str) -> String {
    format!(
        "ply\nformat {format} 1.0\ncomment made by hand\nobj_info test\n\
         element vertex 4\nproperty float32 x\nproperty uchar flag\nproperty double y\n\
         property list uint8 int16 junk\nproperty int z\n\
         element face 2\nproperty uchar kind\nproperty list uchar uint vertex_index\n\
         property list int int other\n\
         element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
    )
}

#[test]
fn ply_ascii_with_extra_properties_and_elements() {
    let mut ply = rich_ply_header("ascii");
    ply.push_str("0 7 0 2 5 5 0\n1 7 0 0 0\n1 7 1 1 9 0\n0 7 1 0 0\n");
    ply.push_str("1 4 0 1 2 3 0\n2 3 0 2 3 2 1 1\n0 1\n");
    let loaded = read_from_bytes(ply.as_bytes(), Format::Ply).unwrap();
    assert_eq!(loaded.mesh.vertex_count(), 4);
    assert_eq!(loaded.mesh.positions()[2], DVec3::new(1.0, 1.0, 0.0));
    assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2], [0, 2, 3], [0, 2, 3]]);
    assert_eq!(loaded.report.faces_in_file, 2);
    assert_eq!(loaded.report.polygons_triangulated, 1);
}

fn rich_binary_body(big_endian: bool) -> Vec<u8> {
    fn put<const N: usize>(out: &mut Vec<u8>, mut bytes: [u8; N], big_endian: bool) {
        if big_endian {
            bytes.reverse();
        }
        out.extend_from_slice(&bytes);
    }
    let mut body = Vec::new();
    let corners = [
        (0.0f32, 0.0f64, 0i32),
        (1.0, 0.0, 0),
        (1.0, 1.0, 0),
        (0.0, 1.0, 0),
    ];
    for (k, (x, y, z)) in corners.into_iter().enumerate() {
        put(&mut body, x.to_le_bytes(), big_endian);
        body.push(7);
        put(&mut body, y.to_le_bytes(), big_endian);
        body.push(u8::try_from(k % 2).unwrap());
        for _ in 0..k % 2 {
            put(&mut body, 5i16.to_le_bytes(), big_endian);
        }
        put(&mut body, z.to_le_bytes(), big_endian);
    }
    for face in [&[0u32, 1, 2, 3][..], &[0, 2, 3]] {
        body.push(1);
        body.push(u8::try_from(face.len()).unwrap());
        for &i in face {
            put(&mut body, i.to_le_bytes(), big_endian);
        }
        put(&mut body, 1i32.to_le_bytes(), big_endian);
        put(&mut body, 42i32.to_le_bytes(), big_endian);
    }
    put(&mut body, 0i32.to_le_bytes(), big_endian);
    put(&mut body, 1i32.to_le_bytes(), big_endian);
    body
}

#[test]
fn ply_binary_both_endians_with_extra_properties() {
    for (format, big) in [("binary_little_endian", false), ("binary_big_endian", true)] {
        let mut bytes = rich_ply_header(format).into_bytes();
        bytes.extend(rich_binary_body(big));
        let loaded = read_from_bytes(&bytes, Format::Ply).unwrap();
        assert_eq!(
            loaded.mesh.positions()[2],
            DVec3::new(1.0, 1.0, 0.0),
            "{format}"
        );
        assert_eq!(
            loaded.mesh.triangles(),
            &[[0, 1, 2], [0, 2, 3], [0, 2, 3]],
            "{format}"
        );
    }
}

#[test]
fn ply_truncated_binary_reports_byte_offset_and_counts() {
    let mut bytes = rich_ply_header("binary_little_endian").into_bytes();
    let header_len = bytes.len() as u64;
    bytes.extend(rich_binary_body(false));
    // The last 8 bytes are the edge record; cutting 10 bytes ends inside the second face.
    let (loc, reason) = parse_error(&bytes[..bytes.len() - 10], Format::Ply);
    // Second face record: after 4 vertices (4+1+8+1+4 bytes each, plus a 2-byte list
    // item in the odd ones) and the first face (1+1+16+8 bytes).
    let second_face = header_len + 4 * 18 + 2 * 2 + 26;
    assert_eq!(loc, Location::Byte(second_face));
    assert_eq!(
        reason,
        ParseReason::MissingRecords {
            element: "face".to_owned(),
            expected: 2,
            found: 1
        }
    );
}

#[test]
fn ply_errors() {
    let header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    let with = |body: &str| format!("{header}{body}");
    assert_eq!(
        parse_error(
            with("0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").as_bytes(),
            Format::Ply
        ),
        (
            Location::Line(13),
            ParseReason::IndexOutOfRange {
                index: 3,
                vertex_count: 3
            }
        )
    );
    assert_eq!(
        parse_error(with("0 0 0\n1 0 0\n0 1 0\n2 0 1\n").as_bytes(), Format::Ply),
        (
            Location::Line(13),
            ParseReason::TooFewFaceVertices { count: 2 }
        )
    );
    assert!(matches!(
        parse_error(
            with("0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n").as_bytes(),
            Format::Ply
        ),
        (
            Location::Line(11),
            ParseReason::NonFiniteCoordinate {
                vertex: 1,
                axis: 'y',
                ..
            }
        )
    ));
    assert_eq!(
        parse_error(with("0 0 0\n1 0\n").as_bytes(), Format::Ply),
        (
            Location::Line(11),
            ParseReason::MissingValues {
                expected: 3,
                found: 2
            }
        )
    );
    assert_eq!(
        parse_error(with("0 0 0\n1 0 0 0\n").as_bytes(), Format::Ply),
        (
            Location::Line(11),
            ParseReason::TooManyValues {
                expected: 3,
                found: 4
            }
        )
    );
    assert_eq!(
        parse_error(with("0 0 0\n1 0 0\n").as_bytes(), Format::Ply),
        (
            Location::Line(12),
            ParseReason::MissingRecords {
                element: "vertex".to_owned(),
                expected: 3,
                found: 2
            }
        )
    );
    assert!(matches!(
        parse_error(
            with("0 0 0\n1 0 0\n0 1 0\n3 0 1 x\n").as_bytes(),
            Format::Ply
        ),
        (Location::Line(13), ParseReason::InvalidNumber { .. })
    ));
    assert_eq!(
        parse_error(b"", Format::Ply),
        (Location::Line(1), ParseReason::EmptyFile)
    );
    assert_eq!(
        parse_error(b"plx\n", Format::Ply),
        (Location::Line(1), ParseReason::BadMagic { expected: "ply" })
    );
    assert!(matches!(
        parse_error(
            b"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n",
            Format::Ply
        ),
        (Location::Line(4), ParseReason::UnexpectedToken { .. })
    ));
    assert!(matches!(
        parse_error(
            b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n",
            Format::Ply
        ),
        (Location::Line(5), ParseReason::UnexpectedEnd { .. })
    ));
    assert_eq!(
        parse_error(
            b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
            Format::Ply
        ),
        (
            Location::Line(3),
            ParseReason::MissingProperty {
                element: "vertex",
                property: "z"
            }
        )
    );
}

#[test]
fn ply_face_element_before_vertex_element() {
    let ply = "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\nend_header\n3 2 1 0\n0 0 0\n1 0 0\n0 1 0\n";
    let loaded = read_from_bytes(ply.as_bytes(), Format::Ply).unwrap();
    assert_eq!(loaded.mesh.triangles(), &[[2, 1, 0]]);
}

#[test]
fn round_trips_are_bit_exact() {
    let mesh = tetrahedron();
    let mut obj = Vec::new();
    write_obj_to(&mut obj, &mesh).unwrap();
    assert_eq!(read_from_bytes(&obj, Format::Obj).unwrap().mesh, mesh);
    for encoding in [PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian] {
        for colors in [None, Some(&[[1, 2, 3]; 4][..])] {
            let mut ply = Vec::new();
            write_ply_to(&mut ply, &mesh, encoding, colors).unwrap();
            let back = read_from_bytes(&ply, Format::Ply).unwrap().mesh;
            // Bitwise, so -0.0 and tiny values count.
            let bits = |m: &TriMesh| -> Vec<u64> {
                m.positions()
                    .iter()
                    .flat_map(|p| p.to_array().map(f64::to_bits))
                    .collect()
            };
            assert_eq!(bits(&back), bits(&mesh), "{encoding:?}");
            assert_eq!(back.triangles(), mesh.triangles());
        }
    }
}

#[test]
fn colors_must_match_vertex_count() {
    let mesh = tetrahedron();
    let err = write_ply_to(
        &mut Vec::new(),
        &mesh,
        PlyEncoding::Ascii,
        Some(&[[0, 0, 0]]),
    )
    .unwrap_err();
    assert!(matches!(
        err,
        IoError::VertexCountMismatch {
            expected: 4,
            actual: 1
        }
    ));
}

#[test]
fn files_round_trip_and_errors_name_the_path() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = tetrahedron();
    for name in ["a.obj", "b.PLY", "c.mesh"] {
        let path = dir.path().join(name);
        if name.ends_with("mesh") {
            write_obj(&path, &mesh).unwrap();
        } else {
            save(&path, &mesh).unwrap();
        }
        assert_eq!(load(&path).unwrap(), mesh, "{name}");
    }
    // No temporary files are left behind.
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(names.len(), 3, "{names:?}");

    let bad = dir.path().join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nf 1 1 1 \nf 1 1\n").unwrap();
    let message = read(&bad).unwrap_err().to_string();
    assert!(message.contains("bad.obj at line 3"), "{message}");

    let unknown = dir.path().join("noise.bin");
    std::fs::write(&unknown, "hello").unwrap();
    assert!(matches!(read(&unknown), Err(IoError::UnknownFormat { .. })));
    assert!(matches!(
        read(dir.path().join("missing.obj")),
        Err(IoError::Io { .. })
    ));
    // A failed write leaves nothing behind and reports the target path.
    let err = write_obj(dir.path().join("no-such-dir").join("x.obj"), &mesh).unwrap_err();
    assert!(err.to_string().contains("x.obj"), "{err}");
}

#[test]
fn sniffing() {
    assert_eq!(Format::sniff(b"ply\nformat ascii 1.0\n"), Some(Format::Ply));
    assert_eq!(Format::sniff(b"# c\nCOFF\n"), Some(Format::Off));
    assert_eq!(Format::sniff(b"solid x\nfacet"), Some(Format::Stl));
    assert_eq!(
        Format::sniff(b"# blender\nmtllib a.mtl\nv 1 2 3\n"),
        Some(Format::Obj)
    );
    let mut binary = vec![0u8; 84];
    binary[..5].copy_from_slice(b"hello");
    assert_eq!(Format::sniff(&binary), Some(Format::Stl));
    assert_eq!(Format::sniff(b"\x00\x01garbage"), None);
    assert_eq!(Format::sniff(b"glTF\x02\x00\x00\x00"), Some(Format::Gltf));
    assert_eq!(
        Format::sniff(b"\xef\xbb\xbf \n{\n  \"asset\": {\"version\": \"2.0\"}}"),
        Some(Format::Gltf)
    );
    assert_eq!(Format::sniff(b"{\"other\": 1}"), None);
    for extension in ["gltf", "GLB", "Gltf"] {
        assert_eq!(Format::from_extension(extension), Some(Format::Gltf));
    }
    assert_eq!(Format::Gltf.to_string(), "glTF");
}

/// Without the `gltf` feature, glTF is still recognised, and reading it is a clear error.
#[cfg(not(feature = "gltf"))]
#[test]
fn gltf_without_the_feature_is_a_clear_error() {
    let err = read_from_bytes(b"glTF\x02\0\0\0\x0c\0\0\0", Format::Gltf).unwrap_err();
    assert_eq!(
        err.to_string(),
        "malformed glTF data at byte offset 0: reading glTF without the `gltf` feature of sphaera-mesh is not supported"
    );
    assert_eq!(Format::from_extension("glb"), Some(Format::Gltf));
}

#[test]
fn garbage_bytes_are_errors_in_every_format() {
    let garbage = b"\x00\xff\x13garbage\x89PNG\r\n\x1a\n";
    for format in ALL_FORMATS {
        assert!(read_from_bytes(garbage, format).is_err(), "{format}");
        assert!(read_from_bytes(b"", format).is_err(), "{format}");
    }
}

/// Valid files of every format, for the truncation property: `(format, bytes, binary)`.
fn samples() -> Vec<(Format, Vec<u8>, bool)> {
    let mesh = tetrahedron();
    let mut obj = Vec::new();
    write_obj_to(&mut obj, &mesh).unwrap();
    let mut ply_ascii = Vec::new();
    write_ply_to(
        &mut ply_ascii,
        &mesh,
        PlyEncoding::Ascii,
        Some(&[[9, 8, 7]; 4]),
    )
    .unwrap();
    let mut ply_binary = Vec::new();
    write_ply_to(
        &mut ply_binary,
        &mesh,
        PlyEncoding::BinaryLittleEndian,
        None,
    )
    .unwrap();
    let mut ply_rich = rich_ply_header("binary_big_endian").into_bytes();
    ply_rich.extend(rich_binary_body(true));
    let stl_ascii = b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n".to_vec();
    let mut stl_binary = vec![0u8; 80];
    stl_binary.extend_from_slice(&2u32.to_le_bytes());
    for k in 0..2u8 {
        stl_binary.extend_from_slice(&[0; 12]);
        for c in [
            [0.0f32, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, f32::from(k)],
        ] {
            for v in c {
                stl_binary.extend_from_slice(&v.to_le_bytes());
            }
        }
        stl_binary.extend_from_slice(&[0; 2]);
    }
    // The same binary STL with a header that starts with `solid`, as CAD exporters write.
    let mut stl_solid_binary = stl_binary.clone();
    let header = b"solid exported by a CAD tool";
    stl_solid_binary[..header.len()].copy_from_slice(header);
    let off = b"OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 1 2 3\n".to_vec();
    let samples = vec![
        (Format::Obj, obj, false),
        (Format::Ply, ply_ascii, false),
        (Format::Ply, ply_binary, true),
        (Format::Ply, ply_rich, true),
        (Format::Stl, stl_ascii, false),
        (Format::Stl, stl_binary, true),
        (Format::Off, off, false),
        (Format::Stl, stl_solid_binary, true),
    ];
    #[cfg(feature = "gltf")]
    let samples = {
        use super::gltf::test_writer::{GltfWriter, mesh_glb, to_f32};
        let mut samples = samples;
        use serde_json::json;
        // A GLB with a node transform, and a .gltf with a data URI holding a strip.
        samples.push((
            Format::Gltf,
            mesh_glb(&mesh, json!({ "scale": [1.0, 2.0, 3.0] })),
            true,
        ));
        let mut writer = GltfWriter::default();
        let points: Vec<[f32; 3]> = mesh.positions().iter().map(|&p| to_f32(p)).collect();
        let positions = writer.positions(&points);
        writer.mesh(json!([{ "attributes": { "POSITION": positions }, "mode": 5 }]));
        writer.node(json!({ "mesh": 0 }));
        samples.push((Format::Gltf, writer.gltf_with_data_uri(), false));
        samples
    };
    samples
}

/// Every strict prefix of a valid binary file is an error: a binary file cut short never
/// loads as a smaller mesh (nor as an empty one).
#[test]
fn strict_prefixes_of_binary_files_are_errors() {
    for (format, bytes, binary) in samples() {
        if !binary {
            continue;
        }
        for len in 0..bytes.len() {
            assert!(
                read_from_bytes(&bytes[..len], format).is_err(),
                "{format} prefix of {len} of {} bytes loaded",
                bytes.len()
            );
        }
    }
}

#[test]
fn samples_are_valid() {
    for (format, bytes, _) in samples() {
        assert!(read_from_bytes(&bytes, format).is_ok(), "{format}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(256)))]

    /// Random bytes never panic any reader (nor sniffing).
    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        let _ = Format::sniff(&bytes);
        for format in ALL_FORMATS {
            let _ = read_from_bytes(&bytes, format);
        }
    }

    /// Random text made of the formats' own vocabulary never panics either (it reaches
    /// deeper than random bytes).
    #[test]
    fn random_token_soup_never_panics(
        words in prop::collection::vec(
            prop::sample::select(vec![
                "v", "f", "-1", "0", "1", "2", "3", "4", "1e9", "nan", "1/2/3", "//", "\\", "\n",
                "\n", "ply", "format", "ascii", "1.0", "binary_big_endian", "element", "vertex",
                "face", "property", "list", "uchar", "int", "float", "x", "y", "z",
                "vertex_indices", "end_header", "OFF", "solid", "facet", "outer", "loop",
                "endloop", "#", "-4294967296", "99999999999", "{", "}", "[", "]", ":", ",",
                "\"asset\"", "\"version\"", "\"2.0\"", "\"meshes\"", "\"nodes\"",
                "\"primitives\"", "\"attributes\"", "\"POSITION\"", "\"accessors\"",
                "\"count\"", "\"buffers\"", "\"uri\"", "\"data:,\"",
            ]),
            0..80,
        )
    ) {
        let text = words.join(" ");
        for format in ALL_FORMATS {
            let _ = read_from_bytes(text.as_bytes(), format);
        }
    }

    /// Truncating or corrupting a valid file gives an error or a mesh, never a panic;
    /// a strict prefix of a binary file (uncorrupted) is always an error.
    #[test]
    fn truncations_and_corruptions_never_panic(
        sample in 0usize..samples().len(),
        cut in 0.0f64..1.0,
        flip in prop::option::of((0.0f64..1.0, any::<u8>())),
    ) {
        let all = samples();
        let (format, bytes, binary) = &all[sample];
        let mut bytes = bytes[..(cut * bytes.len() as f64) as usize].to_vec();
        if let Some((at, value)) = flip
            && !bytes.is_empty()
        {
            let i = ((at * bytes.len() as f64) as usize).min(bytes.len() - 1);
            bytes[i] = value;
        }
        let result = read_from_bytes(&bytes, *format);
        if *binary && flip.is_none() {
            prop_assert!(result.is_err(), "{} prefix of {} bytes loaded", format, bytes.len());
        }
    }
}

#[test]
fn non_convex_and_non_planar_polygons_are_reported() {
    // An L-shaped hexagon (non-convex) and a bent quad (non-planar).
    let obj = b"v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 1\nv 1 0 1\nv 1 1 1.5\nv 0 1 1\n\
        f 1 2 3 4 5 6\nf 7 8 9 10\nf 1 2 3\n";
    let loaded = read_from_bytes(obj, Format::Obj).unwrap();
    let report = loaded.report;
    assert_eq!(report.faces_in_file, 3);
    assert_eq!(report.polygons_triangulated, 2);
    assert_eq!(report.non_convex_polygons, 1);
    assert_eq!(report.non_planar_polygons, 1);
    assert_eq!(report.fan_fallbacks, 0);
    assert_eq!(loaded.mesh.triangle_count(), 4 + 2 + 1);
    // Polygon triangles stay in place: the last triangle is the last face.
    assert_eq!(loaded.mesh.triangles()[6], [0, 1, 2]);
    // The L is covered without overlap: its triangles' areas add up to 3.
    let l_area: f64 = loaded.mesh.triangle_iter().take(4).map(|t| t.area()).sum();
    assert!((l_area - 3.0).abs() < 1e-12);
}

fn finite_f64() -> impl Strategy<Value = f64> {
    any::<f64>().prop_filter("finite", |v| v.is_finite())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    /// Writing then reading gives the same mesh, bit for bit, in OBJ and both PLY
    /// encodings, for arbitrary finite coordinates (subnormals, -0.0, 1e308...).
    #[test]
    fn write_then_read_is_identity(
        coords in prop::collection::vec([finite_f64(), finite_f64(), finite_f64()], 3..12),
        picks in prop::collection::vec([any::<u32>(), any::<u32>(), any::<u32>()], 0..16),
    ) {
        let n = coords.len() as u32;
        let mesh = TriMesh::new(
            coords.iter().map(|c| DVec3::from_array(*c)).collect(),
            picks.iter().map(|t| t.map(|i| i % n)).collect(),
        ).unwrap();
        let bits = |m: &TriMesh| -> Vec<u64> {
            m.positions().iter().flat_map(|p| p.to_array().map(f64::to_bits)).collect()
        };
        let mut obj = Vec::new();
        write_obj_to(&mut obj, &mesh).unwrap();
        let back = read_from_bytes(&obj, Format::Obj).unwrap().mesh;
        prop_assert_eq!(bits(&back), bits(&mesh));
        prop_assert_eq!(back.triangles(), mesh.triangles());
        for encoding in [PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian] {
            let mut ply = Vec::new();
            write_ply_to(&mut ply, &mesh, encoding, None).unwrap();
            let back = read_from_bytes(&ply, Format::Ply).unwrap().mesh;
            prop_assert_eq!(bits(&back), bits(&mesh));
            prop_assert_eq!(back.triangles(), mesh.triangles());
        }
    }
}

#[test]
fn ply_nan_float_index_is_reported_as_non_integer_not_out_of_range() {
    let header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
        property float y\nproperty float z\nelement face 1\nproperty list uchar float vertex_indices\n\
        end_header\n";
    let mut ply = header.as_bytes().to_vec();
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        ply.extend_from_slice(&v.to_le_bytes());
    }
    let face_start = ply.len() as u64;
    ply.push(3);
    for v in [0.0f32, f32::NAN, 2.0] {
        ply.extend_from_slice(&v.to_le_bytes());
    }
    let (location, reason) = parse_error(&ply, Format::Ply);
    assert_eq!(location, Location::Byte(face_start));
    assert!(matches!(reason, ParseReason::NonIntegerIndex { value } if value.is_nan()));
    assert!(reason.to_string().contains("not an integer"), "{reason}");
    // An ASCII float index of 1.5 is non-integer too; 7.0 is out of range.
    let ascii = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
        property float z\nelement face 1\nproperty list uchar double vertex_indices\nend_header\n\
        0 0 0\n1 0 0\n0 1 0\n";
    assert_eq!(
        parse_error(format!("{ascii}3 0 1.5 2\n").as_bytes(), Format::Ply),
        (
            Location::Line(13),
            ParseReason::NonIntegerIndex { value: 1.5 }
        )
    );
    assert_eq!(
        parse_error(format!("{ascii}3 0 7.0 2\n").as_bytes(), Format::Ply),
        (
            Location::Line(13),
            ParseReason::IndexOutOfRange {
                index: 7,
                vertex_count: 3
            }
        )
    );
}

#[test]
fn ply_huge_element_counts_do_not_allocate_up_front() {
    // 2^60 faces (and records of an unknown element): the reader must reserve by what the
    // body can hold, then report the missing records.
    let huge = 1u64 << 60;
    for encoding in ["ascii", "binary_little_endian"] {
        let ply = format!(
            "ply\nformat {encoding} 1.0\nelement vertex 3\nproperty uchar x\nproperty uchar y\n\
             property uchar z\nelement face {huge}\nproperty list uchar uchar vertex_indices\n\
             element junk {huge}\nproperty uchar j\nend_header\n"
        );
        let (_, reason) = parse_error(ply.as_bytes(), Format::Ply);
        assert!(
            matches!(reason, ParseReason::MissingRecords { ref element, found: 0, .. } if element == "vertex"),
            "{encoding}: {reason}"
        );
    }
    let vertices = format!(
        "ply\nformat ascii 1.0\nelement vertex {huge}\nproperty float x\nproperty float y\n\
         property float z\nend_header\n"
    );
    assert_eq!(
        parse_error(vertices.as_bytes(), Format::Ply),
        (
            Location::Line(3),
            ParseReason::TooManyVertices { count: huge }
        )
    );
    let faces = "ply\nformat binary_little_endian 1.0\nelement face 1152921504606846976\n\
        property list uchar uchar vertex_indices\nelement vertex 3\nproperty uchar x\n\
        property uchar y\nproperty uchar z\nend_header\n\x03\x00\x01\x02";
    assert!(matches!(
        parse_error(faces.as_bytes(), Format::Ply).1,
        ParseReason::MissingRecords { found: 1, .. }
    ));
}

#[test]
fn stream_write_errors_do_not_show_an_empty_path() {
    struct Broken;
    impl std::io::Write for Broken {
        fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
            Err(std::io::Error::other("disk on fire"))
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let mesh = tetrahedron();
    let ply = write_ply_to(&mut Broken, &mesh, PlyEncoding::Ascii, None).unwrap_err();
    let obj = write_obj_to(&mut Broken, &mesh).unwrap_err();
    for err in [ply, obj] {
        assert!(matches!(err, IoError::Io { .. }));
        assert_eq!(err.to_string(), "cannot access <stream>: disk on fire");
    }
}
