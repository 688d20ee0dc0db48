//! Budgets honoured and tolerances met, checked by brute force independently of the
//! crates under test: every count from 1 to 64 gives exactly that many spheres on a
//! Franka Panda link (a spread of counts on two more), their surface covered (points
//! sampled here, each inside some sphere) and their reported worst protrusion never
//! below the protrusion measured on points of every sphere (distances to every triangle,
//! the inside by a solid-angle winding number); a total is divided exactly; a tolerance
//! is met or refused; sheets, primitives and more parts than spheres; bad inputs give
//! clear errors.

#![allow(clippy::float_cmp)]

use std::path::PathBuf;

use glam::{DAffine3, DVec3};
use sphaera_mesh::TriMesh;
use sphaera_robot::{
    GeometrySource, Length, LinkGeometry, LinkSpheres, MeshResolver, Primitive, RobotError, Shape,
    Sphere, SphereBudget, SpherizeOptions, Urdf, spherize, spherize_geometry,
};
use sphaera_tests::{SplitMix64, brute};

/// The Panda's collision mesh `name` (`link1`, `hand`, ...), or `None` (the test skips)
/// without the shared data.
fn panda_mesh(name: &str, test: &str) -> Option<TriMesh> {
    let data = sphaera_tests::data_dir(test)?;
    let path = data
        .join("robots/franka_panda/collision")
        .join(format!("{name}.obj"));
    Some(sphaera_io::load(&path).expect("the Panda's mesh loads"))
}

fn panda_urdf(test: &str) -> Option<PathBuf> {
    let data = sphaera_tests::data_dir(test)?;
    Some(
        data.join(sphaera_tests::URDF_ASSETS)
            .join("franka_panda/panda.urdf"),
    )
}

fn mesh_link(name: &str, mesh: TriMesh) -> LinkGeometry {
    LinkGeometry {
        link: name.to_owned(),
        mesh: Some(mesh),
        files: Vec::new(),
        primitives: Vec::new(),
    }
}

fn one_link(link: LinkGeometry, options: &SpherizeOptions) -> LinkSpheres {
    let name = link.link.clone();
    let mut robot = spherize_geometry("r", vec![link], options, &|_| {})
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    robot.links.remove(0)
}

/// The winding number of `mesh` at `p`: the triangles' solid angles (Van Oosterom and
/// Strackee) over 4π.
fn winding_number(mesh: &TriMesh, p: DVec3) -> f64 {
    let mut total = 0.0;
    for t in mesh.triangle_iter() {
        let (a, b, c) = (t.a - p, t.b - p, t.c - p);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let numerator = a.dot(b.cross(c));
        let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        total += 2.0 * numerator.atan2(denominator);
    }
    total / (4.0 * std::f64::consts::PI)
}

/// Points on `mesh`'s surface: every vertex, every edge midpoint, and `count` points
/// drawn by area (a triangle by its share of the area, a point uniformly in it).
fn surface_points(mesh: &TriMesh, count: usize, seed: u64) -> Vec<DVec3> {
    let triangles: Vec<_> = mesh.triangle_iter().collect();
    let mut points: Vec<DVec3> = mesh.positions().to_vec();
    for t in &triangles {
        points.extend([0.5 * (t.a + t.b), 0.5 * (t.b + t.c), 0.5 * (t.c + t.a)]);
    }
    let mut cumulative = Vec::with_capacity(triangles.len());
    let mut sum = 0.0;
    for t in &triangles {
        sum += 0.5 * (t.b - t.a).cross(t.c - t.a).length();
        cumulative.push(sum);
    }
    let mut random = SplitMix64::new(seed);
    for _ in 0..count {
        let pick = random.unit() * sum;
        let i = cumulative
            .partition_point(|&c| c < pick)
            .min(triangles.len() - 1);
        let t = &triangles[i];
        let (r1, r2) = (random.unit().sqrt(), random.unit());
        points.push((1.0 - r1) * t.a + r1 * (1.0 - r2) * t.b + r1 * r2 * t.c);
    }
    points
}

/// `n` directions spread over the unit sphere (a Fibonacci lattice).
fn directions(n: usize) -> Vec<DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let ring = (1.0 - z * z).sqrt();
            let angle = golden * i as f64;
            DVec3::new(ring * angle.cos(), ring * angle.sin(), z)
        })
        .collect()
}

