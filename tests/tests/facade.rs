//! The facade as a user writes it: `sphaera` with its default features, its prelude and
//! its re-exported crates `sphaera::{mesh, simplify, sweep, medial, spheretree}`, used the
//! way the README and the crate docs show. Every path below goes through the facade (no
//! `sphaera_*` crate is named), so a re-export that breaks, or a type that stops being the
//! same type on both sides of two crates, fails to compile here.
//!
//! 0.5–0.7 s wall in the test profile on the shared 2-core machine.

use sphaera::prelude::*;
use sphaera::{medial, mesh, simplify, spheretree, sweep};

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// The facade's own quick start: a torus from the procedural shapes, its topology.
#[test]
fn prelude_and_mesh() -> Result<()> {
    let torus: TriMesh = mesh::shapes::torus(1.0, 0.25, 32)?;
    let report = mesh::topology::analyze(&torus);
    assert!(report.is_closed);
    assert_eq!(report.genus, Some(1));
    let bounds: Aabb = torus.bounding_box();
    assert!(bounds.contains_point(DVec3::ZERO));
    assert!(torus.bounding_box_diagonal() > 2.0);
    let ball: Sphere = mesh::geometry::minimum_enclosing_ball(torus.positions())?;
    assert!(ball.radius >= 1.25 - 1e-9);
    // The prelude's error is the mesh crate's.
    let out_of_range: std::result::Result<TriMesh, MeshError> =
        TriMesh::new(vec![DVec3::ZERO], vec![[0, 0, 1]]);
    assert!(out_of_range.is_err());
    Ok(())
}

/// `sphaera simplify` and `sphaera hausdorff` as a library user writes them: simplify,
/// then bracket the distance with the sweep crate; the bound the simplifier reports is
/// never below the certified lower bound.
#[test]
fn simplify_then_sweep() -> Result<()> {
    let sphere = mesh::shapes::sphere(1.0, 24)?;
    let out: Simplified =
        simplify::simplify(&sphere, &SimplifyOptions::default().with_target_ratio(0.1))?;
    assert!(out.mesh.triangle_count() <= sphere.triangle_count() / 10 + 1);

    let ha = sweep::build_hierarchy(&sphere)?;
    let a = Sweeper::new(&ha)?;
    let mut session = a.session();
    let answer: sweep::ClosestPoint = session.closest(DVec3::new(2.0, 0.0, 0.0))?;
    assert!((answer.distance - 1.0).abs() < 1e-2);

    let options =
        sweep::HausdorffOptions::default().with_tolerance(Length::Absolute(1e-2 * out.error_bound));
    let h = sweep::hausdorff(&sphere, &out.mesh, &options)?;
    assert!(h.lower <= h.upper);
    assert!(out.error_bound >= h.lower - 1e-12);
    Ok(())
}

/// The medial crate through the facade: a surface, the adaptive approximation, a valid
/// Delaunay tetrahedralization.
#[test]
fn medial_approximation() -> Result<()> {
    let capsule = mesh::shapes::capsule(0.5, 2.0, 12)?;
    let surface = Surface::new(&capsule)?;
    let samples: Vec<DVec3> = mesh::sampling::poisson_disk(&capsule, 1_000, 1)?
        .samples
        .iter()
        .map(|s| s.position)
        .collect();
    let params = medial::MedialOptions::default().with_max_error(0.05);
    let approximation = medial::MedialApproximation::build(&surface, &samples, &params)?;
    assert!(approximation.worst_error() <= 0.05);
    assert!(approximation.uncovered_samples().is_empty());
    approximation.delaunay().validate()?;
    let delaunay = medial::Delaunay::new(&samples)?;
    delaunay.validate()?;
    Ok(())
}

