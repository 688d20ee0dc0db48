//! `Surface::signed_closest` against `Surface::closest` and the certified winding number
//! (`Surface::is_inside_certified`), on procedural shapes under random similarity
//! transforms and on the shared real meshes, and the embedded-solid certificate on them.

#![allow(clippy::print_stderr)] // the timing report and skipped tests say what they measured

use std::path::Path;
use std::time::Instant;

use proptest::prelude::*;
use sphaera_io as io;
use sphaera_mesh::{Aabb, DVec3, TriMesh, shapes};
use sphaera_query::Surface;
use sphaera_query::surface::{EmbeddingDefect, SideMethod};
use sphaera_tests::random::SplitMix64;

/// `mesh` rotated by `rotation` (a unit quaternion's axis-angle), scaled and translated.
fn placed(mesh: &TriMesh, axis: DVec3, angle: f64, scale: f64, translation: DVec3) -> TriMesh {
    let rotation = glam::DQuat::from_axis_angle(axis.normalize(), angle);
    let positions = mesh
        .positions()
        .iter()
        .map(|&p| rotation * p * scale + translation)
        .collect();
    TriMesh::new(positions, mesh.triangles().to_vec()).expect("finite positions")
}

fn shape(index: usize) -> TriMesh {
    match index {
        0 => shapes::sphere(1.0, 12),
        1 => shapes::torus(1.0, 0.3, 16),
        2 => shapes::cube(2.0, 3),
        3 => shapes::capsule(0.5, 1.5, 10),
        4 => shapes::cube(2.0, 1),
        _ => shapes::l_block(2.0, 0.8, 1.0, 3),
    }
    .expect("a shape")
}

/// Random points in the box grown by a third of its diagonal.
fn random_points(bounds: Aabb, count: usize, seed: u64) -> Vec<DVec3> {
    let mut rng = SplitMix64::new(seed);
    let grown = bounds.expanded(bounds.diagonal() / 3.0);
    (0..count)
        .map(|_| {
            DVec3::new(
                rng.range(grown.min.x, grown.max.x),
                rng.range(grown.min.y, grown.max.y),
                rng.range(grown.min.z, grown.max.z),
            )
        })
        .collect()
}

/// Random points in the box itself.
fn points_in_box(bounds: Aabb, count: usize, seed: u64) -> Vec<DVec3> {
    let shrunk = bounds;
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .map(|_| {
            DVec3::new(
                rng.range(shrunk.min.x, shrunk.max.x),
                rng.range(shrunk.min.y, shrunk.max.y),
                rng.range(shrunk.min.z, shrunk.max.z),
            )
        })
        .collect()
}

/// Points near the vertices, edges and faces of `mesh`, in random directions, at
/// distances from `1e-8` to `1e-1` of the diagonal.
fn points_near_features(mesh: &TriMesh, count: usize, seed: u64) -> Vec<DVec3> {
    let mut rng = SplitMix64::new(seed);
    let diagonal = mesh.bounding_box().diagonal();
    (0..count)
        .map(|_| {
            let t = mesh
                .triangle(rng.index(mesh.triangle_count()))
                .expect("in range");
            let (u, v) = (rng.unit(), rng.unit());
            let base = match rng.index(3) {
                0 => t.a,
                1 => t.a + u * (t.b - t.a),
                _ => t.point_at(0.5 * u, 0.5 * v),
            };
            base + diagonal * 10_f64.powf(rng.range(-8.0, -1.0)) * rng.direction()
        })
        .collect()
}

