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
    let report = run(&["--method", "expand"]);
    assert_eq!(report["surface"], "solid");
    assert_eq!(report["method_used"], "expand");
    let levels = report["levels"].as_array().expect("levels");
    assert_eq!(levels.len(), 3);
    assert_eq!(levels[0]["spheres"], 1);
    for level in levels {
        assert_eq!(level["uncovered_fraction"].as_f64(), Some(0.0), "{level}");
        assert_eq!(level["leaves_above"], 0, "a tree built to a depth: {level}");
        let lower = level["worst_error_lower"].as_f64().expect("lower");
        let upper = level["worst_error_upper"].as_f64().expect("upper");
        assert!(lower <= upper);
        // The tightest certified bound: never above the construction error.
        assert!(upper <= level["construction_error"].as_f64().expect("construction"));
        assert!(level["spheres"].as_u64().expect("count") <= 64);
    }
    assert!(report["tolerance"].is_null() && report["tolerance_met"].is_null());
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
    // A triangle without area has no surface to cover.
    let triangle = dir.path().join("triangle.obj");
    std::fs::write(&triangle, "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n").expect("written");
    let output = sphaera(&["spheretree", triangle.to_str().expect("utf-8")]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("cannot build a sphere-tree"), "{message}");

    let output = sphaera(&["spheretree", "--branch", "0"]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("branch"));

    // A medial method's option, checked by the medial methods.
    let output = sphaera(&["spheretree", "--method", "expand", "--error-fraction", "0"]);
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

/// A relative length of the report's diagonal.
fn of_diagonal(report: &serde_json::Value, fraction: f64) -> f64 {
    fraction * report["diagonal"].as_f64().expect("diagonal")
}

/// Runs `sphaera spheretree --json` with `args` (no light settings: the minimax method
/// does not use them), writing the tree to `tree`; the report and the tree read back.
fn run_to_file(
    args: &[&str],
    tree: &std::path::Path,
) -> (serde_json::Value, sphaera::spheretree::SphereTree) {
    let mut all = vec![
        "spheretree",
        "--json",
        "-q",
        "-o",
        tree.to_str().expect("utf-8"),
    ];
    all.extend(args);
    let report = json(&sphaera(&all));
    let text = std::fs::read_to_string(tree).expect("written");
    let tree = sphaera::spheretree::export::tree_from_json(&text).expect("our JSON");
    (report, tree)
}

#[test]
fn spheretree_to_a_tolerance_certifies_every_leaf_within_it() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let (report, tree) = run_to_file(&["--tolerance", "2%"], &dir.path().join("tree.json"));
    let tolerance = report["tolerance"].as_f64().expect("the tolerance");
    assert!((tolerance - of_diagonal(&report, 0.02)).abs() <= 1e-12 * tolerance);
    assert_eq!(report["goal"], "tolerance");
    assert_eq!(report["method_used"], "minimax");
    assert_eq!(report["tolerance_met"], true);
    let leaves = tree.leaves();
    assert!(leaves.len() > 1);
    assert_eq!(report["leaves"].as_u64(), Some(leaves.len() as u64));
    for &leaf in &leaves {
        let error = tree.nodes()[leaf].error;
        assert!(error <= tolerance, "leaf {leaf}: {error} > {tolerance}");
    }
    assert!(report["worst_leaf_error"].as_f64().expect("worst leaf") <= tolerance);

    // Each level is reported as its cut, which covers the surface.
    let levels = report["levels"].as_array().expect("levels");
    assert_eq!(levels.len(), tree.level_count());
    for (level, reported) in levels.iter().enumerate() {
        let cut = tree.cut_at(level);
        assert_eq!(reported["spheres"].as_u64(), Some(cut.len() as u64));
        assert_eq!(
            reported["leaves_above"].as_u64(),
            Some((cut.len() - tree.level(level).len()) as u64)
        );
        assert_eq!(
            reported["uncovered_fraction"].as_f64(),
            Some(0.0),
            "{reported}"
        );
        let lower = reported["worst_error_lower"].as_f64().expect("lower");
        let upper = reported["worst_error_upper"].as_f64().expect("upper");
        assert!(0.0 <= lower && lower <= upper, "{reported}");
        let worst_node = cut
            .iter()
            .map(|&i| tree.nodes()[i].error)
            .fold(0.0, f64::max);
        assert!(
            upper <= worst_node,
            "{upper} above the cut's node bounds {worst_node}"
        );
    }
    // The deepest cut is the leaves: certified within the tolerance.
    let deepest = levels.last().expect("a level");
    assert_eq!(deepest["spheres"].as_u64(), Some(leaves.len() as u64));
    assert!(deepest["worst_error_upper"].as_f64().expect("upper") <= tolerance);
}

