//! Properties against brute force: primitives covered and their protrusion exact for any
//! size, pose and count; mesh links at random origins and scales covered where this test
//! places them, their protrusion certified; forward kinematics against a hand-composed
//! chain; awkward meshes as links; powers of two; the same spheres with and without
//! `parallel` (a recorded digest).

#![allow(clippy::float_cmp)]

use glam::{DAffine3, DQuat, DVec3};
use proptest::prelude::*;
use sphaera_robot::{
    GeometrySource, LinkGeometry, MeshResolver, Primitive, RobotError, Shape, SphereBudget,
    SpherizeOptions, Urdf, spherize, spherize_geometry,
};

fn shape(kind: usize, a: f64, b: f64, c: f64) -> Shape {
    match kind {
        0 => Shape::Box {
            half: DVec3::new(a, b, c),
        },
        1 => Shape::Cylinder {
            radius: a,
            half_length: b,
        },
        2 => Shape::Sphere { radius: a },
        _ => Shape::Capsule {
            radius: a,
            half_length: b,
        },
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(96)))]

    /// Dense surface points are covered, and no point on any sphere lies farther from the
    /// primitive than the reported protrusion (the brute-force maximum over the spheres'
    /// surfaces comes within 10 % of it).
    #[test]
    fn primitives_are_covered_with_their_exact_protrusion(
        kind in 0usize..4,
        a in 0.01..1.0f64,
        b in 0.01..1.0f64,
        c in 0.01..1.0f64,
        count in 1usize..60,
        angles in prop::array::uniform3(-3.0..3.0f64),
        t in prop::array::uniform3(-2.0..2.0f64),
    ) {
        let pose = DAffine3::from_rotation_translation(
            DQuat::from_euler(glam::EulerRot::XYZ, angles[0], angles[1], angles[2]),
            DVec3::from_array(t),
        );
        let primitive = Primitive::new(shape(kind, a, b, c), pose);
        let (spheres, protrusion) = primitive.spherize(count);
        prop_assert!(!spheres.is_empty() && spheres.len() <= count);
        for p in primitive.surface_points(1500) {
            prop_assert!(
                spheres.iter().any(|s| s.center.distance(p) <= s.radius * (1.0 + 1e-12) + 1e-15),
                "{p} uncovered"
            );
        }
        let unit = Primitive::new(Shape::Sphere { radius: 1.0 }, DAffine3::IDENTITY).surface_points(300);
        let mut measured: f64 = 0.0;
        for s in &spheres {
            for &u in &unit {
                measured = measured.max(primitive.signed_distance(s.center + u * s.radius));
            }
        }
        let scale = a.max(b).max(c);
        prop_assert!(measured <= protrusion + 1e-12 * scale, "{measured} > {protrusion}");
        prop_assert!(measured >= 0.9 * protrusion - 1e-9 * scale, "{measured} ≪ {protrusion}");
    }

    /// A total budget is divided exactly, at least one each; fewer spheres than links are
    /// refused.
    #[test]
    fn a_total_is_divided_exactly(
        sizes in prop::collection::vec(0.01..1.0f64, 1..8),
        total in 1usize..200,
    ) {
        let mut text = String::from("<robot name=\"r\">");
        for (i, s) in sizes.iter().enumerate() {
            text.push_str(&format!(
                "<link name=\"l{i}\"><collision><geometry><sphere radius=\"{s}\"/></geometry></collision></link>"
            ));
            // One tree: every link hangs from the first.
            if i > 0 {
                text.push_str(&format!(
                    "<joint name=\"j{i}\" type=\"fixed\"><parent link=\"l0\"/><child link=\"l{i}\"/></joint>"
                ));
            }
        }
        text.push_str("</robot>");
        let geometry: Vec<LinkGeometry> = Urdf::parse(&text, "r.urdf")
            .expect("parse")
            .links
            .iter()
            .map(|l| LinkGeometry::load(l, GeometrySource::Collision, &MeshResolver::new("")).expect("load"))
            .collect();
        let options = SpherizeOptions::default().with_budget(SphereBudget::Total(total));
        let result = spherize_geometry("r", geometry, &options, &|_| {});
        if total < sizes.len() {
            // Fewer spheres than links: refused, never exceeded.
            let error = result.expect_err("too few");
            prop_assert!(matches!(error, RobotError::Budget { .. }), "{error}");
            return Ok(());
        }
        let robot = result.expect("spherize");
        let budgets: Vec<usize> = robot.links.iter().filter_map(|l| l.report.budget).collect();
        prop_assert!(budgets.iter().all(|&b| b >= 1));
        prop_assert_eq!(budgets.iter().sum::<usize>(), total);
        // Ball links use one sphere each and say why when given more (no ball link takes
        // what another leaves: it could not use it either).
        for link in &robot.links {
            prop_assert_eq!(link.spheres.len(), 1);
            prop_assert_eq!(link.report.shortfall.is_some(), link.report.budget > Some(1));
        }
        // Bigger links never get fewer spheres (balls: their spherization is instant, the
        // division is what is tested).
        for i in 0..sizes.len() {
            for j in 0..sizes.len() {
                if sizes[i] > sizes[j] * 1.01 {
                    prop_assert!(budgets[i] + 1 >= budgets[j], "{sizes:?} {budgets:?}");
                }
            }
        }
    }
}