/// Checks `signed_closest` against `closest` and `is_inside_certified` at `points` away
/// from the surface (farther than `1e-9` of the diagonal); returns how many sides the
/// pseudo-normal test decided.
fn check_agreement(surface: &Surface, points: &[DVec3]) -> usize {
    let mut decided = 0;
    for &p in points {
        let signed = surface.signed_closest(p).expect("finite query");
        assert_eq!(
            signed.closest,
            surface.closest(p).expect("finite query"),
            "at {p}"
        );
        if signed.closest.distance <= 1e-9 * surface.diagonal() {
            continue;
        }
        assert_eq!(signed.inside, surface.is_inside_certified(p), "at {p}");
        decided += usize::from(signed.method == SideMethod::PseudoNormal);
        if !surface.is_embedded_solid() {
            assert_eq!(signed.method, SideMethod::CertifiedWinding);
        }
    }
    decided
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(48)))]

    /// Random points around a shape placed by a random similarity (scales 2^±20): the
    /// same closest point as `closest`, the same side as the certified winding number.
    #[test]
    fn signed_closest_matches_closest_and_certified_winding(
        index in 0..6_usize,
        axis in (-1.0..1.0_f64, -1.0..1.0_f64, 0.1..1.0_f64),
        angle in 0.0..6.3_f64,
        scale_exponent in -20..=20_i32,
        translation in (-3.0..3.0_f64, -3.0..3.0_f64, -3.0..3.0_f64),
        seed in any::<u64>(),
    ) {
        let scale = 2.0_f64.powi(scale_exponent);
        let translation = DVec3::new(translation.0, translation.1, translation.2) * scale;
        let axis = DVec3::new(axis.0, axis.1, axis.2);
        let mesh = placed(&shape(index), axis, angle, scale, translation);
        let surface = Surface::new(&mesh).expect("a solid");
        prop_assert!(surface.is_embedded_solid(), "{:?}", surface.embedding_defect());
        let mut points = random_points(mesh.bounding_box(), 150, seed);
        // And points very near the surface: vertices and face centres pushed off by a
        // little more than the tolerance, both ways.
        let mut rng = SplitMix64::new(seed ^ 0x5eed);
        for _ in 0..50 {
            let t = rng.index(mesh.triangle_count());
            let triangle = mesh.triangle(t).expect("in range");
            let normal = triangle.unit_normal().expect("not degenerate");
            let offset = 2e-9 * surface.diagonal() * if rng.unit() < 0.5 { 1.0 } else { -1.0 };
            points.push(triangle.centroid() + offset * normal);
            points.push(triangle.a + offset * normal);
        }
        let decided = check_agreement(&surface, &points);
        prop_assert!(decided * 10 >= points.len() * 7, "only {decided} of {} decided", points.len());
    }
}

