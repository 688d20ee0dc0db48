//! End-to-end tests of `sphaera info`: the binary as a user runs it.

use std::process::{Command, Output};

fn sphaera(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sphaera"))
        .args(args)
        .output()
        .expect("the sphaera binary runs")
}

fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn info_without_arguments_describes_the_embedded_bunny() {
    let output = sphaera(&["info"]);
    assert!(output.status.success(), "stderr: {}", stderr(&output));
    let text = stdout(&output);
    assert!(text.contains("3,674"), "triangle count missing:\n{text}");
    assert!(text.contains("closed"), "{text}");
}

#[test]
fn info_json_matches_the_data_readme_for_the_embedded_bunny() {
    let output = sphaera(&["info", "--json"]);
    assert!(output.status.success(), "stderr: {}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("valid JSON");
    assert_eq!(json["triangles"], 3674);
    assert_eq!(json["vertex_records"], 1839);
    assert_eq!(json["topology"]["closed"], true);
    assert_eq!(json["topology"]["manifold"], true);
    assert_eq!(json["topology"]["genus"], 0);
    assert_eq!(json["topology"]["components"], 1);
    assert_eq!(json["topology"]["boundary_edges"], 0);
    assert_eq!(json["topology"]["euler_characteristic"], 2);
    let diagonal = json["bounding_box"]["diagonal"].as_f64().expect("a number");
    assert!((diagonal - 15.76).abs() < 0.01, "diagonal {diagonal}");
}

#[test]
fn info_reads_a_file_and_reports_an_open_mesh() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("two_triangles.obj");
    std::fs::write(
        &path,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n",
    )
    .unwrap();
    let output = sphaera(&["info", path.to_str().unwrap(), "--json"]);
    assert!(output.status.success(), "stderr: {}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("valid JSON");
    assert_eq!(json["triangles"], 2);
    assert_eq!(json["topology"]["closed"], false);
    assert_eq!(json["topology"]["boundary_edges"], 4);
    assert_eq!(json["topology"]["boundary_loops"], 1);
    assert_eq!(json["topology"]["genus"], 0);
}

#[test]
fn info_on_a_missing_file_fails_on_stderr() {
    let output = sphaera(&["info", "/definitely/not/here.obj"]);
    assert!(!output.status.success());
    assert!(stdout(&output).is_empty());
    let message = stderr(&output);
    assert!(message.starts_with("error:"), "{message}");
    assert!(message.contains("/definitely/not/here.obj"), "{message}");
}

#[test]
fn info_on_a_malformed_file_names_the_line() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("bad.obj");
    std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n").unwrap();
    let output = sphaera(&["info", path.to_str().unwrap()]);
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(message.contains("line 4"), "{message}");
}

#[test]
fn info_on_garbage_bytes_fails_cleanly() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("garbage.ply");
    std::fs::write(&path, [0xffu8, 0x00, 0x13, 0x37, 0xde, 0xad, 0xbe, 0xef]).unwrap();
    let output = sphaera(&["info", path.to_str().unwrap(), "--json"]);
    assert!(!output.status.success());
    assert!(
        stdout(&output).is_empty(),
        "no half-written JSON on failure"
    );
    assert!(stderr(&output).starts_with("error:"));
}

/// `sphaera info --json` on every mesh of `shared/data` reports what the data README's
/// table says (closed, 2-manifold, genus, boundary edges, components, χ, counts).
#[test]
fn info_json_matches_the_data_readme_for_every_shared_mesh() {
    let Some(data) =
        sphaera_tests::data_dir("info_json_matches_the_data_readme_for_every_shared_mesh")
    else {
        return;
    };
    let mut failures = Vec::new();
    for expected in sphaera_tests::expected_stats(&data) {
        let path = data.join(&expected.file);
        let output = sphaera(&["info", "--quiet", "--json", path.to_str().unwrap()]);
        if !output.status.success() {
            failures.push(format!("{}: {}", expected.file, stderr(&output)));
            continue;
        }
        let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("valid JSON");
        let topology = &json["topology"];
        let got = (
            json["vertex_records"].as_u64(),
            json["triangles"].as_u64(),
            topology["closed"].as_bool(),
            topology["manifold"].as_bool(),
            topology["components"].as_u64(),
            topology["boundary_edges"].as_u64(),
            topology["genus"].as_i64(),
            topology["euler_characteristic"].as_i64(),
        );
        let want = (
            Some(expected.vertex_records as u64),
            Some(expected.triangles as u64),
            Some(expected.closed),
            Some(expected.manifold),
            Some(expected.components as u64),
            Some(expected.boundary_edges as u64),
            expected.genus,
            Some(expected.euler_characteristic),
        );
        if got != want {
            failures.push(format!("{}: got {got:?}, README {want:?}", expected.file));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn info_on_a_mesh_without_triangles_reports_no_surface() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("points.obj");
    std::fs::write(&path, "v 0 0 0\nv 1 0 0\n").unwrap();
    let output = sphaera(&["info", path.to_str().unwrap(), "--json"]);
    assert!(output.status.success(), "stderr: {}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("valid JSON");
    assert_eq!(json["triangles"], 0);
    assert!(json["bounding_box"].is_null());
    assert_eq!(json["surface_area"].as_f64(), Some(0.0));
    assert!(json["surface_area"].as_f64().unwrap().is_sign_positive());
    assert_eq!(json["topology"]["closed"], false);
    assert!(json["topology"]["genus"].is_null());
    let text = stdout(&sphaera(&["info", path.to_str().unwrap()]));
    assert!(text.contains("none (no triangles)"), "{text}");
}