/// Forward kinematics against the chain composed by hand.
#[test]
fn forward_kinematics_composes_origins_and_motions() {
    let text = r#"<robot name="r">
      <link name="a"/><link name="b"/><link name="c"/><link name="d"/>
      <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
        <origin xyz="0.1 0.2 0.3" rpy="0.2 -0.4 0.6"/><axis xyz="0 1 1"/></joint>
      <joint name="j2" type="prismatic"><parent link="b"/><child link="c"/>
        <origin xyz="0 0 0.5"/><axis xyz="1 0 0"/></joint>
      <joint name="j3" type="continuous"><parent link="c"/><child link="d"/>
        <axis xyz="0 0 1"/><mimic joint="j1" multiplier="2" offset="0.1"/></joint>
    </robot>"#;
    let urdf = Urdf::parse(text, "r.urdf").expect("parse");
    let q = std::collections::BTreeMap::from([("j1".to_owned(), 0.7), ("j2".to_owned(), 0.25)]);
    let poses = urdf.link_poses(&q).expect("poses");
    let rpy = DQuat::from_euler(glam::EulerRot::ZYX, 0.6, -0.4, 0.2);
    let b = DAffine3::from_rotation_translation(rpy, DVec3::new(0.1, 0.2, 0.3))
        * DAffine3::from_quat(DQuat::from_axis_angle(
            DVec3::new(0.0, 1.0, 1.0).normalize(),
            0.7,
        ));
    let c = b
        * DAffine3::from_translation(DVec3::new(0.0, 0.0, 0.5))
        * DAffine3::from_translation(DVec3::new(0.25, 0.0, 0.0));
    let d = c * DAffine3::from_quat(DQuat::from_rotation_z(2.0 * 0.7 + 0.1));
    for (name, expected) in [("b", b), ("c", c), ("d", d)] {
        assert!(poses[name].abs_diff_eq(expected, 1e-12), "{name}");
    }
    let error = urdf
        .link_poses(&std::collections::BTreeMap::from([("j9".to_owned(), 0.0)]))
        .expect_err("unknown");
    assert!(matches!(error, RobotError::Joint { .. }));
    let error = urdf
        .link_poses(&std::collections::BTreeMap::from([(
            "j1".to_owned(),
            f64::NAN,
        )]))
        .expect_err("NaN");
    assert!(error.to_string().contains("not finite"));
}

fn mesh_link(mesh: sphaera_mesh::TriMesh) -> LinkGeometry {
    LinkGeometry {
        link: "part".to_owned(),
        mesh: Some(mesh),
        files: Vec::new(),
        primitives: Vec::new(),
    }
}