fn inside_some(spheres: &[Sphere], p: DVec3) -> bool {
    spheres
        .iter()
        .any(|s| s.center.distance(p) <= s.radius * (1.0 + 1e-9) + 1e-12)
}

/// The largest distance beyond the object (0 inside a solid) over points spread on
/// every sphere: a lower bound on the true worst protrusion, by brute force.
fn measured_protrusion(mesh: &TriMesh, solid: bool, spheres: &[Sphere]) -> f64 {
    let unit = directions(160);
    let mut worst: f64 = 0.0;
    for s in spheres {
        for &u in &unit {
            let p = s.center + s.radius * u;
            let d = brute::distance(mesh, p);
            // Points far closer than the worst so far cannot raise it: skip the
            // winding number there.
            if d <= worst {
                continue;
            }
            if !(solid && winding_number(mesh, p) > 0.5) {
                worst = d;
            }
        }
    }
    worst
}

/// The brute-force checks of one link's spheres: every sampled surface point covered,
/// the reported worst protrusion at least the measured one (and not far above it).
/// Returns the measured protrusion.
fn check_link(mesh: &TriMesh, link: &LinkSpheres, what: &str) -> f64 {
    let r = &link.report;
    for p in surface_points(mesh, 4_000, 17) {
        assert!(inside_some(&link.spheres, p), "{what}: {p} uncovered");
    }
    assert_eq!(r.coverage, 1.0, "{what}");
    assert!(r.coverage_certified, "{what}");
    let measured = measured_protrusion(mesh, !r.shell, &link.spheres);
    let slack = 1e-9 * r.diagonal;
    assert!(
        measured <= r.worst_protrusion + slack,
        "{what}: measured {measured} above the certified {}",
        r.worst_protrusion
    );
    // Sampled points on the spheres come within a few per cent of the worst point.
    assert!(
        measured >= 0.9 * r.worst_protrusion - 1e-3 * r.diagonal,
        "{what}: the certified {} is far above the measured {measured}",
        r.worst_protrusion
    );
    measured
}

/// Every count from 1 to 64 on the Panda's first link, a spread of counts on its hand
/// and on link 6 (34 components, open): exactly that many spheres, covering, the
/// protrusion certified, and more spheres never much looser than fewer.
#[test]
fn every_count_gives_exactly_that_many_spheres_on_panda_links() {
    let spread = [1, 2, 3, 5, 8, 13, 21, 34, 47, 64];
    for (name, counts) in [
        ("link1", (1..=64).collect::<Vec<usize>>()),
        ("hand", spread.to_vec()),
        ("link6", spread.to_vec()),
    ] {
        let Some(mesh) = panda_mesh(name, "every_count_gives_exactly") else {
            return;
        };
        let mut worst: Vec<(usize, f64)> = Vec::new();
        for &n in &counts {
            let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(n));
            let link = one_link(mesh_link(name, mesh.clone()), &options);
            let what = format!("{name} at {n}");
            assert_eq!(link.spheres.len(), n, "{what}");
            assert_eq!(link.report.spheres, n, "{what}");
            assert_eq!(link.report.budget, Some(n), "{what}");
            assert_eq!(link.report.shortfall, None, "{what}");
            check_link(&mesh, &link, &what);
            worst.push((n, link.report.worst_protrusion));
        }
        // Decreasing, give or take: never looser than any smaller count by more than
        // 10 %, and a doubling always tighter.
        for (i, &(n, w)) in worst.iter().enumerate() {
            let best_before = worst[..i].iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
            assert!(
                w <= 1.1 * best_before,
                "{name}: {n} spheres reach {w}, fewer reached {best_before}"
            );
            if let Some(&(_, half)) = worst.iter().find(|p| 2 * p.0 == n) {
                assert!(
                    w < half,
                    "{name}: {n} spheres reach {w}, half as many {half}"
                );
            }
        }
        let (first, last) = (worst[0].1, worst[worst.len() - 1].1);
        assert!(last < 0.2 * first, "{name}: {first} → {last}");
    }
}

