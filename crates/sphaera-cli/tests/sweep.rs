//! End-to-end tests of `sphaera distance` and `sphaera hausdorff`.

mod common;

use common::{json, sphaera};

fn number(value: &serde_json::Value) -> f64 {
    value.as_f64().expect("a number")
}

#[test]
fn hausdorff_of_the_embedded_bunny_and_its_simplification_is_certified() {
    let report = json(&sphaera(&["hausdorff", "--json", "--tolerance", "0.01%"]));
    let (lower, upper) = (number(&report["lower"]), number(&report["upper"]));
    assert!(0.0 < lower && lower <= upper, "[{lower}, {upper}]");
    assert!(upper - lower <= number(&report["tolerance"]) + 1e-15);
    assert_eq!(report["converged"], true);
    // The simplifier's certified bound holds the true distance.
    assert!(number(&report["simplifier_bound"]) >= lower);
    assert!(report["b_to_a"].is_object());
    assert_eq!(report["engine"], "trees");
    assert!(report["seconds"]["hierarchies"].is_null());

    // The paper's engine certifies an interval that overlaps.
    let paper = json(&sphaera(&[
        "hausdorff",
        "--json",
        "--tolerance",
        "0.01%",
        "--engine",
        "meshsweeper",
    ]));
    assert_eq!(paper["engine"], "meshsweeper");
    assert!(number(&paper["seconds"]["hierarchies"]) >= 0.0);
    assert!(number(&paper["lower"]) <= upper && lower <= number(&paper["upper"]));
}

#[test]
fn hausdorff_writes_a_coloured_ply_and_refuses_other_formats() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("field.ply");
    let report = json(&sphaera(&[
        "hausdorff",
        "--json",
        "--one-sided",
        "--tolerance",
        "0.1%",
        "--colors",
        path.to_str().expect("utf-8"),
    ]));
    assert!(report["b_to_a"].is_null());
    let bytes = std::fs::read(&path).expect("written");
    assert!(String::from_utf8_lossy(&bytes).contains("property uchar red"));

    let wrong = dir.path().join("field.obj");
    let output = sphaera(&["hausdorff", "--colors", wrong.to_str().expect("utf-8")]);
    assert!(!output.status.success());
    assert!(!wrong.exists());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("PLY"), "{message}");
}

#[test]
fn hausdorff_reports_missing_files_and_bad_tolerances() {
    let output = sphaera(&["hausdorff", "/no/such/mesh.obj"]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("/no/such/mesh.obj"));
    let output = sphaera(&["hausdorff", "--tolerance", "-1"]);
    assert!(!output.status.success());
}

#[test]
fn distance_answers_random_points_exactly() {
    let report = json(&sphaera(&["distance", "--random", "50", "--json"]));
    let answers = report["answers"].as_array().expect("answers");
    assert_eq!(answers.len(), 50);
    for answer in answers {
        assert_eq!(answer["lower"], answer["upper"]);
        assert!(answer["point"].is_array());
    }
}

#[test]
fn distance_with_a_tolerance_gives_certified_intervals_no_wider() {
    let exact = json(&sphaera(&["distance", "--random", "200", "--json"]));
    let approx = json(&sphaera(&[
        "distance",
        "--random",
        "200",
        "--tolerance",
        "1%",
        "--json",
    ]));
    let tolerance = approx["tolerance"].as_f64().expect("a tolerance");
    let pairs = exact["answers"]
        .as_array()
        .expect("answers")
        .iter()
        .zip(approx["answers"].as_array().expect("answers"));
    for (e, a) in pairs {
        let d = e["lower"].as_f64().expect("exact");
        let (lower, upper) = (
            a["lower"].as_f64().expect("lower"),
            a["upper"].as_f64().expect("upper"),
        );
        assert!(
            lower <= d + 1e-12 && d <= upper + 1e-12,
            "{lower} {d} {upper}"
        );
        assert!(upper - lower <= tolerance + 1e-12);
    }
}