#[test]
fn spheretree_to_a_tolerance_writes_every_format() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    // Four children at most: the leaves end at different depths.
    let light = ["--tolerance", "3%", "--branch", "4", "--no-evaluation"];
    let (report, tree) = run_to_file(&light, &dir.path().join("tree.json"));
    let leaves = tree.leaves();
    let depths: std::collections::BTreeSet<u32> =
        leaves.iter().map(|&i| tree.nodes()[i].level).collect();
    assert!(depths.len() > 1, "leaves at depths {depths:?}");
    assert_eq!(report["leaves"].as_u64(), Some(leaves.len() as u64));
    assert_eq!(
        report["depth"].as_u64(),
        Some(tree.level_count() as u64 - 1)
    );

    // `.sph`: the complete 4-ary layout, the nodes in their slots.
    let sph = dir.path().join("tree.sph");
    let mut args = vec!["spheretree", "-q", "-o", sph.to_str().expect("utf-8")];
    args.extend(light);
    assert!(sphaera(&args).status.success());
    let file = sphaera::spheretree::export::read_sph(
        &std::fs::read_to_string(&sph).expect("written"),
        sphaera::mesh::DVec3::ZERO,
    )
    .expect("a valid .sph");
    assert_eq!((file.levels, file.branch), (tree.level_count(), 4));
    assert_eq!(
        file.nodes.iter().filter(|n| n.is_some()).count(),
        tree.nodes().len()
    );

    // YAML: the leaves, which meet the tolerance.
    let yaml = dir.path().join("spheres.yaml");
    let mut args = vec!["spheretree", "-q", "-o", yaml.to_str().expect("utf-8")];
    args.extend(light);
    assert!(sphaera(&args).status.success());
    let text = std::fs::read_to_string(&yaml).expect("written");
    assert!(text.starts_with("collision_spheres:") && text.contains("\"bunny\":"));
    assert_eq!(text.matches("center:").count(), leaves.len());
    let radii: Vec<f64> = text
        .lines()
        .filter_map(|l| l.trim().strip_prefix("radius:"))
        .map(|r| r.trim().parse().expect("a radius"))
        .collect();
    let mut expected: Vec<f64> = leaves
        .iter()
        .map(|&i| tree.nodes()[i].sphere.radius)
        .collect();
    let mut radii_sorted = radii.clone();
    expected.sort_by(f64::total_cmp);
    radii_sorted.sort_by(f64::total_cmp);
    assert_eq!(radii_sorted, expected, "the YAML holds the leaves");
}

#[test]
fn spheretree_with_an_unreachable_tolerance_says_why() {
    // One child per node never gets tighter: the construction gives up at its depth cap.
    let output = sphaera(&["spheretree", "-q", "--tolerance", "10%", "--branch", "1"]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("cannot meet the tolerance"), "{message}");
}

#[test]
fn spheretree_with_a_node_budget_meets_the_tolerance_within_it_or_says_why() {
    // Within a generous budget: met, and the report says the budget.
    let report = json(&sphaera(&[
        "spheretree",
        "--json",
        "--tolerance",
        "3%",
        "--max-nodes",
        "400",
        "--effort",
        "quick",
        "--no-evaluation",
    ]));
    assert_eq!(report["tolerance_met"], true);
    assert_eq!(report["max_nodes"], 400);
    assert_eq!(report["effort"], "quick");
    let spheres: u64 = report["levels"]
        .as_array()
        .expect("levels")
        .iter()
        .map(|l| l["spheres"].as_u64().expect("spheres") - l["leaves_above"].as_u64().unwrap_or(0))
        .sum();
    assert!(spheres <= 400, "{spheres} nodes");
    // A budget too small for the tolerance: refused with the figures, never more nodes.
    let output = sphaera(&[
        "spheretree",
        "-q",
        "--tolerance",
        "0.5%",
        "--max-nodes",
        "20",
        "--effort",
        "quick",
    ]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains("cannot meet the tolerance") && message.contains("20 nodes"),
        "{message}"
    );
}

