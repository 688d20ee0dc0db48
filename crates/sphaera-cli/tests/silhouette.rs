//! End-to-end tests of `sphaera silhouette`: the report's bounds hold, the mesh and both
//! pictures are written and read back, awkward meshes and settings run, and every bad
//! argument is refused by name before anything is written.

mod common;

use std::path::Path;

use common::{json, sphaera};
use sphaera::mesh::{DVec3, TriMesh, io, shapes};

/// A small, fast setting: 30° between cameras, 128² cells.
const FAST: [&str; 4] = ["--step", "30", "--resolution", "128"];

fn run_json(extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["silhouette", "--json"];
    args.extend_from_slice(&FAST);
    args.extend_from_slice(extra);
    json(&sphaera(&args))
}

fn number(report: &serde_json::Value, key: &str) -> f64 {
    report[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} in {report}"))
}

#[test]
fn the_embedded_bunny_keeps_its_contour_and_writes_everything() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("view.obj");
    let labels = dir.path().join("labels.png");
    let compare = dir.path().join("compare.png");
    let report = run_json(&[
        "--view",
        "0.3,-0.4,0.8",
        "--error",
        "2%",
        "--factor",
        "0.25",
        "--nearest",
        "4",
        "-o",
        mesh.to_str().unwrap(),
        "--labels-png",
        labels.to_str().unwrap(),
        "--compare-png",
        compare.to_str().unwrap(),
    ]);
    assert_eq!(report["triangles_in"], 3674);
    // Both poles and five rings of twelve.
    assert_eq!(report["cameras"], 62);
    let error = number(&report, "error");
    assert!(number(&report, "contour_error") <= 0.25 * error * (1.0 + 1e-12));
    assert!(number(&report, "other_error") <= error * (1.0 + 1e-12));
    let out = report["triangles_out"].as_u64().unwrap();
    assert!(0 < out && out < 3674, "{out}");
    assert!(report["contour_triangles"].as_u64().unwrap() <= out);
    assert!(number(&report, "silhouette_pixels") > 1000.0);
    assert!(number(&report, "contour_displacement") >= 0.0);
    // The mesh reads back with the reported count; the pictures are 128² PNGs.
    let back = io::load(&mesh).unwrap();
    assert_eq!(back.triangle_count() as u64, out);
    for picture in [&labels, &compare] {
        let image = image::open(picture).unwrap();
        assert_eq!((image.width(), image.height()), (128, 128));
    }
}

#[test]
fn factor_zero_keeps_the_contour_exact_and_perspective_runs() {
    let report = run_json(&["--factor", "0", "--perspective", "3"]);
    assert!(number(&report, "contour_error") <= 0.0);
    assert!(
        report["projection"]
            .as_str()
            .unwrap()
            .contains("perspective")
    );
    // Resolution 1 and threshold 0 are legal, if coarse.
    let report = json(&sphaera(&[
        "silhouette",
        "--json",
        "--step",
        "30",
        "--resolution",
        "1",
        "--threshold",
        "0",
    ]));
    assert!(report["triangles_out"].as_u64().unwrap() > 0);
}

fn write(dir: &Path, name: &str, mesh: &TriMesh) -> String {
    let path = dir.join(name);
    io::save(&path, mesh).unwrap();
    path.to_str().unwrap().to_owned()
}

