//! Meshes with holes taken as solids (a scan open at its base, a capsule with a missing
//! patch): the inside the winding number gives them reaches out through the holes, so a
//! sphere's radius less its centre's depth does not bound its error there. Every node's
//! error must still be a certified upper bound, checked independently.

mod checks;

use proptest::prelude::*;
use sphaera_mesh::glam::DQuat;
use sphaera_mesh::{DVec3, Length, TriMesh, shapes};
use sphaera_query::Surface;
use sphaera_spheretree::evaluate::{EvaluationOptions, sphere_error};
use sphaera_spheretree::{Effort, Sphere, SphereTreeOptions, build};

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

/// A sphere poking through the hole was under-estimated before the evaluation took
/// holes into account (0.063 certified, 0.123 sampled): across a hole the winding number
/// passes ½ without crossing the mesh.
#[test]
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
}

/// The holed capsule's tolerance tree: every leaf within 4 % of the diagonal, every
/// node's error bounding its protrusion. (Once out of reach: the spheres covering the
/// hole's rim kept reaching out through it; the nodes that poke out through a hole are now
/// divided on the shell.)
#[test]
fn holed_capsule_tolerance_tree_meets_the_tolerance() {
    let mesh = holed_capsule();
    let surface = Surface::new(&mesh).expect("still a solid by its winding number");
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
    let mesh = sphaera_io::load(data.join("stanford-bunny.obj")).expect("loads");
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
            sphaera_io::load(link6).expect("loads"),
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
            let mesh = sphaera_io::load(data.join(file)).expect("loads");
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

/// `mesh` without the triangles whose centroid's direction from the origin lies within
/// `angle` (radians) of one of `directions`: one hole per direction.
fn without_caps(mesh: &TriMesh, directions: &[DVec3], angle: f64) -> TriMesh {
    let cos = angle.cos();
    let kept: Vec<[u32; 3]> = mesh
        .triangles()
        .iter()
        .copied()
        .filter(|t| {
            let centroid = t
                .iter()
                .map(|&v| mesh.positions()[v as usize])
                .sum::<DVec3>()
                .normalize();
            directions.iter().all(|d| centroid.dot(d.normalize()) < cos)
        })
        .collect();
    assert!(kept.len() < mesh.triangle_count(), "a hole was cut");
    TriMesh::new(mesh.positions().to_vec(), kept).expect("valid mesh")
}

/// The cube `[-1, 1]³` without its face `x = 1`.
fn box_without_a_face(resolution: usize) -> TriMesh {
    let cube = shapes::cube(2.0, resolution).expect("cube");
    let kept: Vec<[u32; 3]> = cube
        .triangles()
        .iter()
        .copied()
        .filter(|t| {
            t.iter()
                .any(|&v| cube.positions()[v as usize].x < 1.0 - 1e-9)
        })
        .collect();
    TriMesh::new(cube.positions().to_vec(), kept).expect("valid mesh")
}

/// `mesh` rotated by `rotation`, scaled by `scale` and moved by `shift`.
fn placed(mesh: &TriMesh, rotation: DQuat, scale: f64, shift: DVec3) -> TriMesh {
    let positions = mesh
        .positions()
        .iter()
        .map(|&p| rotation * (scale * p) + shift)
        .collect();
    TriMesh::new(positions, mesh.triangles().to_vec()).expect("valid mesh")
}

/// The holed meshes of the generated tests: a sphere with one to three holes of several
/// sizes, a capsule with holes at a pole and on its side, a box missing a face.
fn holed_mesh(kind: usize, size: f64) -> TriMesh {
    let sphere = || shapes::sphere(1.0, 24).expect("sphere");
    let capsule = || shapes::capsule(0.5, 2.0, 24).expect("capsule");
    match kind % 5 {
        0 => without_caps(&sphere(), &[DVec3::Z], size),
        1 => without_caps(
            &sphere(),
            &[
                DVec3::Z,
                DVec3::new(1.0, 0.2, -0.3),
                DVec3::new(-0.4, -1.0, -0.5),
            ],
            0.6 * size,
        ),
        2 => without_caps(&capsule(), &[DVec3::Z], 0.5 * size),
        3 => without_caps(
            &capsule(),
            &[DVec3::X, DVec3::new(-0.3, 1.0, -1.5)],
            0.4 * size,
        ),
        _ => box_without_a_face(1 + kind % 3),
    }
}

/// Spheres around the holes and elsewhere: centred near boundary vertices (poking
/// through the holes or sitting inside them), inside, and around the whole object.
fn probe_spheres(mesh: &TriMesh, seed: u64) -> Vec<Sphere> {
    let diagonal = mesh.bounding_box_diagonal();
    let center = mesh.bounding_box().center();
    // The vertices of the boundary: those of edges used by one triangle.
    let mut uses = std::collections::HashMap::new();
    for t in mesh.triangles() {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            *uses.entry((a.min(b), a.max(b))).or_insert(0_u32) += 1;
        }
    }
    let mut rim: Vec<u32> = uses
        .iter()
        .filter(|&(_, &n)| n == 1)
        .map(|(&(a, _), _)| a)
        .collect();
    rim.sort_unstable();
    rim.dedup();
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1_u64 << 53) as f64
    };
    let mut spheres = Vec::new();
    for i in 0..10 {
        let offset = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 0.3 * diagonal;
        let radius = (0.03 + 0.3 * next()) * diagonal;
        let base = match i % 3 {
            0 | 1 if !rim.is_empty() => {
                let v = rim[(next() * rim.len() as f64) as usize % rim.len()];
                let p = mesh.positions()[v as usize];
                // Towards the centre or away from it: through the hole or across it.
                p + (center - p) * (next() - 0.3)
            }
            _ => center,
        };
        spheres.push(Sphere::new(base + offset, radius));
    }
    spheres
}