/// A total is divided among the Panda's eleven links exactly (a per-link count taken
/// out first); fewer spheres than links is refused.
#[test]
fn a_total_budget_sums_exactly() {
    let Some(path) = panda_urdf("a_total_budget_sums_exactly") else {
        return;
    };
    let urdf = Urdf::read(&path).expect("the URDF reads");
    let resolver = MeshResolver::new(urdf.folder());
    for (total, hand) in [(11, None), (60, None), (60, Some(20))] {
        let mut options = SpherizeOptions::default().with_budget(SphereBudget::Total(total));
        if let Some(hand) = hand {
            options = options.with_link("panda_hand", hand);
        }
        let robot = spherize(&urdf, &resolver, &options).expect("spherize");
        let budgets: Vec<usize> = robot.links.iter().filter_map(|l| l.report.budget).collect();
        assert_eq!(budgets.len(), 11);
        assert_eq!(budgets.iter().sum::<usize>(), total, "{budgets:?}");
        assert_eq!(robot.sphere_count(), total);
        for link in &robot.links {
            assert_eq!(
                Some(link.spheres.len()),
                link.report.budget,
                "{}",
                link.link
            );
            assert!(!link.spheres.is_empty() && link.report.shortfall.is_none());
            assert_eq!(link.report.coverage, 1.0);
        }
        if let Some(hand) = hand {
            assert_eq!(
                robot.link("panda_hand").map(|l| l.spheres.len()),
                Some(hand)
            );
        }
        // The big arm links get more than the 32-triangle fingers.
        let of = |name: &str| robot.link(name).map_or(0, |l| l.spheres.len());
        if total > 11 {
            assert!(of("panda_link1") > of("panda_leftfinger"), "{budgets:?}");
        }
    }
    for (options, needle) in [
        (
            SpherizeOptions::default().with_budget(SphereBudget::Total(10)),
            "cannot give each of the 11 links with geometry one",
        ),
        (
            SpherizeOptions::default()
                .with_budget(SphereBudget::Total(20))
                .with_link("panda_hand", 15),
            "the per-link counts take 15",
        ),
    ] {
        let error = spherize(&urdf, &resolver, &options).expect_err("too few");
        assert!(
            matches!(error, RobotError::Budget { .. }) && error.to_string().contains(needle),
            "{error}"
        );
    }
}

/// A tolerance, relative or absolute, is met by every link of the Panda (the report
/// and a brute-force check on two links agree), or refused when it needs more spheres
/// than allowed.
#[test]
fn a_tolerance_is_met_on_every_link_or_refused() {
    let Some(path) = panda_urdf("a_tolerance_is_met") else {
        return;
    };
    let urdf = Urdf::read(&path).expect("the URDF reads");
    let resolver = MeshResolver::new(urdf.folder());
    let geometry = LinkGeometry::load_all(&urdf, GeometrySource::Collision, &resolver)
        .expect("the geometry loads");
    for tolerance in [Length::RelativeToDiagonal(0.05), Length::Absolute(0.012)] {
        let options = SpherizeOptions::default().with_budget(SphereBudget::Tolerance(tolerance));
        let robot =
            spherize_geometry("panda", geometry.clone(), &options, &|_| {}).expect("spherize");
        assert_eq!(robot.links.len(), 11);
        for link in &robot.links {
            let r = &link.report;
            let t = tolerance.resolve(r.diagonal);
            assert_eq!(r.tolerance, Some(t));
            assert_eq!(r.meets_tolerance, Some(true), "{}", r.link);
            assert!(
                r.worst_protrusion <= t,
                "{}: {} > {t}",
                r.link,
                r.worst_protrusion
            );
            assert_eq!((r.budget, r.spheres), (None, link.spheres.len()));
            if ["panda_link1", "panda_hand", "panda_link6"].contains(&r.link.as_str()) {
                let mesh = geometry
                    .iter()
                    .find(|g| g.link == r.link)
                    .and_then(|g| g.mesh.clone())
                    .expect("a mesh");
                let measured = check_link(&mesh, link, &r.link);
                assert!(measured <= t, "{}: measured {measured} > {t}", r.link);
            }
        }
    }
    // Five spheres cannot keep the first link within 2 %.
    let link1 = geometry
        .iter()
        .find(|g| g.link == "panda_link1")
        .cloned()
        .expect("link1");
    let options = SpherizeOptions::default()
        .with_budget(SphereBudget::Tolerance(Length::RelativeToDiagonal(0.02)))
        .with_max_spheres_per_link(5);
    let error = spherize_geometry("panda", vec![link1], &options, &|_| {}).expect_err("too few");
    let message = error.to_string();
    assert!(
        matches!(error, RobotError::ToleranceUnreachable { max: 5, .. })
            && message.contains("panda_link1")
            && message.contains("within 5 spheres"),
        "{message}"
    );
}