fn load(data: &Path, file: &str) -> TriMesh {
    io::load(data.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"))
}

#[test]
fn real_meshes_agree_with_the_certified_winding_number() {
    let Some(data) = sphaera_tests::data_dir("real_meshes_agree_with_the_certified_winding_number")
    else {
        return;
    };
    for (file, embedded, count) in [
        ("bunny_lowres.obj", true, 3000),
        ("spot.obj", true, 1000),
        ("fandisk.obj", true, 1000),
        ("teapot.obj", false, 1000),
        ("stanford-bunny.obj", false, 300),
        ("robots/objects/teddy2_VHACD_CHs.obj", false, 2000),
    ] {
        let surface = Surface::from_mesh(load(&data, file)).expect("a solid");
        assert_eq!(
            surface.is_embedded_solid(),
            embedded,
            "{file}: {:?}",
            surface.embedding_defect()
        );
        let points = random_points(surface.mesh().bounding_box(), count, 42);
        let decided = check_agreement(&surface, &points);
        if embedded {
            assert!(
                decided * 10 >= count * 8,
                "{file}: {decided} of {count} decided"
            );
        }
    }
}

#[test]
fn points_near_sharp_edges_and_vertices_agree() {
    let mut meshes = vec![
        shape(4),
        shape(5),
        shapes::cone(1.0, 2.0, 8).expect("a cone"),
    ];
    if let Some(data) = sphaera_tests::data_dir("points_near_sharp_edges_and_vertices_agree") {
        meshes.push(load(&data, "fandisk.obj"));
    }
    for (index, mesh) in meshes.iter().enumerate() {
        let surface = Surface::new(mesh).expect("a solid");
        assert!(surface.is_embedded_solid());
        let points = points_near_features(mesh, 4000, index as u64);
        let decided = check_agreement(&surface, &points);
        assert!(
            decided * 10 >= points.len() * 9,
            "mesh {index}: {decided} decided"
        );
    }
}

#[test]
#[ignore = "a report: cargo test --release -p sphaera-mesh --test signed_closest -- --ignored --nocapture"]
fn report_certificates_and_timings() {
    let Some(data) = sphaera_tests::data_dir("report_certificates_and_timings") else {
        return;
    };
    let mut files: Vec<String> = sphaera_tests::mesh_files(&data)
        .iter()
        .map(|f| f.display().to_string())
        .collect();
    files.sort();
    for file in &files {
        let mesh = load(&data, file);
        let triangles = mesh.triangle_count();
        let start = Instant::now();
        let surface = match Surface::from_mesh(mesh) {
            Ok(surface) => surface,
            Err(e) => {
                eprintln!("{file}: no surface ({e})");
                continue;
            }
        };
        let built = start.elapsed().as_secs_f64();
        let defect = surface
            .embedding_defect()
            .map_or_else(|| "embedded".to_owned(), |d| d.to_string());
        eprintln!("{file} ({triangles} triangles): Surface in {built:.3} s, {defect}");
        if triangles > 100_000 {
            continue;
        }
        let points = points_in_box(surface.mesh().bounding_box(), 20_000, 1);
        let start = Instant::now();
        let mut decided = 0;
        for &p in &points {
            let s = surface.signed_closest(p).expect("finite");
            decided += usize::from(s.method == SideMethod::PseudoNormal);
        }
        let signed = start.elapsed().as_secs_f64() * 1e6 / points.len() as f64;
        let start = Instant::now();
        for &p in &points {
            let c = surface.closest(p).expect("finite");
            std::hint::black_box((c, surface.is_inside_certified(p)));
        }
        let both = start.elapsed().as_secs_f64() * 1e6 / points.len() as f64;
        let start = Instant::now();
        for &p in &points {
            std::hint::black_box(surface.closest(p).expect("finite"));
        }
        let closest = start.elapsed().as_secs_f64() * 1e6 / points.len() as f64;
        eprintln!(
            "    signed_closest {signed:.2} µs, closest + is_inside_certified {both:.2} µs, \
             closest {closest:.2} µs; pseudo-normal decided {decided} of {}",
            points.len()
        );
    }
}

/// Keeps `EmbeddingDefect` in use for the detector tests below.
fn defect_of(mesh: &TriMesh) -> Option<EmbeddingDefect> {
    Surface::new(mesh).expect("a solid").embedding_defect()
}

#[test]
fn shapes_are_certified() {
    for index in 0..6 {
        assert_eq!(defect_of(&shape(index)), None, "shape {index}");
    }
}

/// The triangles of both meshes as one mesh (the second's vertices after the first's).
fn merged(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let offset = u32::try_from(a.vertex_count()).expect("small");
    let mut positions = a.positions().to_vec();
    positions.extend_from_slice(b.positions());
    let mut triangles = a.triangles().to_vec();
    triangles.extend(b.triangles().iter().map(|t| t.map(|v| v + offset)));
    TriMesh::new(positions, triangles).expect("valid")
}

fn moved(mesh: &TriMesh, by: DVec3) -> TriMesh {
    placed(mesh, DVec3::Z, 0.0, 1.0, by)
}

fn flipped(mesh: &TriMesh) -> TriMesh {
    let triangles = mesh
        .triangles()
        .iter()
        .map(|&[a, b, c]| [a, c, b])
        .collect();
    TriMesh::new(mesh.positions().to_vec(), triangles).expect("valid")
}

fn cube() -> TriMesh {
    shapes::cube(2.0, 1).expect("a cube") // [-1, 1]³
}

/// The index of the vertex of `mesh` at `p`.
fn vertex_at(mesh: &TriMesh, p: DVec3) -> usize {
    mesh.positions()
        .iter()
        .position(|&q| q == p)
        .expect("a vertex there")
}

fn with_vertex_moved(mesh: &TriMesh, vertex: usize, to: DVec3) -> TriMesh {
    let mut positions = mesh.positions().to_vec();
    positions[vertex] = to;
    TriMesh::new(positions, mesh.triangles().to_vec()).expect("valid")
}

/// Agreement with the certified winding number on points around `mesh`.
fn agrees_everywhere(mesh: &TriMesh) {
    let surface = Surface::new(mesh).expect("a solid");
    check_agreement(&surface, &random_points(mesh.bounding_box(), 400, 9));
}

#[test]
fn overlapping_cubes_intersect_and_disjoint_cubes_do_not() {
    let overlapping = merged(&cube(), &moved(&cube(), DVec3::new(1.0, 0.5, 0.25)));
    assert!(matches!(
        defect_of(&overlapping),
        Some(EmbeddingDefect::SelfIntersection { .. })
    ));
    agrees_everywhere(&overlapping);
    let disjoint = merged(&cube(), &moved(&cube(), DVec3::new(2.5, 0.5, 0.25)));
    assert_eq!(defect_of(&disjoint), None);
    agrees_everywhere(&disjoint);
    // Face to face, one touching the other along a whole side: a contact.
    let touching = merged(&cube(), &moved(&cube(), DVec3::new(2.0, 0.5, 0.25)));
    assert!(matches!(
        defect_of(&touching),
        Some(EmbeddingDefect::SelfIntersection { .. })
    ));
}

#[test]
fn a_vertex_pushed_through_the_opposite_face_intersects() {
    let mesh = cube();
    let corner = vertex_at(&mesh, DVec3::ONE);
    let pushed = with_vertex_moved(&mesh, corner, DVec3::new(-1.5, -0.2, -0.4));
    assert!(matches!(
        defect_of(&pushed),
        Some(EmbeddingDefect::SelfIntersection { .. })
    ));
    agrees_everywhere(&pushed);
}

#[test]
fn a_fold_across_an_edge_intersects() {
    // The top face z = 1 is split along the diagonal from (-1, -1) to (1, 1); moving its
    // corner (-1, 1) across that diagonal, in the plane, folds one triangle onto the other.
    let mesh = cube();
    let corner = vertex_at(&mesh, DVec3::new(-1.0, 1.0, 1.0));
    let folded = with_vertex_moved(&mesh, corner, DVec3::new(0.5, -0.5, 1.0));
    let Some(EmbeddingDefect::SelfIntersection { first, second }) = defect_of(&folded) else {
        panic!("the fold is not found");
    };
    // The pair reported is the folded one: two triangles of an edge.
    let [a, b] = [first, second].map(|t| folded.triangles()[t as usize]);
    assert_eq!(a.iter().filter(|v| b.contains(v)).count(), 2, "{a:?} {b:?}");
}

#[test]
fn tetrahedra_touching_at_a_point_intersect() {
    let tetrahedron = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
    .expect("valid");
    // The second's apex on the first's slanted face, at (0.2, 0.3, 0.5).
    let apex = DVec3::new(0.2, 0.3, 0.5);
    let second = TriMesh::new(
        vec![
            apex,
            apex + DVec3::new(1.0, 1.0, 0.0),
            apex + DVec3::new(0.0, 1.0, 1.0),
            apex + DVec3::ONE,
        ],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
    .expect("valid");
    let first_surface = Surface::new(&second).expect("a solid");
    // The second tetrahedron alone is a solid (its orientation is outward).
    assert!(first_surface.is_embedded_solid());
    let touching = merged(&tetrahedron, &second);
    assert!(matches!(
        defect_of(&touching),
        Some(EmbeddingDefect::SelfIntersection { .. })
    ));
    // Moved off by a little: apart.
    let apart = merged(&tetrahedron, &moved(&second, DVec3::splat(1e-9)));
    assert_eq!(defect_of(&apart), None);
    agrees_everywhere(&apart);
}

#[test]
fn cubes_sharing_a_vertex_index_are_pinched() {
    let a = cube();
    let b = moved(&cube(), DVec3::splat(2.0));
    let mut mesh = merged(&a, &b);
    // Vertex (1, 1, 1) of the first and (1, 1, 1) of the second become one index.
    let shared = vertex_at(&a, DVec3::ONE) as u32;
    let other = (a.vertex_count() + vertex_at(&b, DVec3::ONE)) as u32;
    let triangles = mesh
        .triangles()
        .iter()
        .map(|t| t.map(|v| if v == other { shared } else { v }))
        .collect();
    mesh = TriMesh::new(mesh.positions().to_vec(), triangles).expect("valid");
    assert!(matches!(
        defect_of(&mesh),
        Some(EmbeddingDefect::NonManifoldVertex { .. })
    ));
    agrees_everywhere(&mesh);
    // With two indices at one position instead: a duplicate position.
    let two_indices = merged(&a, &b);
    assert!(matches!(
        defect_of(&two_indices),
        Some(EmbeddingDefect::DuplicatePosition { .. })
    ));
}

#[test]
fn nested_shells_are_refused_and_a_cavity_is_certified() {
    let outer = shapes::sphere(2.0, 12).expect("a sphere");
    let inner = shapes::sphere(1.0, 12).expect("a sphere");
    // Both outward: the winding number is 2 inside the inner one.
    let nested = merged(&outer, &inner);
    assert!(matches!(
        defect_of(&nested),
        Some(EmbeddingDefect::NotOutward { .. })
    ));
    agrees_everywhere(&nested);
    // The inner one inward: a hollow ball, 0 in the cavity.
    let hollow = merged(&outer, &flipped(&inner));
    assert_eq!(defect_of(&hollow), None);
    let surface = Surface::new(&hollow).expect("a solid");
    let cavity = surface
        .signed_closest(DVec3::new(0.1, 0.2, 0.0))
        .expect("finite");
    assert!(!cavity.inside && cavity.method == SideMethod::PseudoNormal);
    let shell = surface
        .signed_closest(DVec3::new(1.5, 0.0, 0.1))
        .expect("finite");
    assert!(shell.inside && shell.method == SideMethod::PseudoNormal);
    agrees_everywhere(&hollow);
    // A small inward-oriented ball beside a large outward one: −1 inside the small one.
    let beside = merged(&outer, &flipped(&moved(&inner, DVec3::new(4.0, 0.0, 0.0))));
    assert!(matches!(
        defect_of(&beside),
        Some(EmbeddingDefect::NotOutward { .. })
    ));
    agrees_everywhere(&beside);
}

#[test]
fn open_and_degenerate_meshes_are_refused() {
    let mesh = cube();
    let open =
        TriMesh::new(mesh.positions().to_vec(), mesh.triangles()[1..].to_vec()).expect("valid");
    assert!(matches!(
        defect_of(&open),
        Some(EmbeddingDefect::OpenOrNonManifoldEdge { triangles: 1, .. })
    ));
    let mut reversed = mesh.triangles().to_vec();
    reversed[0] = [reversed[0][0], reversed[0][2], reversed[0][1]];
    let inconsistent = TriMesh::new(mesh.positions().to_vec(), reversed).expect("valid");
    assert!(matches!(
        defect_of(&inconsistent),
        Some(EmbeddingDefect::InconsistentOrientation { .. })
    ));
    // A corner moved onto the middle of the opposite side of one of its triangles: that
    // triangle has zero area.
    let corner = vertex_at(&mesh, DVec3::ONE);
    let &[a, b, c] = mesh
        .triangles()
        .iter()
        .find(|t| t.contains(&(corner as u32)))
        .expect("a triangle at the corner");
    let others: Vec<DVec3> = [a, b, c]
        .iter()
        .filter(|&&v| v as usize != corner)
        .map(|&v| mesh.positions()[v as usize])
        .collect();
    let flat = with_vertex_moved(&mesh, corner, (others[0] + others[1]) / 2.0);
    assert!(matches!(
        defect_of(&flat),
        Some(EmbeddingDefect::DegenerateTriangle { .. })
    ));
    agrees_everywhere(&flat);
}

/// 64-bit FNV-1a of a stream of words.
fn fnv(words: impl IntoIterator<Item = u64>) -> u64 {
    words.into_iter().fold(0xcbf2_9ce4_8422_2325, |h, w| {
        w.to_le_bytes().iter().fold(h, |h, &b| {
            (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
        })
    })
}

/// Golden values: the same bits with and without the `parallel` feature (`cargo xtask
/// test` runs both), and across runs.
#[test]
fn answers_are_the_same_with_and_without_parallel() {
    let torus = shapes::torus(1.0, 0.3, 24).expect("a torus");
    let surface = Surface::new(&torus).expect("a solid");
    let points = random_points(torus.bounding_box(), 2000, 5);
    let answers = surface.signed_closest_many(&points).expect("finite");
    let hash = fnv(answers.iter().flat_map(|a| {
        [
            a.closest.point.x.to_bits(),
            a.closest.point.y.to_bits(),
            a.closest.point.z.to_bits(),
            u64::from(a.closest.triangle),
            u64::from(a.inside),
            u64::from(a.method == SideMethod::PseudoNormal),
        ]
    }));
    assert_eq!(
        hash, 9_355_426_611_684_587_116,
        "signed closest fingerprint"
    );
    // Many crossing pairs: the smallest is reported either way.
    let crossing = merged(
        &shapes::sphere(1.0, 16).expect("a sphere"),
        &moved(
            &shapes::torus(1.0, 0.3, 24).expect("a torus"),
            DVec3::new(0.5, 0.0, 0.1),
        ),
    );
    assert_eq!(
        defect_of(&crossing),
        Some(EmbeddingDefect::SelfIntersection {
            first: 82,
            second: 377
        }),
        "smallest crossing pair"
    );
}
