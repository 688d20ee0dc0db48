//! The bodies of the fuzz targets where input enters Sphaera (`fuzz/fuzz_targets/`:
//! `mesh_files`, `gltf`, `scene_json`, `urdf`), shared with the proptest replay in
//! `tests/tests/input_fuzz_replay.rs` so that every CI run exercises them.
//!
//! Each takes arbitrary bytes and panics only on a bug: a reader that panics, or accepts
//! data and returns something invalid (a non-finite position, an index out of range).
//! Errors are the expected answer to most inputs. Memory is bounded by the libFuzzer
//! options the targets run with (`-rss_limit_mb`, `-malloc_limit_mb`), and time by
//! `-timeout`: see `fuzz/README.md`.

use sphaera_io::{Format, read_from_bytes};
use sphaera_mesh::TriMesh;

/// Checks a mesh a reader accepted: finite positions, every index a vertex.
fn check_mesh(mesh: &TriMesh, format: Format) {
    let n = mesh.positions().len();
    assert!(
        mesh.positions().iter().all(|p| p.is_finite()),
        "{format:?}: a non-finite position was accepted"
    );
    assert!(
        mesh.triangles().iter().flatten().all(|&i| (i as usize) < n),
        "{format:?}: an index out of range was accepted"
    );
}

/// Every mesh reader on `data`: OBJ, PLY, STL, OFF and glTF/GLB (the format sniffed too).
///
/// # Panics
///
/// On a reader's panic, or an invalid mesh accepted.
pub fn mesh_files(data: &[u8]) {
    for format in [
        Format::Obj,
        Format::Ply,
        Format::Stl,
        Format::Off,
        Format::Gltf,
    ] {
        if let Ok(loaded) = read_from_bytes(data, format) {
            check_mesh(&loaded.mesh, format);
        }
    }
    if let Some(format) = Format::sniff(data)
        && let Ok(loaded) = read_from_bytes(data, format)
    {
        check_mesh(&loaded.mesh, format);
    }
}

/// The glTF reader on `data`, as a `.glb` container when the first byte is odd (the bytes
/// after it the JSON chunk, then a binary chunk of the rest split at byte 1's share),
/// else as JSON text: reaches deeper than [`mesh_files`] because the container is valid.
///
/// # Panics
///
/// On a panic of the reader, or an invalid mesh accepted.
pub fn gltf(data: &[u8]) {
    let Some((&first, rest)) = data.split_first() else {
        return;
    };
    let bytes = if first & 1 == 1 {
        let (&share, body) = rest.split_first().unwrap_or((&0, &[]));
        let split = body.len() * usize::from(share) / 256;
        let (json, bin) = body.split_at(split);
        glb(json, bin)
    } else {
        rest.to_vec()
    };
    if let Ok(loaded) = read_from_bytes(&bytes, Format::Gltf) {
        check_mesh(&loaded.mesh, Format::Gltf);
    }
}

/// A GLB container: the 12-byte header, a JSON chunk and a binary chunk (padded).
fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |bytes: &[u8], with: u8| {
        let mut out = bytes.to_vec();
        while !out.len().is_multiple_of(4) {
            out.push(with);
        }
        out
    };
    let (json, bin) = (pad(json, b' '), pad(bin, 0));
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    for value in [total, json.len()] {
        out.extend_from_slice(&u32::try_from(value).unwrap_or(u32::MAX).to_le_bytes());
    }
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&u32::try_from(bin.len()).unwrap_or(u32::MAX).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// A scene file's text: parsed and checked (its meshes are not read: the file names
/// them, and the file policy's tests cover reading).
///
/// # Panics
///
/// On a panic of the parser.
pub fn scene_json(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(description) = sphaera_scene::SceneDescription::parse("fuzz.json", text) {
        for name in description.used_meshes() {
            assert!(description.mesh_path(name).is_some(), "{name}");
        }
    }
}

/// A URDF's text: parsed and checked, then posed at its zero configuration (its meshes
/// are not read).
///
/// # Panics
///
/// On a panic of the parser or of the kinematics, or poses that are not finite for
/// finite joint origins.
pub fn urdf(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(urdf) = sphaera_robot::Urdf::parse(text, "fuzz.urdf") else {
        return;
    };
    let poses = urdf
        .link_poses(&std::collections::BTreeMap::new())
        .expect("a URDF that parsed is one tree: it poses");
    assert_eq!(poses.len(), urdf.links.len());
}
