//! Meshes with holes taken as solids (a scan open at its base, a capsule with a missing
//! patch): the inside the winding number gives them reaches out through the holes, so a
//! sphere's radius less its centre's depth does not bound its error there. Every node's
//! error must still be a certified upper bound, checked independently.

mod checks;

use sphaera_mesh::{Length, Surface, TriMesh, shapes};
use sphaera_spheretree::{Effort, SphereTreeOptions, build};

/// A capsule with the triangles around its top pole removed: a hole a quarter of its
/// width across.
fn holed_capsule() -> TriMesh {
    let mesh = shapes::capsule(0.5, 2.0, 16).expect("capsule");
    let top = mesh
        .positions()
        .iter()
        .map(|p| p.z)
        .fold(f64::NEG_INFINITY, f64::max);
    let kept: Vec<[u32; 3]> = mesh
        .triangles()
        .iter()
        .copied()
        .filter(|t| {
            t.iter()
                .all(|&v| mesh.positions()[v as usize].z < top - 0.02)
        })
        .collect();
    assert!(kept.len() < mesh.triangle_count(), "a hole was cut");
    TriMesh::new(mesh.positions().to_vec(), kept).expect("valid mesh")
}

/// Fails today: the certified evaluation (`evaluate::sphere_error`) takes a patch of a
/// sphere that crosses no triangle to lie on one side, which holds for closed meshes
/// only; across a hole the winding number passes ½ without crossing the mesh, and a
/// sphere poking through this hole is under-estimated (0.063 certified, 0.123 sampled).
#[test]
#[ignore = "known: the certified evaluation assumes a closed mesh (see the doc comment)"]
fn node_errors_bound_the_protrusion_of_a_holed_capsule() {
    let mesh = holed_capsule();
    let surface = Surface::new(&mesh).expect("still a solid by its winding number");
    assert!(!surface.is_embedded_solid());
    let tree = build(
        &surface,
        &SphereTreeOptions::default().with_effort(Effort::Quick),
    )
    .expect("builds");
    checks::check_tree(&surface, &tree, 3_000, 256, "holed capsule, depth 3");
    let tolerance = 0.04 * surface.diagonal();
    let options = SphereTreeOptions::default()
        .with_effort(Effort::Quick)
        .with_tolerance(Length::Absolute(tolerance));
    let tree = build(&surface, &options).expect("builds");
    for &leaf in &tree.leaves() {
        assert!(tree.nodes()[leaf].error <= tolerance);
    }
    checks::check_tree(&surface, &tree, 3_000, 256, "holed capsule, 4 %");
}

/// The Stanford bunny as scanned, open at its base: its level-3 spheres were reported
/// within 2.0 % of the diagonal by eq. 2 while the certified evaluation found 3.3 %.
#[test]
fn node_errors_bound_the_protrusion_of_the_open_stanford_bunny() {
    let Some(data) =
        sphaera_tests::data_dir("node_errors_bound_the_protrusion_of_the_open_stanford_bunny")
    else {
        return;
    };
    let mesh = sphaera_mesh::io::load(data.join("stanford-bunny.obj")).expect("loads");
    let surface = Surface::new(&mesh).expect("a solid by its winding number");
    let options = SphereTreeOptions::default()
        .with_effort(Effort::Quick)
        .with_depth(2);
    let tree = build(&surface, &options).expect("builds");
    checks::check_tree(&surface, &tree, 2_000, 128, "stanford bunny");
}

/// A tolerance tree on an open mesh taken as a solid meets small tolerances: medial
/// balls beside a hole reach into it, and a region whose spheres poke out through the
/// hole is divided around the surface instead (the Panda's sixth link, 56 holes, was
/// refused at 2 % of its diagonal after 119,534 spheres).
#[test]
fn tolerance_trees_on_meshes_with_holes_meet_small_tolerances() {
    let mut cases = vec![("holed capsule".to_owned(), holed_capsule())];
    if let Some(data) =
        sphaera_tests::data_dir("tolerance_trees_on_meshes_with_holes_meet_small_tolerances")
    {
        let link6 = data.join("robots/franka_panda/collision/link6.obj");
        cases.push((
            "panda link6".to_owned(),
            sphaera_mesh::io::load(link6).expect("loads"),
        ));
    }
    for (name, mesh) in cases {
        let surface = Surface::new(&mesh).expect("a solid by its winding number");
        for fraction in [0.03, 0.02] {
            let tolerance = fraction * surface.diagonal();
            let options = SphereTreeOptions::default()
                .with_effort(Effort::Quick)
                .with_tolerance(Length::Absolute(tolerance));
            let tree =
                build(&surface, &options).unwrap_or_else(|e| panic!("{name} at {fraction}: {e}"));
            for &leaf in &tree.leaves() {
                assert!(
                    tree.nodes()[leaf].error <= tolerance,
                    "{name} at {fraction}"
                );
            }
            assert!(
                tree.leaves().len() < 2_000,
                "{name} at {fraction}: {} leaves",
                tree.leaves().len()
            );
        }
    }
}

/// Trees built to a depth on open meshes taken as solids do not get looser down a branch:
/// a region beside a hole whose medial children poke out through it is divided around the
/// surface instead, whichever division is tighter kept (the Stanford bunny's level 3 had
/// a child reaching 3.68 % of the diagonal under a parent within 2.56 %), and a child no
/// division makes tighter than its parent takes the parent's sphere (the holed capsule's
/// spheres near the hole are its own medial balls, pinned by the dent the hole makes in
/// the solid, and at level 3 the surface's pieces are still too large for spheres around
/// them to be tighter).
#[test]
fn depth_trees_on_meshes_with_holes_do_not_loosen_down_a_branch() {
    let mut cases = vec![("holed capsule".to_owned(), holed_capsule())];
    if let Some(data) =
        sphaera_tests::data_dir("depth_trees_on_meshes_with_holes_do_not_loosen_down_a_branch")
    {
        for (name, file) in [
            ("panda link6", "robots/franka_panda/collision/link6.obj"),
            ("stanford bunny", "stanford-bunny.obj"),
        ] {
            let mesh = sphaera_mesh::io::load(data.join(file)).expect("loads");
            cases.push((name.to_owned(), mesh));
        }
    }
    for (name, mesh) in cases {
        let surface = Surface::new(&mesh).expect("a solid by its winding number");
        let options = SphereTreeOptions::default()
            .with_effort(Effort::Quick)
            .with_depth(3);
        let tree = build(&surface, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
        for (index, node) in tree.nodes().iter().enumerate() {
            for child in tree.children(index) {
                assert!(
                    child.error <= node.error,
                    "{name}: node {index} (level {}, {}) has a child reaching {}",
                    node.level,
                    node.error,
                    child.error
                );
            }
        }
    }
}
