//! End-to-end tests of `sphaera spheretree`.

mod common;

use common::{json, sphaera};

/// Small settings, so that the tests stay fast.
const LIGHT: [&str; 8] = [
    "--samples",
    "1500",
    "--initial-spheres",
    "100",
    "--min-spheres-per-node",
    "30",
    "--depth",
    "2",
];

fn run(extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["spheretree", "--json"];
    args.extend(LIGHT);
    args.extend(extra);
    json(&sphaera(&args))
}

#[test]
fn spheretree_of_the_embedded_bunny_covers_the_surface_at_every_level() {
    let report = run(&["--method", "expand", "--tolerance", "50%"]);
    let levels = report["levels"].as_array().expect("levels");
    assert_eq!(levels.len(), 3);
    assert_eq!(levels[0]["spheres"], 1);
    for level in levels {
        assert_eq!(level["uncovered_fraction"].as_f64(), Some(0.0), "{level}");
        let lower = level["worst_error_lower"].as_f64().expect("lower");
        let upper = level["worst_error_upper"].as_f64().expect("upper");
        assert!(lower <= upper);
        assert!(level["spheres"].as_u64().expect("count") <= 64);
    }
    // The root's error is below half the diagonal, so level 0 meets a 50 % tolerance.
    assert_eq!(report["level_for_tolerance"], 0);
}

#[test]
fn spheretree_writes_json_and_sph_atomically() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    for (name, method) in [
        ("tree.json", "merge"),
        ("tree.sph", "combined"),
        ("spheres.yaml", "expand"),
    ] {
        let path = dir.path().join(name);
        let report = run(&[
            "--method",
            method,
            "--no-evaluation",
            "-o",
            path.to_str().expect("utf-8"),
        ]);
        let text = std::fs::read_to_string(&path).expect("written");
        let spheres: u64 = report["levels"]
            .as_array()
            .expect("levels")
            .iter()
            .map(|l| l["spheres"].as_u64().expect("count"))
            .sum();
        if name.ends_with(".json") {
            let tree = sphaera::spheretree::export::tree_from_json(&text).expect("our JSON");
            assert_eq!(tree.nodes().len() as u64, spheres);
            assert_eq!(tree.coverage().len(), 3);
        } else if name.ends_with(".yaml") {
            // The deepest level's spheres, one `center`/`radius` pair each.
            assert!(text.starts_with("collision_spheres:"), "{text}");
            assert!(text.contains("\"bunny\":"), "{text}");
            let deepest = report["levels"][2]["spheres"].as_u64().expect("count");
            assert_eq!(text.matches("center:").count() as u64, deepest);
        } else {
            let file = sphaera::spheretree::export::read_sph(&text, sphaera::mesh::DVec3::ZERO)
                .expect("a valid .sph");
            assert_eq!((file.levels, file.branch), (3, 8));
            let used = file.nodes.iter().filter(|n| n.is_some()).count() as u64;
            assert_eq!(used, spheres);
        }
    }
    // No temporary files are left behind.
    assert_eq!(std::fs::read_dir(dir.path()).expect("listed").count(), 3);
}

#[test]
fn spheretree_bad_input_is_a_clear_error() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let triangle = dir.path().join("triangle.obj");
    std::fs::write(&triangle, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").expect("written");
    let output = sphaera(&["spheretree", triangle.to_str().expect("utf-8")]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("cannot build a sphere-tree"), "{message}");

    let output = sphaera(&["spheretree", "--branch", "0"]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("branch"));

    let output = sphaera(&["spheretree", "--error-fraction", "0"]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("error_fraction"));

    // A typo of a depth is refused at once, not run for hours.
    let output = sphaera(&["spheretree", "--depth", "1000"]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains("depth") && message.contains("at most 24"),
        "{message}"
    );

    let output = sphaera(&["spheretree", "-o", "tree.txt"]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("unknown output format"));
}

/// A missing folder, a folder in the file's place or a read-only file: a clear error
/// before any work, and nothing written or left behind.
#[test]
fn spheretree_refuses_a_bad_output_path_before_building() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let missing = dir.path().join("no such folder").join("tree.json");
    let folder = dir.path().join("tree.sph");
    std::fs::create_dir(&folder).expect("created");
    let read_only = dir.path().join("spheres.yaml");
    std::fs::write(&read_only, "keep me").expect("written");
    let mut permissions = std::fs::metadata(&read_only).expect("exists").permissions();
    permissions.set_readonly(true);
    std::fs::set_permissions(&read_only, permissions).expect("made read-only");
    for (path, expected) in [
        (&missing, "does not exist"),
        (&folder, "it is a folder"),
        (&read_only, "read-only"),
    ] {
        let output = sphaera(&["spheretree", "-o", path.to_str().expect("utf-8")]);
        assert!(!output.status.success());
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(message.contains(expected), "{message}");
        assert!(
            !message.contains("build"),
            "failed only after building: {message}"
        );
    }
    assert_eq!(
        std::fs::read_to_string(&read_only).expect("kept"),
        "keep me"
    );
    // Nothing else appeared: the folder, the read-only file.
    assert_eq!(std::fs::read_dir(dir.path()).expect("listed").count(), 2);
}