#[test]
fn open_non_manifold_and_far_away_meshes_run() {
    let dir = tempfile::tempdir().unwrap();
    // An open mesh: a sphere without its top cap (back faces visible through the hole).
    let sphere = shapes::sphere(1.0, 16).unwrap();
    let kept: Vec<[u32; 3]> = sphere
        .triangles()
        .iter()
        .copied()
        .filter(|t| t.iter().all(|&v| sphere.positions()[v as usize].z < 0.8))
        .collect();
    let open = TriMesh::new(sphere.positions().to_vec(), kept).unwrap();
    // Two spheres sharing one vertex (pinched, non-manifold there).
    let a = shapes::sphere(1.0, 10).unwrap();
    let top = a
        .positions()
        .iter()
        .position(|p| p.z > 0.999)
        .expect("a pole") as u32;
    let n = a.vertex_count() as u32;
    let mut positions = a.positions().to_vec();
    positions.extend(
        a.positions()
            .iter()
            .map(|p| DVec3::new(p.x, p.y, 2.0 - p.z)),
    );
    let mut triangles = a.triangles().to_vec();
    triangles.extend(a.triangles().iter().map(|t| {
        // Mirrored: reverse the order to keep it outward, and weld the pole.
        [t[0], t[2], t[1]].map(|v| if v == top { top } else { v + n })
    }));
    let pinched = TriMesh::new(positions, triangles).unwrap();
    // Far away and tiny.
    let tiny = TriMesh::new(
        sphere
            .positions()
            .iter()
            .map(|p| *p * 1e-6 + DVec3::splat(1e6))
            .collect(),
        sphere.triangles().to_vec(),
    )
    .unwrap();
    for (name, mesh) in [
        ("open.obj", &open),
        ("pinched.obj", &pinched),
        ("tiny.obj", &tiny),
    ] {
        let path = write(dir.path(), name, mesh);
        let report = run_json(&[&path]);
        let error = number(&report, "error");
        assert!(
            number(&report, "other_error") <= error * (1.0 + 1e-12),
            "{name}"
        );
        assert!(report["triangles_out"].as_u64().unwrap() > 0, "{name}");
    }
}

fn fails_with(args: &[&str], expected: &str) {
    let mut all = vec!["silhouette"];
    all.extend_from_slice(&FAST);
    all.extend_from_slice(args);
    let output = sphaera(&all);
    assert!(!output.status.success(), "{args:?} succeeded");
    let message = String::from_utf8_lossy(&output.stderr).to_lowercase();
    assert!(message.contains(expected), "{args:?}: {message}");
}

#[test]
fn bad_arguments_are_named_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let jpeg = dir.path().join("labels.jpg");
    fails_with(&["--labels-png", jpeg.to_str().unwrap()], "png");
    assert!(!jpeg.exists());
    let stl = dir.path().join("out.stl");
    fails_with(&["-o", stl.to_str().unwrap()], "stl");
    assert!(!stl.exists());
    fails_with(&["--view", "0,0,0"], "not zero");
    fails_with(&["--view", "1,2"], "direction");
    fails_with(&["--perspective", "0.5"], "inside the bounding sphere");
    fails_with(&["--factor", "1.5"], "factor");
    fails_with(&["--factor=-1"], "factor");
    fails_with(&["--nearest", "0"], "nearest");
    fails_with(&["--nearest", "500"], "nearest");
    fails_with(&["--step", "7"], "step");
    fails_with(&["--contour-cells=-1"], "cells");
    fails_with(&["--contour-cells", "NaN"], "cells");
    fails_with(&["--region", "edges"], "widened");
    fails_with(&["--eye", "0,0,0"], "inside the bounding sphere");
    fails_with(&["--eye", "0,0,inf"], "finite");
    fails_with(
        &["--eye", "0,0,9", "--view", "0,0,1"],
        "cannot be used with",
    );
    let output = sphaera(&["silhouette", "--resolution", "0"]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("resolution"));
    let empty = dir.path().join("empty.obj");
    std::fs::write(&empty, "# nothing\n").unwrap();
    fails_with(&[empty.to_str().unwrap()], "empty.obj");
    let broken = dir.path().join("broken.obj");
    std::fs::write(&broken, "v 0 0 0\nv 1 0 0\nf 1 2 9\n").unwrap();
    fails_with(&[broken.to_str().unwrap()], "broken.obj");
}

/// The numbers a run reports that must not depend on where its labels came from.
const SAME: [&str; 11] = [
    "cameras",
    "label_bytes",
    "triangles_out",
    "contour_triangles",
    "contour_allowance",
    "contour_error",
    "other_error",
    "silhouette_pixels_wrong",
    "contour_displacement",
    "plain_pixels_wrong",
    "gains",
];

