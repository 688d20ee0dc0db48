//! The self-collision matrix and the compiled kinematics under it: poses equal to
//! `Urdf::link_poses`, every adjacent pair left out, no "Never" pair whose posed meshes a
//! brute-force test finds in contact (at the matrix's own configurations and at fresh
//! ones), the same matrix whatever the thread count, and bad options refused.

use std::collections::BTreeMap;

use glam::DAffine3;
use proptest::prelude::*;
use sphaera_mesh::TriMesh;
use sphaera_robot::{
    DisableReason, GeometrySource, KinematicChain, LinkGeometry, MeshResolver, RobotError,
    RobotSpheres, SelfCollisionMatrix, SelfCollisionOptions, SphereBudget, SpherizeOptions, Urdf,
    self_collision_matrix, spherize,
};

fn spherized(urdf: &Urdf, per_link: usize) -> RobotSpheres {
    let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(per_link));
    spherize(urdf, &MeshResolver::new(urdf.folder()), &options).expect("spherize")
}

/// A procedural arm of `n` links of boxes along z, each on a revolute joint about y.
fn arm(n: usize, mimic: bool) -> Urdf {
    let mut text = String::from("<robot name=\"arm\">");
    for k in 0..n {
        text += &format!(
            "<link name=\"l{k}\"><collision><origin xyz=\"0 0 0.15\"/><geometry><box size=\"0.06 0.06 0.3\"/></geometry></collision></link>"
        );
    }
    for k in 1..n {
        let follows = if mimic && k == n - 1 && k >= 2 {
            format!(
                "<mimic joint=\"j{}\" multiplier=\"-0.5\" offset=\"0.1\"/>",
                k - 1
            )
        } else {
            String::new()
        };
        text += &format!(
            "<joint name=\"j{k}\" type=\"revolute\"><parent link=\"l{}\"/><child link=\"l{k}\"/><origin xyz=\"0 0 0.32\" rpy=\"0.1 0 0\"/><axis xyz=\"0 1 0\"/><limit lower=\"-2\" upper=\"2\"/>{follows}</joint>",
            k - 1
        );
    }
    text += "</robot>";
    Urdf::parse(&text, "arm.urdf").expect("the arm parses")
}

/// The arm's poses computed here, independently of the crate: link `k` hangs from link
/// `k − 1` at `(0, 0, 0.32)`, turned by 0.1 rad about x (the origin's roll), then by its
/// joint's value about y; the last joint of a mimicking arm is `−0.5 · q[k − 1] + 0.1`.
fn arm_poses(n: usize, mimic: bool, q: &[f64]) -> Vec<DAffine3> {
    let mut poses = vec![DAffine3::IDENTITY];
    let mut values = Vec::new();
    for k in 1..n {
        let value = if mimic && k == n - 1 && k >= 2 {
            -0.5 * values[k - 2] + 0.1
        } else {
            q[values.len()]
        };
        values.push(value);
        let origin = DAffine3::from_translation(glam::DVec3::new(0.0, 0.0, 0.32))
            * DAffine3::from_rotation_x(0.1);
        poses.push(poses[k - 1] * origin * DAffine3::from_rotation_y(value));
    }
    poses
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(32)))]

    /// The compiled chain (and `Urdf::link_poses`, which uses it) poses every link as the
    /// arm's own arithmetic does, mimic joints included, and its samples stay in the
    /// joints' ranges.
    #[test]
    fn the_chain_poses_as_link_poses(n in 2usize..9, seed in 0u64..1000, index in 0u64..1000, mimic in any::<bool>()) {
        let urdf = arm(n, mimic);
        let chain = KinematicChain::new(&urdf).unwrap();
        prop_assert_eq!(chain.joints().len(), n - 1 - usize::from(mimic && n > 2));
        let q = chain.sample(seed, index);
        for (j, v) in chain.joints().iter().zip(&q) {
            prop_assert!(j.lower <= *v && *v <= j.upper);
        }
        let expected = arm_poses(n, mimic, &q);
        let poses = chain.poses(&q).unwrap();
        let named: BTreeMap<String, f64> =
            chain.joints().iter().zip(&q).map(|(j, &v)| (j.name.clone(), v)).collect();
        let by_name = urdf.link_poses(&named).unwrap();
        for (k, pose) in expected.iter().enumerate() {
            let name = format!("l{k}");
            let got = poses[chain.link_index(&name).unwrap()];
            prop_assert!(got.abs_diff_eq(*pose, 1e-12), "{name}: {got:?} against {pose:?}");
            prop_assert!(by_name[&name].abs_diff_eq(*pose, 1e-12), "{name} by link_poses");
        }
    }
}