/// Every awkward mesh (pinched vertices, tiny components, slivers, far-apart parts,
/// spikes) as a link: spherized with coverage certified (each is closed with area, which
/// the minimax trees take), never a panic.
#[test]
fn awkward_meshes_as_links() {
    let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(12));
    let all = sphaera_tests::awkward::all();
    for awkward in &all {
        let robot = spherize_geometry(
            "r",
            vec![mesh_link(awkward.mesh.clone())],
            &options,
            &|_| {},
        )
        .unwrap_or_else(|error| panic!("{}: {error}", awkward.name));
        let link = &robot.links[0];
        assert!(link.report.coverage_certified, "{}", awkward.name);
        assert_eq!(link.report.coverage, 1.0, "{}", awkward.name);
        assert!(link.report.worst_protrusion.is_finite());
        assert!(
            !link.spheres.is_empty() && link.spheres.len() <= 12,
            "{}",
            awkward.name
        );
        for &p in awkward.mesh.positions() {
            assert!(
                link.spheres
                    .iter()
                    .any(|s| s.center.distance(p) <= s.radius * (1.0 + 1e-9)),
                "{}: vertex {p} uncovered",
                awkward.name
            );
        }
    }
    assert!(all.len() >= 7);
    // A link of no area is an error naming it, not spheres of nothing.
    let flat = sphaera_mesh::TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)],
        vec![[0, 1, 2]],
    )
    .expect("a degenerate triangle is a mesh");
    let error =
        spherize_geometry("r", vec![mesh_link(flat)], &options, &|_| {}).expect_err("no area");
    assert!(error.to_string().contains("\"part\""), "{error}");
}

/// A mesh scaled by a power of two gives the same spheres, scaled exactly.
#[test]
fn powers_of_two_scale_the_spheres_exactly() {
    let mesh = sphaera_mesh::shapes::torus(0.2, 0.06, 20).expect("torus");
    let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(10));
    let base =
        spherize_geometry("r", vec![mesh_link(mesh.clone())], &options, &|_| {}).expect("base");
    for exponent in [-20, 3, 30] {
        let k = 2f64.powi(exponent);
        let scaled_mesh = sphaera_mesh::TriMesh::new(
            mesh.positions().iter().map(|p| *p * k).collect(),
            mesh.triangles().to_vec(),
        )
        .expect("scaled");
        let scaled = spherize_geometry("r", vec![mesh_link(scaled_mesh)], &options, &|_| {})
            .expect("scaled");
        let (a, b) = (&base.links[0], &scaled.links[0]);
        assert_eq!(a.spheres.len(), b.spheres.len(), "2^{exponent}");
        for (s, t) in a.spheres.iter().zip(&b.spheres) {
            assert_eq!(s.center * k, t.center, "2^{exponent}");
            assert_eq!(s.radius * k, t.radius, "2^{exponent}");
        }
    }
}