#[test]
fn spheretree_tolerance_and_sphere_counts_need_minimax_and_sane_values() {
    for (args, expected) in [
        (
            &["--tolerance", "2%", "--method", "merge"][..],
            "--tolerance",
        ),
        (&["--spheres", "8", "--method", "octree"][..], "--spheres"),
        (&["--spheres", "0"][..], "10,000"),
        (&["--spheres", "10001"][..], "10,000"),
        (&["--spheres", "8", "--depth", "2"][..], "--depth"),
        (&["--spheres", "8", "--branch", "2"][..], "--branch"),
        (&["--spheres", "8", "--tolerance", "1%"][..], "--tolerance"),
        (&["--tolerance", "1%", "--depth", "2"][..], "--depth"),
        (&["--max-nodes", "100"][..], "--tolerance"),
        (
            &["--tolerance", "1%", "--max-nodes", "0"][..],
            "--max-nodes",
        ),
        (
            &["--tolerance", "1%", "--max-nodes", "3000000"][..],
            "--max-nodes",
        ),
        (
            &["--effort", "thorough", "--method", "merge"][..],
            "--effort",
        ),
        (
            &["--effort", "fast"][..],
            "[possible values: quick, default, thorough]",
        ),
    ] {
        let mut all = vec!["spheretree", "-q"];
        all.extend(args);
        let output = sphaera(&all);
        assert!(!output.status.success(), "{args:?}");
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(
            message.contains(expected) && !message.contains("cannot build"),
            "{args:?}: {message}"
        );
        if expected == "10,000" {
            assert!(message.contains("--spheres"), "{message}");
        }
    }
}

/// `--spheres N`: the report and the written tree, one level below the root.
fn one_level(spheres: usize) -> (serde_json::Value, sphaera::spheretree::SphereTree) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let n = spheres.to_string();
    let (report, tree) = run_to_file(&["--spheres", &n], &dir.path().join("tree.json"));
    assert_eq!(report["goal"], "spheres");
    assert_eq!(report["spheres_requested"].as_u64(), Some(spheres as u64));
    assert_eq!(tree.level_count(), 2);
    let levels = report["levels"].as_array().expect("levels");
    assert_eq!(levels.len(), 2);
    let level = &levels[1];
    assert_eq!(level["spheres"].as_u64(), Some(tree.level(1).len() as u64));
    assert_eq!(report["leaves"].as_u64(), Some(tree.level(1).len() as u64));
    assert_eq!(level["uncovered_fraction"].as_f64(), Some(0.0), "{level}");
    assert!(level["certificate"].is_object(), "certified: {level}");
    let lower = level["worst_error_lower"].as_f64().expect("lower");
    let upper = level["worst_error_upper"].as_f64().expect("upper");
    assert!(0.0 < lower && lower <= upper);
    // A budget is never exceeded.
    assert!(tree.level(1).len() <= spheres);
    (report, tree)
}

#[test]
fn spheretree_gives_exactly_8_spheres_in_one_level() {
    let (_, tree) = one_level(8);
    assert_eq!(tree.level(1).len(), 8);
}

#[test]
fn spheretree_gives_exactly_37_spheres_in_one_level() {
    let (_, tree) = one_level(37);
    assert_eq!(tree.level(1).len(), 37);
}

#[test]
fn spheretree_covers_a_flat_sheet_as_a_shell() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let sheet = dir.path().join("sheet.obj");
    std::fs::write(
        &sheet,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n",
    )
    .expect("written");
    let sheet = sheet.to_str().expect("utf-8");
    let report = json(&sphaera(&[
        "spheretree",
        sheet,
        "--depth",
        "2",
        "--json",
        "-q",
    ]));
    assert_eq!(report["surface"], "shell");
    assert_eq!(report["method"], "auto");
    assert_eq!(report["method_used"], "minimax");
    for level in report["levels"].as_array().expect("levels") {
        assert_eq!(level["uncovered_fraction"].as_f64(), Some(0.0), "{level}");
    }
    let text = sphaera(&["spheretree", sheet, "--depth", "1", "-q"]);
    assert!(String::from_utf8_lossy(&text.stdout).contains("shell (no inside)"));

    let output = sphaera(&["spheretree", sheet, "--method", "expand", "-q"]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("needs a solid"), "{message}");
}

#[test]
fn spheretree_too_deep_for_sph_says_so_and_writes_nothing() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("tree.sph");
    // Nine levels of up to eight children: more slots than a .sph file may have.
    let output = sphaera(&[
        "spheretree",
        "-q",
        "--method",
        "octree",
        "--depth",
        "8",
        "--samples",
        "2000",
        "--no-evaluation",
        "-o",
        path.to_str().expect("utf-8"),
    ]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains("cannot write the .sph tree")
            && message.contains("9 levels")
            && message.contains(".json"),
        "{message}"
    );
    assert_eq!(std::fs::read_dir(dir.path()).expect("listed").count(), 0);
}