#[test]
fn a_configuration_of_the_wrong_length_is_refused() {
    let chain = KinematicChain::new(&arm(3, false)).unwrap();
    assert!(matches!(chain.poses(&[0.0]), Err(RobotError::Joint { .. })));
    let error = chain.poses(&[0.0, f64::NAN]).unwrap_err();
    assert!(error.to_string().contains("j2"), "{error}");
}

#[test]
fn bad_options_are_refused() {
    let urdf = arm(3, false);
    let robot = spherized(&urdf, 2);
    for options in [
        SelfCollisionOptions::default().with_always_fraction(0.0),
        SelfCollisionOptions::default().with_always_fraction(1.5),
        SelfCollisionOptions::default().with_always_fraction(f64::NAN),
        SelfCollisionOptions::default().with_padding(-0.1),
        SelfCollisionOptions::default().with_padding(f64::INFINITY),
        SelfCollisionOptions::default().with_samples(sphaera_robot::MAX_SELF_COLLISION_SAMPLES + 1),
    ] {
        assert!(
            matches!(
                self_collision_matrix(&urdf, &robot, &options),
                Err(RobotError::InvalidParameter { .. })
            ),
            "{options:?}"
        );
    }
    // Spheres of a link the URDF does not have.
    let other = spherized(&arm(4, false), 2);
    assert!(matches!(
        self_collision_matrix(&urdf, &other, &SelfCollisionOptions::default()),
        Err(RobotError::UnknownLink { .. })
    ));
}

/// A link without geometry between two links makes them adjacent (MoveIt's rule), and
/// the rules apply in MoveIt's order.
#[test]
fn links_without_geometry_join_their_neighbours() {
    let urdf = Urdf::parse(
        r#"<robot name="r">
          <link name="a"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>
          <link name="flange"/>
          <link name="b"><collision><origin xyz="0 0 0.1"/><geometry><sphere radius="0.05"/></geometry></collision></link>
          <link name="c"><collision><origin xyz="0 0 0.1"/><geometry><sphere radius="0.05"/></geometry></collision></link>
          <joint name="f" type="fixed"><parent link="a"/><child link="flange"/><origin xyz="0 0 0.1"/></joint>
          <joint name="j1" type="revolute"><parent link="flange"/><child link="b"/><axis xyz="1 0 0"/><limit lower="-1" upper="1"/></joint>
          <joint name="j2" type="revolute"><parent link="flange"/><child link="c"/><axis xyz="0 1 0"/><limit lower="-1" upper="1"/></joint>
        </robot>"#,
        "r.urdf",
    )
    .unwrap();
    let robot = spherized(&urdf, 1);
    let matrix = self_collision_matrix(
        &urdf,
        &robot,
        &SelfCollisionOptions::default().with_samples(200),
    )
    .unwrap();
    assert_eq!(matrix.pairs.len(), 3);
    assert_eq!(matrix.count(DisableReason::Adjacent), 3, "{matrix:?}");
    // With no samples, only the adjacent and default rules apply.
    let unsampled = self_collision_matrix(
        &urdf,
        &robot,
        &SelfCollisionOptions::default().with_samples(0),
    )
    .unwrap();
    assert_eq!(
        unsampled.count(DisableReason::Never) + unsampled.count(DisableReason::Always),
        0
    );
}

/// Posed link meshes, by link name.
fn posed_meshes(urdf: &Urdf, chain: &KinematicChain, q: &[f64]) -> BTreeMap<String, TriMesh> {
    let geometry = LinkGeometry::load_all(
        urdf,
        GeometrySource::Collision,
        &MeshResolver::new(urdf.folder()),
    )
    .expect("the meshes load");
    let poses = chain.poses(q).expect("poses");
    geometry
        .into_iter()
        .filter_map(|g| {
            let mesh = g.mesh?;
            let pose = poses[chain.link_index(&g.link)?];
            let (p, t) = mesh.into_parts();
            let moved = p.into_iter().map(|x| pose.transform_point3(x)).collect();
            Some((g.link, TriMesh::new(moved, t).expect("a mesh")))
        })
        .collect()
}

