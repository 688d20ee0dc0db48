//! A mesh scaled by a power of two gives the same tree, scaled: every centre, radius and
//! error exactly, and the same structure. (Other similarities move the rounding, and the
//! spread they cause is measured by `sphaera-eval`'s `spheretree_similarity` chart.)

use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_spheretree::{Method, SphereTree, SphereTreeOptions, Surface, build};
use sphaera_tests::awkward;

fn small(method: Method) -> SphereTreeOptions {
    SphereTreeOptions::default()
        .with_method(method)
        .with_samples(800)
        .with_depth(2)
        .with_branch(4)
        .with_initial_spheres(60)
        .with_min_spheres_per_node(20)
        .with_forming_points(150)
}

fn scaled(mesh: &TriMesh, factor: f64) -> TriMesh {
    awkward::mapped(mesh, |p| p * factor, false)
}

/// The same tree, every number of `b` exactly `factor` times `a`'s.
fn assert_scaled(a: &SphereTree, b: &SphereTree, factor: f64, what: &str) {
    assert_eq!(a.nodes().len(), b.nodes().len(), "{what}: node count");
    // Bit for bit: the same tree, every number scaled.
    let bits = |v: DVec3| [v.x, v.y, v.z].map(f64::to_bits);
    for (i, (x, y)) in a.nodes().iter().zip(b.nodes()).enumerate() {
        assert_eq!(
            bits(x.sphere.center * factor),
            bits(y.sphere.center),
            "{what}: node {i} centre"
        );
        assert_eq!(
            (x.sphere.radius * factor).to_bits(),
            y.sphere.radius.to_bits(),
            "{what}: node {i} radius"
        );
        assert_eq!(
            (x.error * factor).to_bits(),
            y.error.to_bits(),
            "{what}: node {i} error"
        );
        assert_eq!(
            (x.parent, x.children.clone(), x.region_samples),
            (y.parent, y.children.clone(), y.region_samples),
            "{what}: node {i} structure"
        );
    }
}

#[test]
fn scaling_by_a_power_of_two_gives_the_same_tree_scaled() {
    let meshes = [
        ("L-block", shapes::l_block(2.0, 1.0, 0.5, 4).expect("valid")),
        ("pinched tori", awkward::tori_touching_at_a_vertex(16)),
        (
            "moved cube",
            awkward::mapped(
                &shapes::cube(1.0, 4).expect("valid"),
                |p| p + DVec3::new(3.0, -2.0, 0.5),
                false,
            ),
        ),
    ];
    for (name, mesh) in &meshes {
        for method in [Method::Auto, Method::Merge, Method::Octree] {
            let base = build(&Surface::new(mesh).expect("solid"), &small(method)).expect("builds");
            for factor in [4.0, 0.125] {
                let other = scaled(mesh, factor);
                let tree =
                    build(&Surface::new(&other).expect("solid"), &small(method)).expect("builds");
                assert_scaled(
                    &base,
                    &tree,
                    factor,
                    &format!("{name}, {method:?}, ×{factor}"),
                );
            }
        }
    }
}
