//! Hostile input through the binary (issue 38): every case is a one-line error naming the
//! problem, within seconds, a non-zero exit, and an existing output left as it was.

mod common;

use std::path::Path;
use std::process::Output;
use std::time::{Duration, Instant};

use common::sphaera;

/// What an output file held before a failed run: it must hold it after.
const BEFORE: &str = "an output from an earlier run\n";

/// Runs `args`, which must fail at once with a one-line error containing `needle`.
fn refused(args: &[&str], needle: &str) -> Output {
    let started = Instant::now();
    let output = sphaera(args);
    let seconds = started.elapsed();
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{args:?} succeeded");
    assert!(message.contains(needle), "{args:?}: {message}");
    assert_eq!(message.trim_end().lines().count(), 1, "{args:?}: {message}");
    assert!(seconds < Duration::from_secs(20), "{args:?}: {seconds:?}");
    output
}

/// An output file holding [`BEFORE`].
fn existing_output(dir: &Path, name: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, BEFORE).expect("write");
    path.to_str().expect("UTF-8").to_owned()
}

fn unchanged(path: &str) {
    assert_eq!(
        std::fs::read_to_string(path).expect("read"),
        BEFORE,
        "{path}"
    );
}

/// A glTF triangle whose one buffer is the file `uri` (the bytes the buffer must hold:
/// three `f32` positions and three `u16` indices).
fn gltf_naming(uri: &str) -> (String, Vec<u8>) {
    let mut bin: Vec<u8> = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    bin.extend([0u16, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    bin.extend([0, 0]);
    let document = serde_json::json!({
        "asset": { "version": "2.0" },
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [{ "byteLength": bin.len(), "uri": uri }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 36 },
            { "buffer": 0, "byteOffset": 36, "byteLength": 6 }
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
              "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR" }
        ]
    });
    (document.to_string(), bin)
}

#[test]
fn parameters_that_size_memory_are_refused_before_any_work() {
    let dir = tempfile::tempdir().expect("a folder");
    let out = existing_output(dir.path(), "out.obj");
    refused(
        &["silhouette", "-q", "--step", "0.00001", "-o", &out],
        "step",
    );
    refused(
        &["silhouette", "-q", "--resolution", "4000000000", "-o", &out],
        "resolution",
    );
    unchanged(&out);
    let tree = existing_output(dir.path(), "tree.json");
    refused(
        &["spheretree", "-q", "--depth", "1000", "-o", &tree],
        "depth",
    );
    refused(
        &["spheretree", "-q", "--branch", "100000000", "-o", &tree],
        "branch",
    );
    unchanged(&tree);
}

#[test]
fn devices_pipes_and_folders_named_as_meshes_are_refused_at_once() {
    let dir = tempfile::tempdir().expect("a folder");
    let out = existing_output(dir.path(), "out.obj");
    #[cfg(unix)]
    {
        refused(&["info", "/dev/zero"], "it is a device, not a regular file");
        refused(
            &["simplify", "/dev/zero", "--ratio", "0.5", "-o", &out],
            "it is a device",
        );
        let pipe = dir.path().join("pipe.obj");
        let made = std::process::Command::new("mkfifo").arg(&pipe).status();
        assert!(
            made.is_ok_and(|s| s.success()),
            "mkfifo is part of coreutils"
        );
        refused(&["info", pipe.to_str().expect("UTF-8")], "a named pipe");
        // A scene naming a device: the scene's mesh entry and the reason.
        let scene = dir.path().join("scene.json");
        std::fs::write(
            &scene,
            r#"{ "meshes": { "zero": "/dev/zero" }, "instances": [ { "mesh": "zero" } ] }"#,
        )
        .expect("write");
        refused(
            &["scene", "-q", scene.to_str().expect("UTF-8")],
            "meshes.zero",
        );
        // A URDF naming a device as a link's mesh.
        let urdf = dir.path().join("robot.urdf");
        std::fs::write(
            &urdf,
            r#"<robot name="r"><link name="base"><collision><geometry><mesh filename="file:///dev/zero"/></geometry></collision></link></robot>"#,
        )
        .expect("write");
        let spheres = existing_output(dir.path(), "spheres.urdf");
        refused(
            &["urdf", urdf.to_str().expect("UTF-8"), "-q", "-o", &spheres],
            "it is a device",
        );
        unchanged(&spheres);
    }
    refused(
        &["info", dir.path().to_str().expect("UTF-8")],
        "it is a folder",
    );
    unchanged(&out);
}

