//! End-to-end tests of `sphaera view`: the page holds the mesh and every level of the
//! tree, fetches nothing, and bad inputs are clear errors, never a broken page.

mod common;

use common::{json, sphaera};

/// The page's data element, parsed.
fn page_data(html: &str) -> serde_json::Value {
    let start = html
        .find(r#"<script type="application/json" id="sphaera-data">"#)
        .expect("the data element");
    let rest = &html[start..];
    let open = rest.find('>').expect("its tag") + 1;
    let close = rest.find("</script>").expect("its end");
    serde_json::from_str(&rest[open..close]).expect("the data is JSON")
}

/// A small closed mesh and a shallow tree of it, written to `dir`.
fn mesh_and_tree(dir: &std::path::Path) -> (String, String) {
    let mesh = dir.join("ball.obj");
    sphaera_mesh_obj(
        &mesh,
        &sphaera::mesh::shapes::sphere(1.0, 12).expect("sphere"),
    );
    let tree = dir.join("ball.json");
    let output = sphaera(&[
        "spheretree",
        mesh.to_str().expect("utf-8"),
        "--depth",
        "2",
        "--branch",
        "4",
        "--samples",
        "1500",
        "--initial-spheres",
        "80",
        "--min-spheres-per-node",
        "20",
        "--no-evaluation",
        "-q",
        "-o",
        tree.to_str().expect("utf-8"),
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    (mesh.display().to_string(), tree.display().to_string())
}

fn sphaera_mesh_obj(path: &std::path::Path, mesh: &sphaera::mesh::TriMesh) {
    sphaera::mesh::io::save(path, mesh).expect("save");
}

#[test]
fn the_page_holds_the_mesh_and_every_level_and_fetches_nothing() {
    let dir = tempfile::tempdir().expect("a folder");
    let (mesh, tree) = mesh_and_tree(dir.path());
    let page = dir.path().join("view.html");
    let report = json(&sphaera(&[
        "view",
        &mesh,
        "--tree",
        &tree,
        "-o",
        page.to_str().expect("utf-8"),
        "--json",
    ]));
    let html = std::fs::read_to_string(&page).expect("the page");
    let data = page_data(&html);
    let levels = data["levels"].as_array().expect("levels");
    let reported = report["levels"].as_array().expect("levels");
    assert_eq!(levels.len(), 3);
    assert_eq!(levels.len(), reported.len());
    for (level, reported) in levels.iter().zip(reported) {
        assert_eq!(level["count"], reported["spheres"]);
        // Four f32 per sphere, base64.
        let bytes = level["spheres"].as_str().expect("base64").len() / 4 * 3;
        let count = level["count"].as_u64().expect("count") as usize;
        assert!(
            bytes >= 16 * count && bytes <= 16 * count + 2,
            "{bytes} for {count}"
        );
        let (lower, upper) = (
            level["error_lower"].as_f64().expect("certified"),
            level["error_upper"].as_f64().expect("certified"),
        );
        assert!(0.0 <= lower && lower <= upper);
        assert_eq!(level["error_upper"], reported["error_upper"]);
    }
    assert_eq!(data["triangles_count"], report["triangles"]);
    // Self-contained: three.js inlined, no script or stylesheet from the network.
    assert!(html.contains("data:text/javascript;base64,"));
    for fetch in ["src=\"http", "href=\"http", "from \"http", "from 'http"] {
        assert!(!html.contains(fetch), "{fetch}");
    }
    assert!(
        !html.contains("SPHAERA_"),
        "a placeholder was left in the page"
    );
    assert!(data["simplified"].is_null());

    // With a simplification: its mesh and certified bound are in the page and the report.
    let report = json(&sphaera(&[
        "view",
        &mesh,
        "--tree",
        &tree,
        "--simplify",
        "0.3",
        "-o",
        page.to_str().expect("utf-8"),
        "--json",
    ]));
    let data = page_data(&std::fs::read_to_string(&page).expect("the page"));
    let simplified = &data["simplified"];
    let triangles = simplified["triangles_count"].as_u64().expect("triangles");
    let input = data["triangles_count"].as_u64().expect("triangles");
    assert!(triangles < input, "{triangles} of {input}");
    assert_eq!(
        simplified["error_bound"],
        report["simplified"]["error_bound"]
    );
    assert!(report["simplified"]["error_bound"].as_f64().expect("bound") > 0.0);
    let output = sphaera(&["view", &mesh, "--tree", &tree, "--simplify", "1.5"]);
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && message.contains("(0, 1]"),
        "{message}"
    );
}

#[test]
fn bad_inputs_are_clear_errors_and_write_no_page() {
    let dir = tempfile::tempdir().expect("a folder");
    let (_, tree) = mesh_and_tree(dir.path());
    let page = dir.path().join("view.html");
    let page_arg = page.to_str().expect("utf-8");

    // A tree for another mesh: the ball's tree does not hold a far-away cube.
    let cube = dir.path().join("cube.obj");
    let far = sphaera::mesh::shapes::cube(1.0, 2).expect("cube");
    let moved = sphaera::mesh::TriMesh::new(
        far.positions()
            .iter()
            .map(|p| *p + sphaera::mesh::DVec3::new(10.0, 0.0, 0.0))
            .collect(),
        far.triangles().to_vec(),
    )
    .expect("moved");
    sphaera_mesh_obj(&cube, &moved);
    let output = sphaera(&[
        "view",
        cube.to_str().expect("utf-8"),
        "--tree",
        &tree,
        "-o",
        page_arg,
    ]);
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && message.contains("another mesh"),
        "{message}"
    );

    // A .sph whose header promises more spheres than it has.
    let sph = dir.path().join("short.sph");
    std::fs::write(&sph, "2 4\n0 0 0 1 1\n0.5 0 0 0.5 1\n").expect("write");
    let output = sphaera(&[
        "view",
        "--tree",
        sph.to_str().expect("utf-8"),
        "-o",
        page_arg,
    ]);
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && message.contains("short.sph"),
        "{message}"
    );

    // An empty mesh.
    let empty = dir.path().join("empty.obj");
    std::fs::write(&empty, "v 0 0 0\nv 1 0 0\nv 0 1 0\n").expect("write");
    let output = sphaera(&["view", empty.to_str().expect("utf-8"), "-o", page_arg]);
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && message.contains("empty.obj"),
        "{message}"
    );

    assert!(!page.exists(), "no page is written for bad input");
}
