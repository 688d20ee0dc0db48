//! End-to-end tests of `sphaera medial`.

mod common;

use common::{json, sphaera};

#[test]
fn medial_of_the_embedded_bunny_covers_every_sample_and_writes_the_spheres() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("spheres.json");
    let report = json(&sphaera(&[
        "medial",
        "--json",
        "--spheres",
        "200",
        "--samples",
        "3000",
        "-o",
        path.to_str().expect("utf-8"),
    ]));
    assert_eq!(report["method"], "adaptive");
    assert_eq!(report["uncovered_samples"], 0);
    assert!(report["spheres"].as_u64().expect("count") >= 200);
    let file: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&path).expect("written")).expect("JSON");
    let spheres = file["spheres"].as_array().expect("an array");
    assert_eq!(
        spheres.len() as u64,
        report["spheres"].as_u64().expect("count")
    );
    let worst = spheres
        .iter()
        .map(|s| s["error"].as_f64().expect("error"))
        .fold(0.0, f64::max);
    assert!((worst - report["worst_error"].as_f64().expect("worst")).abs() < 1e-12);
}

#[test]
fn medial_error_target_and_static_baseline() {
    let report = json(&sphaera(&[
        "medial",
        "--json",
        "--max-error",
        "3%",
        "--samples",
        "2000",
    ]));
    assert!(report["worst_error_relative"].as_f64().expect("relative") <= 0.03);
    let baseline = json(&sphaera(&[
        "medial",
        "--json",
        "--static-points",
        "150",
        "--samples",
        "2000",
    ]));
    assert_eq!(baseline["method"], "static");
    assert_eq!(baseline["cover_spheres"], 0);
}

#[test]
fn medial_of_a_flat_sheet_is_a_clear_error() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("sheet.obj");
    std::fs::write(
        &path,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n",
    )
    .expect("written");
    let output = sphaera(&["medial", path.to_str().expect("utf-8")]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("no meaningful inside"), "{message}");
}
