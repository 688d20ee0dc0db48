//! The input fuzz targets' bodies ([`sphaera_tests::input_fuzz`]) on bytes from proptest,
//! so that every CI run exercises what `cargo +nightly fuzz run mesh_files` (and `gltf`,
//! `scene_json`, `urdf`) explores for hours: arbitrary bytes, and bytes shaped like each
//! format so that the readers get past their first line.

use proptest::prelude::*;
use sphaera_tests::input_fuzz::{gltf, mesh_files, scene_json, urdf};

/// Text made of a format's tokens, numbers and separators.
fn tokens(words: &'static [&'static str]) -> impl Strategy<Value = Vec<u8>> {
    let word = prop_oneof![
        prop::sample::select(words).prop_map(str::to_owned),
        any::<i32>().prop_map(|n| n.to_string()),
        prop::sample::select(&["1e308", "-1e-320", "nan", "inf", "0.5", "-0", "4294967296"][..])
            .prop_map(str::to_owned),
        prop::sample::select(
            &[
                " ", "\n", "/", "//", "\t", "#", "\\\n", "{", "}", "[", "]", ",", ":", "\"", "<",
                ">", "=", "%20"
            ][..]
        )
        .prop_map(str::to_owned),
    ];
    prop::collection::vec(word, 0..200).prop_map(|words| words.concat().into_bytes())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(256)))]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..600)) {
        mesh_files(&bytes);
        gltf(&bytes);
        scene_json(&bytes);
        urdf(&bytes);
    }

    #[test]
    fn mesh_text_never_panics(bytes in tokens(&[
        "v", "f", "vn", "vt", "l", "ply", "format ascii 1.0", "format binary_little_endian 1.0",
        "element vertex", "element face", "property float x", "property float y",
        "property float z", "property list uchar int vertex_indices", "end_header", "OFF",
        "solid", "facet normal", "outer loop", "vertex", "endloop", "endfacet", "endsolid",
    ])) {
        mesh_files(&bytes);
    }

    #[test]
    fn gltf_json_never_panics(bytes in tokens(&[
        "\"asset\"", "\"version\"", "\"2.0\"", "\"buffers\"", "\"byteLength\"", "\"uri\"",
        "\"data:application/octet-stream;base64,AAAA\"", "\"bufferViews\"", "\"buffer\"",
        "\"byteOffset\"", "\"byteStride\"", "\"accessors\"", "\"bufferView\"", "\"count\"",
        "\"componentType\"", "5126", "5125", "5123", "\"type\"", "\"VEC3\"", "\"SCALAR\"",
        "\"meshes\"", "\"primitives\"", "\"attributes\"", "\"POSITION\"", "\"indices\"",
        "\"mode\"", "\"nodes\"", "\"mesh\"", "\"children\"", "\"matrix\"", "\"scale\"",
        "\"scenes\"", "\"scene\"", "\"sparse\"", "\"min\"", "\"max\"",
    ])) {
        let mut shaped = vec![0];
        shaped.extend(&bytes);
        gltf(&shaped);
        shaped[0] = 1;
        gltf(&shaped);
    }

    #[test]
    fn scene_json_never_panics(bytes in tokens(&[
        "\"meshes\"", "\"instances\"", "\"mesh\"", "\"name\"", "\"position\"",
        "\"rotation_degrees\"", "\"quaternion\"", "\"scale\"", "\"camera\"", "\"eye\"",
        "\"target\"", "\"fov_y_degrees\"", "\"width\"", "\"height\"", "\"near\"", "\"a.obj\"",
        "null", "true",
    ])) {
        scene_json(&bytes);
    }

    #[test]
    fn urdf_never_panics(bytes in tokens(&[
        "<robot name=\"r\">", "</robot>", "<link name=\"a\">", "<link name=\"b\"/>", "</link>",
        "<joint name=\"j\" type=\"revolute\">", "<joint name=\"k\" type=\"fixed\">", "</joint>",
        "<parent link=\"a\"/>", "<child link=\"b\"/>", "<origin xyz=\"0 0 1\" rpy=\"0 0 1\"/>",
        "<axis xyz=\"0 0 1\"/>", "<mimic joint=\"j\"/>", "<mimic joint=\"k\"/>",
        "<collision>", "</collision>", "<geometry>", "</geometry>", "<box size=\"1 1 1\"/>",
        "<sphere radius=\"1\"/>", "<mesh filename=\"package://x/y.stl\"/>",
    ])) {
        urdf(&bytes);
    }
}