#[test]
fn gltf_buffers_may_not_leave_the_assets_folder() {
    let outer = tempfile::tempdir().expect("a folder");
    let asset = outer.path().join("asset");
    std::fs::create_dir_all(&asset).expect("mkdir");
    let out = existing_output(outer.path(), "out.obj");
    let (_, bin) = gltf_naming("");
    // A readable file outside the asset's folder, right for the buffer: never read.
    let secret = outer.path().join("secret.bin");
    std::fs::write(&secret, &bin).expect("write");
    let gltf = asset.join("scene.gltf");
    let gltf_arg = gltf.to_str().expect("UTF-8");
    for (uri, needle) in [
        ("../secret.bin".to_owned(), "outside the allowed folder"),
        (secret.display().to_string(), "an absolute path"),
        ("%2e%2e/secret.bin".to_owned(), "outside the allowed folder"),
    ] {
        std::fs::write(&gltf, gltf_naming(&uri).0).expect("write");
        refused(&["info", gltf_arg], needle);
        refused(
            &["simplify", gltf_arg, "--ratio", "0.5", "-o", &out],
            needle,
        );
    }
    unchanged(&out);
    // The same buffer beside the asset is read.
    std::fs::write(asset.join("inside.bin"), &bin).expect("write");
    std::fs::write(&gltf, gltf_naming("inside.bin").0).expect("write");
    let output = sphaera(&["info", gltf_arg]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// `--max-file-bytes` caps every file the run reads, the files a scene or a URDF names
/// included: a file over the cap is refused with its size, one under it is read, and a cap
/// of zero is refused by the parser.
#[test]
fn the_file_size_cap_applies_to_every_file_read() {
    let dir = tempfile::tempdir().expect("a folder");
    let mesh = dir.path().join("tetra.obj");
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::fs::write(&mesh, text).expect("write");
    let mesh = mesh.to_str().expect("UTF-8");
    let size = text.len().to_string();
    let under = (text.len() - 1).to_string();
    refused(
        &["info", mesh, "--max-file-bytes", &under],
        &format!("it is {size} bytes, more than the cap of {under} bytes"),
    );
    let read = sphaera(&["info", mesh, "--max-file-bytes", &size]);
    assert!(read.status.success(), "{read:?}");
    // The scene file is small; the mesh it names is over the cap.
    let scene = dir.path().join("scene.json");
    std::fs::write(
        &scene,
        r#"{ "meshes": { "tetra": "tetra.obj" }, "instances": [ { "mesh": "tetra" } ] }"#,
    )
    .expect("write");
    let scene = scene.to_str().expect("UTF-8");
    refused(
        &["scene", "-q", scene, "--max-file-bytes", &under],
        "more than the cap",
    );
    // So is a URDF link's mesh.
    let urdf = dir.path().join("robot.urdf");
    std::fs::write(
        &urdf,
        r#"<robot name="r"><link name="base"><collision><geometry><mesh filename="tetra.obj"/></geometry></collision></link></robot>"#,
    )
    .expect("write");
    let spheres = existing_output(dir.path(), "spheres.urdf");
    refused(
        &[
            "urdf",
            urdf.to_str().expect("UTF-8"),
            "-q",
            "-o",
            &spheres,
            "--max-file-bytes",
            &under,
        ],
        "more than the cap",
    );
    unchanged(&spheres);
    let zero = sphaera(&["info", mesh, "--max-file-bytes", "0"]);
    assert!(!zero.status.success());
    let message = String::from_utf8_lossy(&zero.stderr);
    assert!(message.contains("would refuse every file"), "{message}");
}
