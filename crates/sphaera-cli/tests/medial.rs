//! End-to-end tests of `sphaera medial`.

mod common;

use std::path::Path;

use common::{json, sphaera};
use sphaera::mesh::{DVec3, TriMesh, io, sampling, shapes};

/// Independent surface points for the coverage checks: this many uniform random samples
/// (not the command's Poisson-disk ones), and every vertex of a triangle.
const CHECK_SAMPLES: usize = 30_000;

/// The spheres (centre, radius) of a `-o` file.
fn written_spheres(path: &Path) -> (serde_json::Value, Vec<(DVec3, f64)>) {
    let file: serde_json::Value =
        serde_json::from_slice(&std::fs::read(path).expect("written")).expect("JSON");
    let spheres = file["spheres"]
        .as_array()
        .expect("an array")
        .iter()
        .map(|s| {
            let center: Vec<f64> = s["center"]
                .as_array()
                .expect("a center")
                .iter()
                .map(|c| c.as_f64().expect("a coordinate"))
                .collect();
            let radius = s["radius"].as_f64().expect("a radius");
            (DVec3::new(center[0], center[1], center[2]), radius)
        })
        .collect();
    (file, spheres)
}

/// The surface points of `mesh` (uniform samples, then the vertices of its triangles;
/// unreferenced vertices are not on the surface) outside every sphere, by brute force, up
/// to a rounding tolerance of 1e-9 of the diagonal.
fn outside_every_sphere(mesh: &TriMesh, spheres: &[(DVec3, f64)]) -> Vec<DVec3> {
    let tolerance = 1e-9 * mesh.bounding_box_diagonal();
    let samples = sampling::random(mesh, CHECK_SAMPLES, 0xC0FE).expect("samples");
    let mut corners: Vec<u32> = mesh.triangles().iter().flatten().copied().collect();
    corners.sort_unstable();
    corners.dedup();
    samples
        .iter()
        .map(|s| s.position)
        .chain(corners.iter().map(|&v| mesh.positions()[v as usize]))
        .filter(|&p| {
            !spheres
                .iter()
                .any(|&(center, radius)| center.distance(p) <= radius + tolerance)
        })
        .collect()
}

/// Runs `sphaera medial` on `mesh` with `args`, writing the spheres; checks the surface
/// certificate and that no independent surface point lies outside every sphere.
fn assert_surface_covered(mesh_path: &Path, args: &[&str]) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let out = dir.path().join("spheres.json");
    let mut all = vec![
        "medial",
        "--json",
        mesh_path.to_str().expect("utf-8"),
        "-o",
        out.to_str().expect("utf-8"),
    ];
    all.extend_from_slice(args);
    let report = json(&sphaera(&all));
    assert_eq!(report["coverage"], "surface", "{report}");
    assert_eq!(report["uncovered_samples"], 0);
    let mesh = io::load(mesh_path).expect("the mesh");
    let (file, spheres) = written_spheres(&out);
    assert_eq!(file["coverage"], "surface");
    assert_eq!(
        spheres.len() as u64,
        report["spheres"].as_u64().expect("count")
    );
    let outside = outside_every_sphere(&mesh, &spheres);
    assert!(
        outside.is_empty(),
        "{} surface points (of {CHECK_SAMPLES} samples and the vertices) outside every \
         sphere, e.g. {:?}",
        outside.len(),
        outside.first()
    );
}

#[test]
fn medial_spheres_cover_the_whole_surface_of_a_block_by_default() {
    // Sharp edges and corners: where samples leave the most surface between them.
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("l_block.obj");
    let mesh = shapes::l_block(2.0, 0.8, 0.5, 4).expect("an L block");
    io::write_obj(&path, &mesh).expect("written");
    assert_surface_covered(&path, &["--medial-target", "120", "--samples", "2000"]);
}

#[test]
fn medial_spheres_cover_the_whole_surface_of_spot() {
    let Some(data) = sphaera_tests::data_dir("medial_spheres_cover_the_whole_surface_of_spot")
    else {
        return;
    };
    // Issue 16: with 500 spheres, 0.26 % of the surface and 1.7 % of the vertices were
    // outside every sphere.
    assert_surface_covered(&data.join("spot.obj"), &["--medial-target", "500"]);
}