/// `sphaera spheretree` as a library user writes it: build, choose a level by tolerance,
/// evaluate it, write and read JSON.
#[test]
fn spheretree_build_select_evaluate_export() -> Result<()> {
    let capsule = mesh::shapes::capsule(0.5, 2.0, 12)?;
    let surface = Surface::new(&capsule)?;
    let options = SphereTreeOptions::default()
        .with_method(Method::Expand)
        .with_depth(2)
        .with_branch(4)
        .with_samples(1_500)
        .with_initial_spheres(100)
        .with_min_spheres_per_node(30);
    let tree: SphereTree = spheretree::build(&surface, &options)?;
    assert_eq!(tree.level_count(), 3);
    assert_eq!(tree.coverage().len(), 3);
    let worst = |l: usize| tree.level(l).iter().map(|n| n.error).fold(0.0, f64::max);
    assert_eq!(spheretree::level_for_tolerance(&tree, worst(1)), Some(1));

    // The prelude's `Sphere` is the sphere-tree's, and the surface the tree was built on
    // evaluates it.
    let spheres: Vec<Sphere> = tree.level_spheres(2);
    let options = spheretree::EvaluationOptions::default().with_coverage_samples(5_000);
    let set = spheretree::evaluate_set(&surface, &spheres, &options)?;
    assert_eq!(set.coverage.uncovered, 0);
    assert!(set.worst_lower <= set.worst_upper);

    let text = spheretree::export::tree_to_json(&tree);
    assert_eq!(spheretree::export::tree_from_json(&text)?, tree);
    let rebuilt = SphereTree::from_levels(
        tree.branch(),
        (0..tree.level_count())
            .map(|l| tree.level(l).to_vec())
            .collect(),
    )?;
    assert_eq!(rebuilt.nodes(), tree.nodes());
    Ok(())
}

/// Every crate's error converts for a user's `?` (into `Box<dyn Error>`) and says what
/// went wrong.
#[test]
fn errors_of_every_crate_convert_for_question_mark() {
    fn nan_vertex() -> Result<()> {
        TriMesh::new(vec![DVec3::NAN], Vec::new())?;
        Ok(())
    }
    fn nan_ratio() -> Result<()> {
        let capsule = mesh::shapes::capsule(0.5, 2.0, 8)?;
        simplify::simplify(
            &capsule,
            &SimplifyOptions::default().with_target_ratio(f64::NAN),
        )?;
        Ok(())
    }
    fn flat_points() -> Result<()> {
        let square = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)];
        medial::Delaunay::new(&square)?;
        Ok(())
    }
    fn no_branching() -> Result<()> {
        let capsule = mesh::shapes::capsule(0.5, 2.0, 8)?;
        let surface = Surface::new(&capsule)?;
        spheretree::build(&surface, &SphereTreeOptions::default().with_branch(0))?;
        Ok(())
    }
    for (what, result) in [
        ("a NaN vertex", nan_vertex()),
        ("a NaN ratio", nan_ratio()),
        ("flat points", flat_points()),
        ("branch 0", no_branching()),
    ] {
        let error = result.err().unwrap_or_else(|| panic!("{what}: no error"));
        assert!(!error.to_string().is_empty(), "{what}: an empty message");
    }
}

/// One error type across crates: `?` on a mesh, a simplification, a sphere-tree and a
/// scene error in one function, each message the crate's own.
#[test]
fn one_error_type_across_crates() {
    use std::sync::Arc;

    fn pipeline(radius: f64, branch: usize) -> sphaera::Result<usize> {
        let torus = mesh::shapes::torus(1.0, radius, 24)?;
        let coarse =
            simplify::simplify(&torus, &SimplifyOptions::default().with_target_ratio(0.5))?;
        let options = SphereTreeOptions::default()
            .with_depth(1)
            .with_branch(branch);
        let model = ObjectModel::build(
            "torus",
            coarse.mesh,
            &ModelOptions::default().with_tree(options),
        )?;
        let mut scene = Scene::new();
        scene.add("one", Arc::new(model), mesh::geometry::Similarity::IDENTITY);
        let report = scene.detail(None, sphaera::scene::Tolerance::RelativeToDiagonal(0.05))?;
        Ok(report.triangles)
    }

    assert!(pipeline(0.3, 4).expect("a pipeline") > 0);
    let mesh_error = pipeline(-1.0, 4).expect_err("a negative radius");
    assert!(
        matches!(mesh_error, sphaera::Error::Mesh(_)),
        "{mesh_error:?}"
    );
    let direct = mesh::shapes::torus(1.0, -1.0, 24).expect_err("a negative radius");
    assert_eq!(mesh_error.to_string(), direct.to_string());
    let tree_error = pipeline(0.3, 0).expect_err("no children");
    assert!(
        matches!(
            &tree_error,
            sphaera::Error::Scene(e) if matches!(**e, sphaera::scene::SceneError::SphereTree(_))
        ),
        "{tree_error:?}"
    );
    // Boxed: a `Result` of it stays two words wide.
    assert!(size_of::<sphaera::Error>() <= 16);
}
