//! End-to-end tests of `sphaera simplify`.

mod common;

use common::{json, sphaera};

#[test]
fn simplify_the_embedded_bunny_to_a_ratio_and_write_it() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("bunny_10.ply");
    let report = json(&sphaera(&[
        "simplify",
        "--ratio",
        "0.1",
        "--json",
        "-o",
        path.to_str().unwrap(),
    ]));
    assert_eq!(report["triangles_in"], 3674);
    let out = report["triangles_out"].as_u64().unwrap();
    assert!(out <= 368, "{out} triangles");
    assert!(report["error_bound"].as_f64().unwrap() > 0.0);
    // The file is there, and `info` reads back the same triangle count.
    let info = json(&sphaera(&["info", "--json", path.to_str().unwrap()]));
    assert_eq!(info["triangles"].as_u64(), Some(out));
    assert_eq!(info["topology"]["closed"], true);
}

#[test]
fn simplify_stops_at_a_relative_error_bound() {
    let report = json(&sphaera(&["simplify", "--max-error", "0.5%", "--json"]));
    let relative = report["error_bound_relative"].as_f64().unwrap();
    assert!(relative <= 0.005, "bound {relative} of the diagonal");
    assert!(report["triangles_out"].as_u64().unwrap() < 3674);
}

#[test]
fn simplify_rejects_a_bad_ratio_with_a_clear_message() {
    let output = sphaera(&["simplify", "--ratio", "1.5"]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.starts_with("error:"), "{message}");
    assert!(message.contains("ratio"), "{message}");
}

#[test]
fn simplify_refuses_to_write_an_unsupported_format_and_leaves_no_file() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("out.stl");
    let output = sphaera(&["simplify", "--ratio", "0.5", "-o", path.to_str().unwrap()]);
    assert!(!output.status.success());
    assert!(!path.exists());
    let message = String::from_utf8_lossy(&output.stderr).to_lowercase();
    assert!(message.contains("stl"), "{message}");
    assert!(message.contains("out.stl"), "{message}");
}

#[test]
fn simplify_measure_reports_a_distance_below_the_certified_bound() {
    let report = json(&sphaera(&[
        "simplify",
        "--ratio",
        "0.1",
        "--placement",
        "subset",
        "--measure",
        "--json",
    ]));
    assert_eq!(report["placement"], "subset");
    let bound = report["error_bound"].as_f64().unwrap();
    let measured = report["measured_hausdorff"].as_f64().unwrap();
    // A sampled lower bound of the true distance, which the certified bound encloses.
    assert!(measured > 0.0, "measured {measured}");
    assert!(
        measured <= bound * (1.0 + 1e-9),
        "{measured} > bound {bound}"
    );
    let relative = report["measured_hausdorff_relative"].as_f64().unwrap();
    let bound_relative = report["error_bound_relative"].as_f64().unwrap();
    assert!((relative / bound_relative - measured / bound).abs() < 1e-9);
    assert!(report["seconds"]["measure"].as_f64().unwrap() >= 0.0);
}

#[test]
fn simplify_without_measure_leaves_the_measured_fields_null() {
    let report = json(&sphaera(&["simplify", "--ratio", "0.5", "--json"]));
    assert_eq!(report["placement"], "subset");
    assert!(report["measured_hausdorff"].is_null());
    assert!(report["measured_hausdorff_relative"].is_null());
    assert!(report["seconds"]["measure"].is_null());
}

#[test]
fn simplify_text_output_names_the_placement_and_the_measurement() {
    let output = sphaera(&["simplify", "--ratio", "0.5", "--measure", "--quiet"]);
    assert!(output.status.success());
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.contains("placement       subset (order auto)"),
        "{text}"
    );
    assert!(text.contains("sampled lower bound"), "{text}");
    assert!(text.contains("s to measure"), "{text}");
    // Not a terminal: no progress bar on stderr.
    assert!(
        output.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

#[test]
fn simplify_rejects_an_unknown_placement_and_lists_the_known_ones() {
    let output = sphaera(&["simplify", "--placement", "centroid"]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("--placement"), "{message}");
    assert!(message.contains("centroid"), "{message}");
    assert!(message.contains("subset"), "{message}");
}

#[test]
fn simplify_order_is_reported_and_both_orders_certify_their_bound() {
    let auto = json(&sphaera(&["simplify", "--ratio", "0.2", "--json"]));
    assert_eq!(auto["order"], "auto");
    for order in ["strict", "batched"] {
        let report = json(&sphaera(&[
            "simplify",
            "--ratio",
            "0.2",
            "--order",
            order,
            "--measure",
            "--json",
        ]));
        assert_eq!(report["order"], order);
        let bound = report["error_bound"].as_f64().unwrap();
        let measured = report["measured_hausdorff"].as_f64().unwrap();
        assert!(
            measured <= bound * (1.0 + 1e-9),
            "{order}: {measured} > {bound}"
        );
    }
    // The embedded bunny is small: auto takes the strict order.
    let strict = json(&sphaera(&[
        "simplify", "--ratio", "0.2", "--order", "strict", "--json",
    ]));
    assert_eq!(auto["error_bound"], strict["error_bound"]);
    let output = sphaera(&["simplify", "--order", "sideways"]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("batched"), "{message}");
}