#[test]
fn medial_json_reports_the_certificate_and_grown_spheres_consistently() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("spheres.json");
    let report = json(&sphaera(&[
        "medial",
        "--json",
        "--medial-target",
        "150",
        "--samples",
        "2000",
        "-o",
        path.to_str().expect("utf-8"),
    ]));
    assert_eq!(report["coverage"], "surface");
    let certificate = &report["certificate"];
    let triangles = report["triangles"].as_u64().expect("triangles");
    // At least one piece per triangle.
    assert!(certificate["pieces"].as_u64().expect("pieces") >= triangles);
    let grown = certificate["grown_spheres"].as_u64().expect("grown");
    let largest = certificate["largest_growth"].as_f64().expect("largest");
    assert!(grown > 0, "2,000 samples leave gaps: {certificate}");
    assert!(largest > 0.0);
    assert!(certificate["resolution"].as_f64().expect("resolution") > 0.0);
    assert!(report["seconds"]["certify"].as_f64().expect("seconds") >= 0.0);

    // The file carries the same certificate, and each grown sphere its growth, with an
    // error measured at its grown radius.
    let (file, _) = written_spheres(&path);
    assert_eq!(&file["certificate"], certificate);
    let spheres = file["spheres"].as_array().expect("an array");
    let growths: Vec<f64> = spheres
        .iter()
        .map(|s| s["growth"].as_f64().expect("growth"))
        .collect();
    assert_eq!(growths.iter().filter(|&&g| g > 0.0).count() as u64, grown);
    let most = growths.iter().copied().fold(0.0, f64::max);
    assert!(
        (most - largest).abs() <= 1e-12 * largest.max(1.0),
        "{most} {largest}"
    );

    // Grown spheres against the same run with `--samples-only` (same medial spheres).
    let ungrown_path = dir.path().join("ungrown.json");
    let ungrown_report = json(&sphaera(&[
        "medial",
        "--json",
        "--medial-target",
        "150",
        "--samples",
        "2000",
        "--samples-only",
        "-o",
        ungrown_path.to_str().expect("utf-8"),
    ]));
    let (ungrown, _) = written_spheres(&ungrown_path);
    let ungrown = ungrown["spheres"].as_array().expect("an array");
    assert_eq!(ungrown.len(), spheres.len());
    let field = |s: &serde_json::Value, name: &str| s[name].as_f64().expect(name);
    for ((s, before), g) in spheres.iter().zip(ungrown).zip(&growths) {
        assert_eq!(s["center"], before["center"]);
        let radius = field(s, "radius");
        assert!((radius - (field(before, "radius") + g)).abs() <= 1e-12 * radius.max(1.0));
        if *g > 0.0 {
            // eq. 2 keeps the centre's distance to the surface: the error grows with the
            // radius (from its unclamped value, so by at most the growth).
            let (error, was) = (field(s, "error"), field(before, "error"));
            assert!(error >= was && error <= was + g + 1e-12 * radius.max(1.0));
            let covered = |s: &serde_json::Value| {
                s["covered_samples"]
                    .as_u64()
                    .unwrap_or_else(|| panic!("covered_samples: {s}"))
            };
            assert!(
                covered(s) >= covered(before),
                "a grown sphere covers what it covered"
            );
        } else {
            assert_eq!(s, before);
        }
    }
    let worst = spheres
        .iter()
        .map(|s| field(s, "error"))
        .fold(0.0, f64::max);
    assert_eq!(serde_json::json!(worst), report["worst_error"]);
    assert_eq!(
        report["medial_worst_error"], ungrown_report["worst_error"],
        "the medial spheres before growth are the samples-only spheres"
    );
}

#[test]
fn medial_samples_only_reports_the_samples_guarantee() {
    let report = json(&sphaera(&[
        "medial",
        "--json",
        "--medial-target",
        "100",
        "--samples",
        "2000",
        "--samples-only",
    ]));
    assert_eq!(report["coverage"], "samples");
    assert!(report["certificate"].is_null());
    assert_eq!(report["uncovered_samples"], 0);
    assert_eq!(report["worst_error"], report["medial_worst_error"]);
    let text = sphaera(&[
        "medial",
        "-q",
        "--medial-target",
        "100",
        "--samples",
        "2000",
        "--samples-only",
    ]);
    assert!(text.status.success());
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("the surface samples only"), "{text}");
    let certified = sphaera(&[
        "medial",
        "-q",
        "--medial-target",
        "100",
        "--samples",
        "2000",
    ]);
    let certified = String::from_utf8_lossy(&certified.stdout);
    assert!(
        certified.contains("the whole surface, certified"),
        "{certified}"
    );
}

