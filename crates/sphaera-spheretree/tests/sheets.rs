//! Sheets and open patches (a surface without inside): the default method covers them,
//! the paper's medial methods say they need a solid.

mod checks;

use sphaera_mesh::{DVec3, Length, TriMesh, shapes};
use sphaera_query::Surface;
use sphaera_spheretree::{Method, SphereTreeError, SphereTreeOptions, build};
use sphaera_tests::awkward;

/// The sheets: a square, a disc, a ring (a sheet with a hole), two squares crossing at a
/// right angle, and a box flattened to zero thickness (its two faces coincide).
fn sheets() -> Vec<(&'static str, TriMesh)> {
    let square = shapes::square_sheet(2.0, 6).expect("square");
    let upright = awkward::mapped(&square, |p| DVec3::new(p.x, 0.0, p.y), false);
    let flat_box = awkward::mapped(
        &shapes::cube(2.0, 3).expect("cube"),
        |p| DVec3::new(p.x, p.y, 0.0),
        false,
    );
    vec![
        ("square", square.clone()),
        ("disc", shapes::ring_sheet(1.0, 0.0, 24).expect("disc")),
        ("ring", shapes::ring_sheet(1.0, 0.4, 24).expect("ring")),
        ("crossing squares", awkward::join(&[square, upright])),
        ("flattened box", flat_box),
    ]
}

#[test]
fn sheets_are_shells_and_get_trees_that_cover_them() {
    for (name, mesh) in sheets() {
        let surface = Surface::solid_or_shell(&mesh).expect("a mesh with area");
        assert!(!surface.has_inside(), "{name}: taken as a solid");
        let tree = build(
            &surface,
            &SphereTreeOptions::default().with_depth(2).with_branch(4),
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(tree.level(1).len(), 4, "{name}");
        assert_eq!(tree.level(2).len(), 16, "{name}");
        checks::check_tree(&surface, &tree, 4_000, 200, name);
        // Finer levels reach less far from the sheet.
        let worst = |level: usize| {
            tree.level(level)
                .iter()
                .map(|n| n.error)
                .fold(0.0, f64::max)
        };
        assert!(worst(2) < worst(1) && worst(1) < worst(0), "{name}");
    }
}

#[test]
fn a_tolerance_is_met_on_sheets() {
    for (name, mesh) in sheets() {
        let surface = Surface::solid_or_shell(&mesh).expect("a mesh with area");
        let tolerance = 0.08 * surface.diagonal();
        let options = SphereTreeOptions::default().with_tolerance(Length::Absolute(tolerance));
        let tree = build(&surface, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
        for leaf in tree.leaves() {
            assert!(tree.nodes()[leaf].error <= tolerance, "{name}: leaf {leaf}");
        }
        checks::check_tree(&surface, &tree, 3_000, 120, name);
    }
}

#[test]
fn the_medial_methods_need_a_solid() {
    let surface = Surface::shell(&shapes::square_sheet(1.0, 2).expect("square")).expect("shell");
    for method in [
        Method::Merge,
        Method::Burst,
        Method::Expand,
        Method::Combined,
    ] {
        let options = SphereTreeOptions::default().with_method(method);
        match build(&surface, &options) {
            Err(SphereTreeError::NeedsInside { method: named }) => {
                assert_eq!(named, method.name());
                let text = SphereTreeError::NeedsInside { method: named }.to_string();
                assert!(
                    text.contains("needs a solid") && text.contains("minimax"),
                    "{text}"
                );
            }
            other => panic!("{method:?}: {other:?}"),
        }
    }
}