fn check_against_meshes(
    name: &str,
    urdf: &Urdf,
    matrix: &SelfCollisionMatrix,
    configurations: &[Vec<f64>],
) -> usize {
    assert!(
        matrix.count(DisableReason::Never) > 0,
        "{name}: some pairs never meet"
    );
    check_meshes(urdf, matrix, configurations)
}

/// How many pairs of posed link meshes parry finds in contact over `configurations`;
/// fails when one of them is a "Never" pair.
fn check_meshes(urdf: &Urdf, matrix: &SelfCollisionMatrix, configurations: &[Vec<f64>]) -> usize {
    let name = &urdf.name;
    let chain = KinematicChain::new(urdf).unwrap();
    let mut meshes_in_contact = 0;
    for q in configurations {
        let meshes = posed_meshes(urdf, &chain, q);
        for pair in &matrix.pairs {
            let (Some(a), Some(b)) = (meshes.get(&pair.first), meshes.get(&pair.second)) else {
                continue;
            };
            if sphaera_tests::regions::surfaces_meet(a, b) {
                meshes_in_contact += 1;
                assert_ne!(
                    pair.reason,
                    Some(DisableReason::Never),
                    "{name}: {} and {} meet at {q:?}",
                    pair.first,
                    pair.second
                );
            }
        }
    }
    meshes_in_contact
}

#[test]
fn real_robots_never_disable_a_pair_in_contact() {
    for (name, path) in sphaera_tests::robot_urdfs("real_robots_never_disable_a_pair_in_contact") {
        let urdf = Urdf::read(&path).expect("the URDF reads");
        let robot = spherized(&urdf, 12);
        let options = SelfCollisionOptions::default();
        let matrix = self_collision_matrix(&urdf, &robot, &options).expect("the matrix");
        // Every joint between two links with spheres gives an adjacent pair.
        for joint in &urdf.joints {
            if robot.link(&joint.parent).is_some() && robot.link(&joint.child).is_some() {
                let pair = matrix
                    .pairs
                    .iter()
                    .find(|p| {
                        (p.first == joint.parent && p.second == joint.child)
                            || (p.first == joint.child && p.second == joint.parent)
                    })
                    .expect("the pair");
                assert_eq!(
                    pair.reason,
                    Some(DisableReason::Adjacent),
                    "{name}: {}",
                    joint.name
                );
            }
        }
        let chain = KinematicChain::new(&urdf).unwrap();
        // The matrix's own configurations (its verdicts must hold there: the spheres cover
        // the links) and fresh ones.
        let own: Vec<Vec<f64>> = (0..40)
            .map(|i| chain.sample(options.seed, i * 250))
            .collect();
        let fresh: Vec<Vec<f64>> = (0..40).map(|i| chain.sample(99, i)).collect();
        let touching = check_against_meshes(name, &urdf, &matrix, &own)
            + check_against_meshes(name, &urdf, &matrix, &fresh);
        assert!(
            touching > 0,
            "{name}: the brute-force test found some contact"
        );
        // The same matrix with one thread.
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let single = pool
            .install(|| self_collision_matrix(&urdf, &robot, &options))
            .unwrap();
        assert_eq!(single.pairs, matrix.pairs, "{name}");
        // Every pair has one verdict.
        let counted: usize = DisableReason::ALL.iter().map(|&r| matrix.count(r)).sum();
        assert_eq!(
            counted + matrix.checked().count(),
            matrix.pairs.len(),
            "{name}"
        );
    }
}