#[test]
fn a_label_file_is_written_then_reused_with_the_same_result() {
    let dir = tempfile::tempdir().unwrap();
    let labels = dir.path().join("bunny.labels");
    let labels_arg = labels.to_str().unwrap();
    let first_mesh = dir.path().join("first.obj");
    let second_mesh = dir.path().join("second.obj");
    let view = ["--view", "0.3,-0.4,0.8", "--nearest", "4"];
    let mut args = vec!["--labels", labels_arg, "-o", first_mesh.to_str().unwrap()];
    args.extend_from_slice(&view);
    let first = run_json(&args);
    assert_eq!(first["labels_file"]["path"], labels_arg);
    assert_eq!(first["labels_file"]["reused"], false);
    let written = std::fs::read(&labels).unwrap();
    // 62 views of 1,839 vertices, 2 bytes each, an 80-byte header and a checksum.
    assert_eq!(written.len(), 80 + 2 * 62 * 1839 + 8);

    let mut args = vec!["--labels", labels_arg, "-o", second_mesh.to_str().unwrap()];
    args.extend_from_slice(&view);
    let second = run_json(&args);
    assert_eq!(second["labels_file"]["reused"], true);
    for key in SAME {
        assert!(!first[key].is_null(), "{key}");
        assert_eq!(first[key], second[key], "{key}");
    }
    assert_eq!(
        std::fs::read(&first_mesh).unwrap(),
        std::fs::read(&second_mesh).unwrap()
    );
    // Reading the file leaves it as it was; the text report says where the labels came
    // from.
    assert_eq!(std::fs::read(&labels).unwrap(), written);
    let mut all = vec!["silhouette"];
    all.extend_from_slice(&FAST);
    all.extend_from_slice(&["--labels", labels_arg]);
    let text = sphaera(&all);
    assert!(text.status.success());
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains("bunny.labels (read instead of labelling)"),
        "{text}"
    );
    // Without --labels the report says none.
    assert!(run_json(&[])["labels_file"].is_null());
}

#[test]
fn a_label_file_of_other_options_or_another_mesh_is_refused_and_kept() {
    let dir = tempfile::tempdir().unwrap();
    let labels = dir.path().join("bunny.labels");
    let labels_arg = labels.to_str().unwrap();
    run_json(&["--labels", labels_arg]);
    let written = std::fs::read(&labels).unwrap();
    // FAST is 30° and 128²; each option that differs is named, with the file's value.
    let with = |extra: &[&'static str]| {
        let mut args = FAST.to_vec();
        args.extend_from_slice(extra);
        args
    };
    for (args, named, file_setting) in [
        (
            vec!["--step", "15", "--resolution", "128"],
            "step 30°, not 15°",
            "--step 30",
        ),
        (
            vec!["--step", "30", "--resolution", "64"],
            "resolution 128, not 64",
            "--resolution 128",
        ),
        (
            with(&["--transform", "chamfer"]),
            "transform euclidean, not chamfer",
            "--transform euclidean",
        ),
        (
            with(&["--contours", "all"]),
            "contours outline, not all",
            "--contours outline",
        ),
        (
            with(&["--perspective", "3"]),
            "projection orthographic, not perspective at 3 radii",
            "without --perspective",
        ),
    ] {
        let mut all = vec!["silhouette", "--labels", labels_arg];
        all.extend_from_slice(&args);
        let output = sphaera(&all);
        assert!(!output.status.success(), "{args:?}");
        let message = String::from_utf8_lossy(&output.stderr);
        assert_eq!(message.lines().count(), 1, "{message}");
        for part in [named, file_setting, "bunny.labels", "delete the file"] {
            assert!(message.contains(part), "{args:?}: {part}: {message}");
        }
        assert_eq!(std::fs::read(&labels).unwrap(), written, "{args:?}");
    }
    // Another mesh.
    let sphere = write(dir.path(), "sphere.obj", &shapes::sphere(1.0, 12).unwrap());
    fails_with(&[&sphere, "--labels", labels_arg], "another mesh");
    assert_eq!(std::fs::read(&labels).unwrap(), written);
    // A damaged file.
    let mut damaged = written.clone();
    let middle = damaged.len() / 2;
    damaged[middle] ^= 1;
    std::fs::write(&labels, &damaged).unwrap();
    fails_with(&["--labels", labels_arg], "checksum");
    assert_eq!(std::fs::read(&labels).unwrap(), damaged);
    // A folder, and a file in a folder that does not exist.
    fails_with(
        &["--labels", dir.path().to_str().unwrap()],
        "not a regular file",
    );
    let nowhere = dir.path().join("no").join("labels");
    fails_with(&["--labels", nowhere.to_str().unwrap()], "does not exist");
    assert!(!nowhere.exists());
}