/// Checks `fit` against the independent sampled measure: no sampled point of the sphere
/// lies farther outside than `upper`, and the witness of `lower` is outside, that far
/// from the surface.
fn check_fit(surface: &Surface, sphere: &Sphere, what: &str) {
    let diagonal = surface.diagonal();
    let options = EvaluationOptions::default().with_tolerance(Length::Absolute(1e-3 * diagonal));
    let fit = sphere_error(surface, sphere, &options).expect("evaluates");
    let sampled = checks::protrusion(surface, &checks::sphere_points(sphere, 2_000));
    let slack = 1e-9 * diagonal;
    assert!(
        sampled <= fit.upper + slack,
        "{what}: {sphere:?} reaches {sampled} beyond the surface, certified {}",
        fit.upper
    );
    assert!(fit.lower <= fit.upper + slack, "{what}: {fit:?}");
    if let Some(witness) = fit.witness {
        let signed = surface.signed_closest(witness).expect("finite");
        assert!(!signed.inside, "{what}: the witness {witness} is inside");
        assert!(
            (signed.closest.distance - fit.lower).abs() <= slack,
            "{what}: the witness is {} out, lower is {}",
            signed.closest.distance,
            fit.lower
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(24)))]

    /// Every sphere's certified error bounds its sampled protrusion on meshes with holes
    /// of several sizes, rotated, scaled and moved.
    #[test]
    fn certified_errors_bound_the_protrusion_on_holed_meshes(
        kind in 0_usize..15,
        size in 0.2_f64..0.9,
        axis in (-1.0_f64..1.0, -1.0_f64..1.0, 0.1_f64..1.0),
        angle in 0.0_f64..6.3,
        scale in 0.01_f64..100.0,
        seed in 0_u64..1_000,
    ) {
        let rotation = DQuat::from_axis_angle(DVec3::new(axis.0, axis.1, axis.2).normalize(), angle);
        let shift = DVec3::new(3.0, -1.0, 2.0) * scale;
        let mesh = placed(&holed_mesh(kind, size), rotation, scale, shift);
        let Ok(surface) = Surface::new(&mesh) else {
            // The hole is too large for an inside: nothing to check.
            return Ok(());
        };
        prop_assume!(!surface.is_embedded_solid());
        let what = format!("kind {kind}, size {size:.2}, scale {scale:.3}");
        for sphere in probe_spheres(&mesh, seed) {
            check_fit(&surface, &sphere, &what);
        }
    }
}

/// Whole trees on holed meshes: every node's error bounds its sampled protrusion.
#[test]
fn node_errors_bound_the_protrusion_of_holed_meshes() {
    for (kind, size) in [(0, 0.3), (1, 0.5), (3, 0.6), (4, 0.0)] {
        let mesh = placed(
            &holed_mesh(kind, size),
            DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7),
            3.0,
            DVec3::new(-1.0, 0.5, 2.0),
        );
        let surface = Surface::new(&mesh).expect("a solid by its winding number");
        let options = SphereTreeOptions::default()
            .with_effort(Effort::Quick)
            .with_depth(2)
            .with_branch(4);
        let tree = build(&surface, &options).expect("builds");
        checks::check_tree(&surface, &tree, 2_000, 256, &format!("holed mesh {kind}"));
    }
}