/// A generated arm nobody tuned anything for: `links` box links (OBJ files in `dir`, each a
/// random size; every length times `factor`) in a chain with random joint origins, axes and limits, the last two links
/// siblings (a gripper's fingers).
fn random_arm(dir: &std::path::Path, seed: u64, links: usize, factor: f64) -> Urdf {
    let mut rng = sphaera_tests::SplitMix64::new(seed);
    let cube = sphaera_mesh::shapes::cube(1.0, 1).expect("a cube");
    let mut text = String::from("<robot name=\"random\">");
    for k in 0..links {
        let size = glam::DVec3::new(
            rng.range(0.03, 0.12),
            rng.range(0.03, 0.12),
            rng.range(0.1, 0.35),
        );
        let mut obj = String::new();
        for p in cube.positions() {
            let q = factor * (*p * size + glam::DVec3::new(0.0, 0.0, 0.5 * size.z));
            obj += &format!("v {} {} {}\n", q.x, q.y, q.z);
        }
        for t in cube.triangles() {
            obj += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
        }
        std::fs::write(dir.join(format!("l{k}.obj")), obj).expect("write a link mesh");
        text += &format!(
            "<link name=\"l{k}\"><collision><geometry><mesh filename=\"l{k}.obj\"/></geometry></collision></link>"
        );
    }
    for k in 1..links {
        let parent = if k == links - 1 { k - 2 } else { k - 1 };
        let axis = ["1 0 0", "0 1 0", "0 0 1"][rng.below(3) as usize];
        let lower = -rng.range(0.5, 2.5);
        let upper = rng.range(0.5, 2.5);
        text += &format!(
            "<joint name=\"j{k}\" type=\"revolute\"><parent link=\"l{parent}\"/><child link=\"l{k}\"/><origin xyz=\"{} 0 {}\" rpy=\"{} {} 0\"/><axis xyz=\"{axis}\"/><limit lower=\"{lower}\" upper=\"{upper}\"/></joint>",
            factor * rng.range(-0.03, 0.03),
            factor * rng.range(0.1, 0.3),
            rng.range(-0.4, 0.4),
            rng.range(-0.4, 0.4),
        );
    }
    text += "</robot>";
    let path = dir.join("random.urdf");
    std::fs::write(&path, &text).expect("write the URDF");
    Urdf::read(&path).expect("the generated arm reads")
}

/// On arms nobody has seen: every adjacent pair left out, and no "Never" pair whose posed
/// meshes parry finds in contact at the matrix's own configurations.
#[test]
fn generated_arms_never_disable_a_pair_in_contact() {
    let mut contacts = 0;
    for seed in 0..4 {
        let dir = tempfile::tempdir().expect("a folder");
        let urdf = random_arm(dir.path(), seed, 5 + seed as usize, 1.0);
        let robot = spherized(&urdf, 6);
        let options = SelfCollisionOptions::default()
            .with_samples(2_000)
            .with_seed(seed);
        let matrix = self_collision_matrix(&urdf, &robot, &options).expect("the matrix");
        for joint in &urdf.joints {
            assert!(
                matrix.is_disabled(&joint.parent, &joint.child),
                "seed {seed}: {}",
                joint.name
            );
        }
        let chain = KinematicChain::new(&urdf).unwrap();
        let own: Vec<Vec<f64>> = (0..30).map(|i| chain.sample(seed, i * 60)).collect();
        contacts += check_meshes(&urdf, &matrix, &own);
    }
    assert!(contacts > 0, "the brute-force test found some contact");
}

/// The same arm at twice the size (a power of two: every length exactly doubled) gets the
/// same verdict and the same contact count on every pair, and spheres exactly doubled.
#[test]
fn a_robot_twice_the_size_gets_the_same_matrix() {
    let (small_dir, large_dir) = (
        tempfile::tempdir().expect("a folder"),
        tempfile::tempdir().expect("a folder"),
    );
    let small = random_arm(small_dir.path(), 11, 6, 1.0);
    let large = random_arm(large_dir.path(), 11, 6, 2.0);
    let (a, b) = (spherized(&small, 5), spherized(&large, 5));
    for (x, y) in a.links.iter().zip(&b.links) {
        for (s, t) in x.spheres.iter().zip(&y.spheres) {
            assert_eq!(
                (2.0 * s.center, 2.0 * s.radius),
                (t.center, t.radius),
                "{}",
                x.link
            );
        }
    }
    let options = SelfCollisionOptions::default().with_samples(3_000);
    let (m, n) = (
        self_collision_matrix(&small, &a, &options).unwrap(),
        self_collision_matrix(&large, &b, &options).unwrap(),
    );
    assert_eq!(m.pairs, n.pairs);
}
