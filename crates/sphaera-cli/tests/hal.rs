//! End-to-end tests of `sphaera hal`.

mod common;

use common::{json, sphaera};
use sphaera::hal::{Containment, HalTree2, Polyline2};
use sphaera::mesh::glam::DVec2;
use sphaera_tests::regions::{self, Side};

/// An L-shaped polygon with a notch, as a file.
fn write_polygon(dir: &std::path::Path) -> std::path::PathBuf {
    let path = dir.join("l.txt");
    std::fs::write(
        &path,
        "# an L\n0 0\n4 0\n4 1\n2 1\n2 1.5\n1 1.5\n1 4\n0 4\n",
    )
    .unwrap();
    path
}

#[test]
fn levels_tolerance_contains_and_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let polygon = write_polygon(dir.path());
    let points = dir.path().join("points.txt");
    std::fs::write(&points, "0.5 0.5\n3 3\n2 1.25\n0 2\n").unwrap();
    let svg = dir.path().join("l.svg");
    let report = json(&sphaera(&[
        "hal",
        polygon.to_str().unwrap(),
        "--tolerance",
        "10%",
        "--contains",
        points.to_str().unwrap(),
        "-o",
        svg.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(report["vertices"], 8);
    assert_eq!(report["nodes"], 6);
    let levels = report["levels"].as_array().unwrap();
    assert_eq!(levels[0]["vertices"], 2);
    assert_eq!(levels.last().unwrap()["vertices"], 8);
    let approximation = &report["approximation"];
    let diagonal = report["diagonal"].as_f64().unwrap();
    assert!(approximation["width"].as_f64().unwrap() <= 0.1 * diagonal);
    let answers: Vec<&str> = report["contains"]["answers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_str().unwrap())
        .collect();
    assert_eq!(answers, ["inside", "outside", "boundary", "boundary"]);
    let drawing = std::fs::read_to_string(&svg).unwrap();
    assert!(drawing.starts_with("<svg") && drawing.contains("<path"));

    // The answers agree with a reference outside HAL, and with the library's tree.
    let outline = Polyline2::read_polygon(&polygon).unwrap();
    let tree = HalTree2::build(&outline).unwrap();
    for (p, answer) in [(0.5, 0.5), (3.0, 3.0), (2.0, 1.25), (0.0, 2.0)]
        .iter()
        .zip(&answers)
    {
        let x = DVec2::new(p.0, p.1);
        let (expected, containment) = match regions::locate_in_outline(outline.points(), x) {
            Side::Inside => ("inside", Containment::Inside),
            Side::Outside => ("outside", Containment::Outside),
            Side::Boundary => ("boundary", Containment::Boundary),
        };
        assert_eq!(*answer, expected);
        assert_eq!(tree.contains(x).unwrap(), containment);
    }

    // A level as text.
    let text = dir.path().join("level1.txt");
    let report = json(&sphaera(&[
        "hal",
        polygon.to_str().unwrap(),
        "--level",
        "1",
        "-o",
        text.to_str().unwrap(),
        "--json",
    ]));
    let written = std::fs::read_to_string(&text).unwrap();
    assert_eq!(
        written.lines().count(),
        report["approximation"]["vertices"].as_u64().unwrap() as usize
    );
}

#[test]
fn bad_input_gives_a_clear_error_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.txt");
    std::fs::write(&bad, "0 0\n1 0\n1 one\n").unwrap();
    let output = sphaera(&["hal", bad.to_str().unwrap()]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("line 3"), "{message}");

    let polygon = write_polygon(dir.path());
    let missing = dir.path().join("no/such/folder/out.svg");
    let output = sphaera(&[
        "hal",
        polygon.to_str().unwrap(),
        "-o",
        missing.to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("does not exist"));

    let wrong = dir.path().join("out.obj");
    let output = sphaera(&[
        "hal",
        polygon.to_str().unwrap(),
        "-o",
        wrong.to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    assert!(!wrong.exists());

    // An open polyline has no inside.
    let points = dir.path().join("p.txt");
    std::fs::write(&points, "0 0\n").unwrap();
    let output = sphaera(&[
        "hal",
        polygon.to_str().unwrap(),
        "--open",
        "--contains",
        points.to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("no inside"));
}

#[test]
fn a_genus_zero_mesh_gets_a_3d_tree_and_a_torus_a_clear_error() {
    use sphaera::mesh::{io, shapes};
    let dir = tempfile::tempdir().unwrap();
    let sphere = dir.path().join("sphere.obj");
    io::save(&sphere, &shapes::sphere(1.0, 12).unwrap()).unwrap();
    let out = dir.path().join("approx.obj");
    let report = json(&sphaera(&[
        "hal",
        sphere.to_str().unwrap(),
        "--tolerance",
        "5%",
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]));
    let triangles = report["triangles"].as_u64().unwrap();
    // (On a sphere this coarse, the filled gaps can outnumber the faces saved.)
    let kept = report["approximation"]["triangles"].as_u64().unwrap();
    let diagonal = report["diagonal"].as_f64().unwrap();
    assert!(report["approximation"]["width"].as_f64().unwrap() <= 0.05 * diagonal);
    let written = io::load(&out).unwrap();
    assert_eq!(written.triangle_count() as u64, kept);
    // Watertight: every edge used as often one way as the other.
    let mut net = std::collections::HashMap::new();
    for t in written.triangles() {
        for (u, v) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            *net.entry((u.min(v), u.max(v))).or_insert(0_i64) += if u < v { 1 } else { -1 };
        }
    }
    assert!(net.values().all(|&c| c == 0));
    let levels = report["levels"].as_array().unwrap();
    assert_eq!(
        levels.last().unwrap()["triangles"].as_u64().unwrap(),
        triangles
    );

    let torus = dir.path().join("torus.obj");
    io::save(&torus, &shapes::torus(1.0, 0.3, 12).unwrap()).unwrap();
    let output = sphaera(&["hal", torus.to_str().unwrap()]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains("genus 1") && message.contains("sphere-tree"),
        "{message}"
    );

    // 3D point inclusion: `x y z` lines, answers in file order.
    let points = dir.path().join("p.txt");
    std::fs::write(
        &points,
        "# center, outside, a vertex\n0 0 0\n2 0 0\n0 0 -1\n",
    )
    .unwrap();
    let report = json(&sphaera(&[
        "hal",
        sphere.to_str().unwrap(),
        "--contains",
        points.to_str().unwrap(),
        "--json",
    ]));
    let answers: Vec<&str> = report["contains"]["answers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_str().unwrap())
        .collect();
    assert_eq!(answers, ["inside", "outside", "boundary"]);
    // Two numbers a line is a 2D file: refused, naming the line.
    std::fs::write(&points, "0 0\n").unwrap();
    let output = sphaera(&[
        "hal",
        sphere.to_str().unwrap(),
        "--contains",
        points.to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains("line 1") && message.contains("3 finite numbers"),
        "{message}"
    );
}

/// The country files kept in the repository (`tests/data/countries`).
fn country(name: &str) -> String {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/countries")
        .join(format!("{name}.geojson"))
        .to_str()
        .unwrap()
        .to_owned()
}

#[test]
fn a_country_with_islands_and_holes_says_where_and_meets_its_enclave() {
    let dir = tempfile::tempdir().unwrap();
    let points = dir.path().join("points.txt");
    // Rome, San Marino, the sea west of Sardinia.
    std::fs::write(&points, "12.5 41.9\n12.45 43.93\n6 40\n").unwrap();
    let report = json(&sphaera(&[
        "hal",
        &country("italy"),
        "--contains",
        points.to_str().unwrap(),
        "--intersect",
        &country("san-marino"),
        "--json",
    ]));
    assert_eq!(report["polygons"], 29);
    assert_eq!(report["holes"], 1, "{report}");
    // The Vatican is two points at 1:10m: dropped, and said so.
    assert_eq!(report["dropped_rings"][0]["ring"], 2);
    let answers = report["contains"]["answers"].as_array().unwrap();
    assert_eq!(answers[0]["containment"], "inside");
    assert_eq!(answers[0]["ring"]["ring"], 0);
    assert_eq!(answers[1]["containment"], "outside");
    assert_eq!(answers[1]["ring"]["ring"], 1, "San Marino is Italy's hole");
    assert_eq!(answers[2]["containment"], "outside");
    assert!(answers[2]["ring"].is_null());
    assert!(answers[2]["distance"].as_f64().unwrap() > 0.1);
    let intersect = &report["intersect"];
    assert_eq!(intersect["intersects"], true);
    let pairs = intersect["edge_pairs"].as_array().unwrap();
    assert_eq!(pairs.len(), intersect["pairs"].as_u64().unwrap() as usize);
    assert!(pairs.iter().all(|p| p[0]["ring"] == 1 && p[1]["ring"] == 0));
}

#[test]
fn wkt_lines_inside_a_polygon_meet_it_and_a_text_polygon_intersects_too() {
    let dir = tempfile::tempdir().unwrap();
    let lake = dir.path().join("lake.wkt");
    std::fs::write(
        &lake,
        "POLYGON ((0 0, 10 0, 10 10, 0 10, 0 0), (4 4, 6 4, 6 6, 4 6, 4 4))",
    )
    .unwrap();
    let road = dir.path().join("road.wkt");
    std::fs::write(&road, "LINESTRING (1 1, 2 3)").unwrap();
    let report = json(&sphaera(&[
        "hal",
        lake.to_str().unwrap(),
        "--intersect",
        road.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(
        report["intersect"]["intersects"], true,
        "a road inside the land"
    );
    assert_eq!(report["intersect"]["pairs"], 0);
    let pier = dir.path().join("pier.wkt");
    std::fs::write(&pier, "MULTILINESTRING ((4.5 4.5, 5.5 5.5), (3 5, 5 5))").unwrap();
    let report = json(&sphaera(&[
        "hal",
        lake.to_str().unwrap(),
        "--intersect",
        pier.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(report["intersect"]["intersects"], true);
    let pairs = report["intersect"]["edge_pairs"].as_array().unwrap();
    assert_eq!(pairs.len(), 1, "{pairs:?}");
    assert_eq!(pairs[0][0]["ring"], 1, "the lake's shore");
    assert_eq!(pairs[0][1]["line"], 1);
    // A single ring from a text file against the WKT.
    let polygon = write_polygon(dir.path());
    let report = json(&sphaera(&[
        "hal",
        polygon.to_str().unwrap(),
        "--intersect",
        lake.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(report["intersect"]["intersects"], true);
    // Text: the answer and the pairs.
    let output = sphaera(&[
        "hal",
        lake.to_str().unwrap(),
        "--intersect",
        pier.to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.contains("polygon 0 hole 0 edge 3 meets line 1 edge 0"),
        "{text}"
    );
}

#[test]
fn bad_gis_files_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let broken = dir.path().join("broken.geojson");
    std::fs::write(
        &broken,
        "{\"type\": \"Polygon\", \"coordinates\": [[[0, 0], [1",
    )
    .unwrap();
    let output = sphaera(&["hal", broken.to_str().unwrap()]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains("broken.geojson") && message.contains("GeoJSON"),
        "{message}"
    );
    let short = dir.path().join("short.wkt");
    std::fs::write(
        &short,
        "MULTIPOLYGON (((0 0, 1 0, 1 1, 0 0)), ((5 5, 6 5, 5 5)))",
    )
    .unwrap();
    let output = sphaera(&["hal", short.to_str().unwrap(), "--json"]);
    assert!(output.status.success());
    assert_eq!(json(&output)["dropped_rings"][0]["polygon"], 1);
    let nan = dir.path().join("nan.wkt");
    std::fs::write(&nan, "POLYGON ((0 0, 1 0, 1e999 1, 0 0))").unwrap();
    let output = sphaera(&["hal", nan.to_str().unwrap()]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("non-finite"), "{message}");
    let lines = dir.path().join("lines.wkt");
    std::fs::write(&lines, "LINESTRING (0 0, 1 1)").unwrap();
    let output = sphaera(&["hal", lines.to_str().unwrap()]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("no polygon"));
    let output = sphaera(&["hal", &country("lesotho"), "-o", "out.svg"]);
    assert!(!output.status.success());
}

/// A reader that stops early (`… --json | head`) gets no panic on stderr: the tool leaves
/// with the status of a process the closed pipe ended.
#[test]
fn a_closed_stdout_is_not_a_panic() {
    use std::io::Read;
    use std::process::{Command, Stdio};
    let indonesia = country("indonesia");
    let mut child = Command::new(env!("CARGO_BIN_EXE_sphaera"))
        .args(["hal", &indonesia, "--intersect", &indonesia, "--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0_u8; 16];
    child.stdout.take().unwrap().read_exact(&mut first).unwrap();
    // The pipe's read end is dropped here, with megabytes of pairs still to print.
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(output.status.code(), Some(141), "{stderr}");
}

/// Two balls, overlapping and apart: `--intersect` between meshes says whether the solids
/// meet and lists every pair of faces that do, each pair checked exactly.
#[test]
fn meshes_intersect_with_their_face_pairs() {
    use sphaera::mesh::{io, shapes};
    let dir = tempfile::tempdir().unwrap();
    let ball = shapes::sphere(1.0, 10).unwrap();
    let a = dir.path().join("a.obj");
    io::save(&a, &ball).unwrap();
    let moved = |dx: f64| {
        let positions = ball
            .positions()
            .iter()
            .map(|&p| p + sphaera::mesh::glam::DVec3::X * dx)
            .collect();
        sphaera::mesh::TriMesh::new(positions, ball.triangles().to_vec()).unwrap()
    };
    let (near, far) = (dir.path().join("near.obj"), dir.path().join("far.obj"));
    io::save(&near, &moved(1.5)).unwrap();
    io::save(&far, &moved(3.0)).unwrap();
    let report = json(&sphaera(&[
        "hal",
        a.to_str().unwrap(),
        "--intersect",
        near.to_str().unwrap(),
        "--json",
    ]));
    let intersect = &report["intersect"];
    assert_eq!(intersect["intersects"], true);
    let pairs = intersect["face_pairs"].as_array().unwrap();
    assert!(!pairs.is_empty());
    let shifted = moved(1.5);
    for pair in pairs {
        let (i, j) = (
            pair[0].as_u64().unwrap() as usize,
            pair[1].as_u64().unwrap() as usize,
        );
        let corners = |m: &sphaera::mesh::TriMesh, t: usize| {
            let t = m.triangle(t).unwrap();
            [t.a, t.b, t.c]
        };
        assert!(
            sphaera::hal::triangles_meet(corners(&ball, i), corners(&shifted, j)),
            "faces {i} and {j}"
        );
    }
    let report = json(&sphaera(&[
        "hal",
        a.to_str().unwrap(),
        "--intersect",
        far.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(report["intersect"]["intersects"], false);
    assert_eq!(report["intersect"]["pairs"], 0);
}