#[test]
fn medial_of_the_embedded_bunny_covers_every_sample_and_writes_the_spheres() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("spheres.json");
    let report = json(&sphaera(&[
        "medial",
        "--json",
        "--medial-target",
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
    // `--max-error` bounds the medial spheres; the certificate may grow a few past it.
    assert!(
        report["medial_worst_error"].as_f64().expect("medial worst")
            <= report["worst_error"].as_f64().expect("worst")
    );
    let diagonal = report["worst_error"].as_f64().expect("worst")
        / report["worst_error_relative"].as_f64().expect("relative");
    assert!(
        report["medial_worst_error"].as_f64().expect("medial worst")
            <= 0.03 * diagonal * (1.0 + 1e-12)
    );
    let largest = report["certificate"]["largest_growth"]
        .as_f64()
        .expect("growth");
    assert!(report["worst_error"].as_f64().expect("worst") <= 0.03 * diagonal + largest);
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
    // The error says what covers a sheet.
    assert!(message.contains("--spheres N"), "{message}");
}

#[test]
fn medial_spheres_n_gives_exactly_n_spheres_covering_the_surface() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let mesh = dir.path().join("bunny.obj");
    std::fs::write(
        &mesh,
        include_bytes!("../assets/bunny_lowres.obj").as_slice(),
    )
    .expect("written");
    let out = dir.path().join("spheres.json");
    let report = json(&sphaera(&[
        "medial",
        "--json",
        "-q",
        mesh.to_str().expect("utf-8"),
        "--spheres",
        "8",
        "-o",
        out.to_str().expect("utf-8"),
    ]));
    assert_eq!(report["method"], "minimax");
    assert_eq!(report["surface"], "solid");
    assert_eq!(report["spheres_requested"], 8);
    assert_eq!(report["spheres"], 8);
    assert_eq!(report["coverage"], "surface");
    assert!(report["certificate"]["pieces"].as_u64().expect("pieces") > 0);
    let (file, spheres) = written_spheres(&out);
    assert_eq!(spheres.len(), 8);
    assert!(
        file["spheres"]
            .as_array()
            .expect("spheres")
            .iter()
            .all(|s| s["kind"] == "Minimax")
    );
    let worst = file["spheres"]
        .as_array()
        .expect("spheres")
        .iter()
        .map(|s| s["error"].as_f64().expect("error"))
        .fold(0.0, f64::max);
    assert_eq!(serde_json::json!(worst), report["worst_error"]);
    // Covered, by an independent brute-force check.
    let outside = outside_every_sphere(&io::load(&mesh).expect("the mesh"), &spheres);
    assert!(outside.is_empty(), "{} points outside", outside.len());

    let text = sphaera(&["medial", "-q", "--spheres", "8"]);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("8 (8 asked)"), "{text}");
}

#[test]
fn medial_target_keeps_the_adaptive_approximation() {
    let report = json(&sphaera(&[
        "medial",
        "--json",
        "-q",
        "--medial-target",
        "100",
        "--samples",
        "2000",
    ]));
    assert_eq!(report["method"], "adaptive");
    assert_eq!(report["target"], "medial-target 100");
    assert!(report["spheres_requested"].is_null());
    assert!(report["spheres"].as_u64().expect("count") >= 100);
}

#[test]
fn medial_spheres_cover_a_flat_sheet_and_bad_counts_are_refused() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("sheet.obj");
    std::fs::write(
        &path,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n",
    )
    .expect("written");
    let sheet = path.to_str().expect("utf-8");
    let report = json(&sphaera(&[
        "medial",
        "--json",
        "-q",
        sheet,
        "--spheres",
        "4",
    ]));
    assert_eq!(report["surface"], "shell");
    assert_eq!(report["spheres"], 4);
    for (args, expected) in [
        (&["--spheres", "0"][..], "10,000"),
        (&["--spheres", "10001"][..], "10,000"),
        (
            &["--spheres", "8", "--medial-target", "8"][..],
            "--medial-target",
        ),
        (&["--spheres", "8", "--max-error", "1%"][..], "--max-error"),
        (&["--spheres", "8", "--samples", "100"][..], "--samples"),
    ] {
        let mut all = vec!["medial", "-q", sheet];
        all.extend(args);
        let output = sphaera(&all);
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(
            !output.status.success() && message.contains(expected),
            "{args:?}: {message}"
        );
    }
}