/// A flat sheet has no inside: it is spherized as a shell, every point of a sphere
/// counting towards the protrusion, with exactly the spheres asked for or within a
/// tolerance.
#[test]
fn sheets_are_spherized_as_shells() {
    let sheet = sphaera_mesh::shapes::square_sheet(0.4, 6).expect("sheet");
    for n in [1, 4, 9, 20] {
        let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(n));
        let link = one_link(mesh_link("plate", sheet.clone()), &options);
        assert!(link.report.shell);
        assert_eq!(link.spheres.len(), n);
        check_link(&sheet, &link, &format!("sheet at {n}"));
    }
    let options =
        SpherizeOptions::default().with_budget(SphereBudget::Tolerance(Length::Absolute(0.03)));
    let link = one_link(mesh_link("plate", sheet.clone()), &options);
    assert!(link.report.worst_protrusion <= 0.03);
    assert!(check_link(&sheet, &link, "sheet within 0.03") <= 0.03);
}

/// Primitives: a sphere is its own sphere (the rest of the count unused, and the report
/// says why; beside a mesh, the mesh takes them), more parts than spheres share them,
/// and a box or cylinder gets exactly its count or says why not.
#[test]
fn primitives_use_what_they_can_and_say_why_not() {
    let ball = Primitive::new(Shape::Sphere { radius: 0.1 }, DAffine3::IDENTITY);
    let link = |mesh: Option<TriMesh>, primitives: Vec<Primitive>| LinkGeometry {
        link: "l".to_owned(),
        mesh,
        files: Vec::new(),
        primitives,
    };
    let count = |n| SpherizeOptions::default().with_budget(SphereBudget::PerLink(n));
    let alone = one_link(link(None, vec![ball]), &count(8));
    assert_eq!(alone.spheres.len(), 1);
    assert_eq!(alone.report.worst_protrusion, 0.0);
    let why = alone.report.shortfall.as_deref().expect("a reason");
    assert_eq!(why, "a sphere primitive is its own sphere");

    // Beside a mesh the ball's unused share goes to the mesh: 8 in all.
    let rod = sphaera_mesh::shapes::capsule(0.03, 0.3, 10).expect("capsule");
    let moved = Primitive::new(
        Shape::Sphere { radius: 0.05 },
        DAffine3::from_translation(DVec3::new(0.0, 0.0, 0.4)),
    );
    let both = one_link(link(Some(rod.clone()), vec![moved]), &count(8));
    assert_eq!(both.spheres.len(), 8);
    assert_eq!(both.report.shortfall, None);

    // Four parts, two spheres: the parts share them, every part covered, the protrusion
    // bound holding on points of the spheres.
    let parts = vec![
        Primitive::new(
            Shape::Box {
                half: DVec3::new(0.05, 0.04, 0.03),
            },
            DAffine3::from_translation(DVec3::new(0.3, 0.0, 0.0)),
        ),
        Primitive::new(
            Shape::Cylinder {
                radius: 0.02,
                half_length: 0.06,
            },
            DAffine3::from_translation(DVec3::new(0.35, 0.1, 0.0)),
        ),
        moved,
    ];
    let shared = one_link(link(Some(rod.clone()), parts.clone()), &count(2));
    assert_eq!(shared.spheres.len(), 2);
    for primitive in &parts {
        for p in primitive.surface_points(800) {
            assert!(inside_some(&shared.spheres, p), "{p} uncovered");
        }
    }
    for p in surface_points(&rod, 2_000, 3) {
        assert!(inside_some(&shared.spheres, p), "{p} uncovered");
    }
    let unit = directions(400);
    for s in &shared.spheres {
        for &u in &unit {
            let p = s.center + s.radius * u;
            let mut d = brute::distance(&rod, p);
            if winding_number(&rod, p) > 0.5 {
                d = 0.0;
            }
            for primitive in &parts {
                d = d.min(primitive.signed_distance(p).max(0.0));
            }
            assert!(d <= shared.report.worst_protrusion + 1e-12, "{d}");
        }
    }

    // A total: what the ball cannot use goes to the links that can, so the robot has
    // exactly the total, and the budgets sum to it.
    let named = |name: &str, mut geometry: LinkGeometry| {
        geometry.link = name.to_owned();
        geometry
    };
    let robot = spherize_geometry(
        "r",
        vec![
            named("ball", link(None, vec![ball])),
            named("rod", link(Some(rod.clone()), Vec::new())),
            named("plate", link(None, vec![parts[0]])),
        ],
        &SpherizeOptions::default().with_budget(SphereBudget::Total(30)),
        &|_| {},
    )
    .expect("spherize");
    assert_eq!(robot.sphere_count(), 30);
    let budgets: Vec<Option<usize>> = robot.links.iter().map(|l| l.report.budget).collect();
    assert_eq!(budgets.iter().flatten().sum::<usize>(), 30, "{budgets:?}");
    let ball = &robot.links[0].report;
    assert_eq!((ball.spheres, ball.budget), (1, Some(1)));
    let why = ball.shortfall.as_deref().unwrap_or_default();
    assert!(why.contains("passed to other links"), "{why}");

    // A box and a cylinder: their count exactly, or fewer with the reason.
    for primitive in &parts[..2] {
        for n in [1, 5, 12] {
            let fit = one_link(link(None, vec![*primitive]), &count(n));
            match &fit.report.shortfall {
                None => assert_eq!(fit.spheres.len(), n),
                Some(why) => assert!(fit.spheres.len() < n && why.contains("tightest layout")),
            }
            for p in primitive.surface_points(800) {
                assert!(
                    inside_some(&fit.spheres, p),
                    "{} at {n}: {p}",
                    primitive.kind()
                );
            }
        }
    }
}