#[test]
fn the_result_is_judged_against_the_plain_simplifier_and_says_when_nothing_is_gained() {
    // The bunny has outline detail to keep: the guided level beats `sphaera simplify`.
    let report = run_json(&["--view", "0.3,-0.4,0.8", "--error", "1%"]);
    assert_eq!(report["region"], "widened");
    assert_eq!(report["contour_cells"], 0.25);
    assert_eq!(report["plain_triangles"], report["triangles_out"]);
    let (ours, plain) = (
        number(&report, "silhouette_pixels_wrong"),
        number(&report, "plain_pixels_wrong"),
    );
    assert_eq!(report["gains"], ours < plain, "{report}");
    assert!(ours < plain, "{report}");
    // A quarter of a 128² cell of the bunny's bounding sphere, and within ¼ e.
    let allowance = number(&report, "contour_allowance");
    assert!(allowance <= 0.25 * number(&report, "error") * (1.0 + 1e-12));
    assert!(number(&report, "contour_error") <= allowance * (1.0 + 1e-12));
    // The paper's rule, no cap in cells: `null` in the report.
    let paper = run_json(&[
        "--view",
        "0.3,-0.4,0.8",
        "--error",
        "1%",
        "--region",
        "corners",
        "--contour-cells",
        "inf",
    ]);
    assert_eq!(paper["region"], "corners");
    assert!(paper["contour_cells"].is_null(), "{paper}");
    assert!(
        (number(&paper, "contour_allowance") - 0.25 * number(&paper, "error")).abs()
            <= 1e-12 * number(&paper, "error")
    );
    // A cube has no outline detail to keep: both keep its silhouette, and the text says
    // the plain simplifier does as well.
    let dir = tempfile::tempdir().unwrap();
    let cube = write(dir.path(), "cube.obj", &shapes::cube(1.0, 4).unwrap());
    let mut args = vec!["silhouette", cube.as_str()];
    args.extend_from_slice(&FAST);
    let output = sphaera(&args);
    assert!(output.status.success());
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(text.contains("no gain on this mesh"), "{text}");
    let mut args = vec!["silhouette", "--json", cube.as_str()];
    args.extend_from_slice(&FAST);
    let report = json(&sphaera(&args));
    assert_eq!(report["gains"], false, "{report}");
}

#[test]
fn a_camera_position_gives_the_view_and_a_finer_contour_when_near() {
    // A unit ball around the origin.
    let dir = tempfile::tempdir().unwrap();
    let ball = write(dir.path(), "ball.obj", &shapes::sphere(1.0, 24).unwrap());
    let far = run_json(&[ball.as_str(), "--eye", "0.2,-0.3,40"]);
    let near = run_json(&[ball.as_str(), "--eye", "0.03,-0.045,1.5"]);
    assert_eq!(far["eye"][2], 40.0);
    for report in [&far, &near] {
        assert!(
            number(report, "contour_error") <= number(report, "contour_allowance") * (1.0 + 1e-12)
        );
        let [x, y, z] = [0, 1, 2].map(|k| report["view"][k].as_f64().unwrap());
        assert!(z > 0.99 && x > 0.0 && y < 0.0, "{report}");
    }
    assert!(number(&near, "contour_allowance") < number(&far, "contour_allowance"));
    let mut args = vec!["silhouette", ball.as_str(), "--eye", "0.2,-0.3,40"];
    args.extend_from_slice(&FAST);
    let text = String::from_utf8_lossy(&sphaera(&args).stdout).into_owned();
    assert!(text.contains("from a camera at 0.2,-0.3,40"), "{text}");
}