/// The spheres of a small robot (a mesh link and primitives) are the same run after run
/// and with or without `parallel` (`cargo xtask test` runs this crate both ways).
#[test]
fn the_same_spheres_with_and_without_parallel() {
    let dir = tempfile::tempdir().expect("a folder");
    let mesh = sphaera_mesh::shapes::capsule(0.04, 0.2, 12).expect("capsule");
    sphaera_io::save(dir.path().join("arm.obj"), &mesh).expect("save");
    let text = r#"<robot name="r">
      <link name="base"><collision><geometry><box size="0.3 0.2 0.1"/></geometry></collision>
        <collision><origin xyz="0 0 0.1"/><geometry><cylinder radius="0.05" length="0.1"/></geometry></collision></link>
      <link name="arm"><collision><origin rpy="0 1.5707963 0"/><geometry><mesh filename="arm.obj"/></geometry></collision></link>
      <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.2"/><axis xyz="0 0 1"/></joint>
    </robot>"#;
    let path = dir.path().join("r.urdf");
    std::fs::write(&path, text).expect("write");
    let urdf = Urdf::read(&path).expect("read");
    let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(9));
    let robot = spherize(&urdf, &MeshResolver::new(urdf.folder()), &options).expect("spherize");
    let mut digest: u64 = 0xcbf2_9ce4_8422_2325;
    for link in &robot.links {
        for s in &link.spheres {
            for x in [s.center.x, s.center.y, s.center.z, s.radius] {
                digest ^= x.to_bits();
                digest = digest.wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
    assert_eq!(robot.sphere_count(), RECORDED_COUNT);
    assert_eq!(digest, RECORDED_DIGEST, "digest {digest:#x}");
}

const RECORDED_COUNT: usize = 16;
const RECORDED_DIGEST: u64 = 0xd457_a293_7e6b_cb6f;

/// An OBJ of `mesh`'s vertices and triangles.
fn obj_text(mesh: &sphaera_mesh::TriMesh) -> String {
    let mut text = String::new();
    for p in mesh.positions() {
        text.push_str(&format!("v {:?} {:?} {:?}\n", p.x, p.y, p.z));
    }
    for t in mesh.triangles() {
        text.push_str(&format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1));
    }
    text
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(24)))]

    /// A mesh link at a random origin (`xyz`, `rpy`) with a random per-axis scale (a
    /// mirror included): its spheres cover the mesh placed by this test's own
    /// composition (`translation · Rz(yaw) · Ry(pitch) · Rx(roll) · diag(scale)`) at its
    /// vertices and at random points of its triangles, and no point sampled on the
    /// spheres lies farther outside the placed mesh than the certified worst protrusion.
    #[test]
    fn mesh_links_at_random_origins_and_scales_are_covered(
        kind in 0usize..3,
        xyz in prop::array::uniform3(-1.0..1.0f64),
        rpy in prop::array::uniform3(-3.1..3.1f64),
        scale in prop::array::uniform3(0.3..3.0f64),
        mirror in any::<bool>(),
        seed in any::<u64>(),
    ) {
        let mesh = match kind {
            0 => sphaera_mesh::shapes::torus(0.2, 0.07, 12),
            1 => sphaera_mesh::shapes::l_block(0.3, 0.1, 0.1, 2),
            _ => sphaera_mesh::shapes::capsule(0.05, 0.25, 10),
        }
        .expect("shape");
        let scale = DVec3::from_array(scale) * DVec3::new(if mirror { -1.0 } else { 1.0 }, 1.0, 1.0);
        let dir = tempfile::tempdir().expect("a folder");
        std::fs::write(dir.path().join("part.obj"), obj_text(&mesh)).expect("write the mesh");
        let text = format!(
            r#"<robot name="r"><link name="l"><collision>
                 <origin xyz="{:?} {:?} {:?}" rpy="{:?} {:?} {:?}"/>
                 <geometry><mesh filename="part.obj" scale="{:?} {:?} {:?}"/></geometry>
               </collision></link></robot>"#,
            xyz[0], xyz[1], xyz[2], rpy[0], rpy[1], rpy[2], scale.x, scale.y, scale.z
        );
        let path = dir.path().join("r.urdf");
        std::fs::write(&path, text).expect("write the URDF");
        let urdf = Urdf::read(&path).expect("read");
        let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(8));
        let robot = spherize(&urdf, &MeshResolver::new(urdf.folder()), &options).expect("spherize");
        let link = &robot.links[0];
        prop_assert!(link.report.coverage_certified);

        // The placement, composed here from the URDF's conventions.
        let rotation = DQuat::from_rotation_z(rpy[2])
            * DQuat::from_rotation_y(rpy[1])
            * DQuat::from_rotation_x(rpy[0]);
        let place = |p: DVec3| DVec3::from_array(xyz) + rotation * (p * scale);
        let mut points: Vec<DVec3> = mesh.positions().iter().map(|&p| place(p)).collect();
        let mut rng = sphaera_tests::random::SplitMix64::new(seed);
        for t in mesh.triangles() {
            let [a, b, c] = t.map(|i| mesh.positions()[i as usize]);
            for _ in 0..4 {
                let (mut u, mut v) = (rng.unit_by_max(), rng.unit_by_max());
                if u + v > 1.0 {
                    (u, v) = (1.0 - u, 1.0 - v);
                }
                points.push(place(a + (b - a) * u + (c - a) * v));
            }
        }
        let size = link.report.diagonal;
        for p in &points {
            prop_assert!(
                link.spheres.iter().any(|s| s.center.distance(*p) <= s.radius + 1e-9 * size),
                "{p} uncovered"
            );
        }

        // Protrusion: points on the spheres, outside the placed mesh, are no farther from
        // it than the certified worst.
        let placed = sphaera_mesh::TriMesh::new(
            mesh.positions().iter().map(|&p| place(p)).collect(),
            mesh.triangles()
                .iter()
                .map(|&[a, b, c]| if mirror { [a, c, b] } else { [a, b, c] })
                .collect(),
        )
        .expect("placed");
        let surface = sphaera_query::Surface::new(&placed).expect("surface");
        let unit = Primitive::new(Shape::Sphere { radius: 1.0 }, DAffine3::IDENTITY).surface_points(200);
        let mut measured: f64 = 0.0;
        for s in &link.spheres {
            for &u in &unit {
                let q = s.center + u * s.radius;
                if !surface.is_inside(q) {
                    measured = measured.max(surface.closest(q).expect("closest").distance);
                }
            }
        }
        prop_assert!(
            measured <= link.report.worst_protrusion + 1e-9 * size,
            "measured {measured} > certified {}",
            link.report.worst_protrusion
        );
    }
}