/// Bad inputs are refused with the parameter, the link or the file named.
#[test]
fn bad_inputs_give_clear_errors() {
    let urdf = Urdf::parse(
        r#"<robot name="r"><link name="a"><collision><geometry><sphere radius="0.1"/></geometry></collision></link></robot>"#,
        "r.urdf",
    )
    .expect("parse");
    let resolver = MeshResolver::new(urdf.folder());
    let refused = |options: SpherizeOptions| {
        spherize(&urdf, &resolver, &options)
            .expect_err("refused")
            .to_string()
    };
    for budget in [SphereBudget::PerLink(0), SphereBudget::Total(0)] {
        let message = refused(SpherizeOptions::default().with_budget(budget));
        assert!(
            message.contains("sphere count") && message.contains("at least 1"),
            "{message}"
        );
    }
    let message = refused(SpherizeOptions::default().with_link("a", 0));
    assert!(message.contains("at least 1"), "{message}");
    for value in [f64::NAN, f64::INFINITY, -0.01, 0.0] {
        for tolerance in [Length::Absolute(value), Length::RelativeToDiagonal(value)] {
            let message =
                refused(SpherizeOptions::default().with_budget(SphereBudget::Tolerance(tolerance)));
            assert!(
                message.contains("tolerance") && message.contains("positive and finite"),
                "{value}: {message}"
            );
        }
    }
    let medial = SpherizeOptions::default().with_tree(
        sphaera_spheretree::SphereTreeOptions::default()
            .with_method(sphaera_spheretree::Method::Merge),
    );
    assert!(refused(medial).contains("minimax"));
    let message = refused(SpherizeOptions::default().with_link("b", 3));
    assert!(message.contains("no link \"b\""), "{message}");

    // A mesh file that is not there: the link, the file and every path tried.
    let dir = tempfile::tempdir().expect("a folder");
    let path = dir.path().join("r.urdf");
    std::fs::write(
        &path,
        r#"<robot name="r"><link name="arm"><collision><geometry><mesh filename="package://meshes/gone.stl"/></geometry></collision></link></robot>"#,
    )
    .expect("write");
    let urdf = Urdf::read(&path).expect("read");
    let error = spherize(
        &urdf,
        &MeshResolver::new(urdf.folder()),
        &SpherizeOptions::default(),
    )
    .expect_err("missing");
    let message = error.to_string();
    assert!(
        matches!(error, RobotError::MeshNotFound { .. })
            && message.contains("\"arm\"")
            && message.contains("gone.stl")
            && message.contains(&dir.path().join("meshes/gone.stl").display().to_string()),
        "{message}"
    );
}
