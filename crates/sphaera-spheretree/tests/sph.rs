//! The `.sph` reader and writer: conventions, malformed files, round trips.

use proptest::prelude::*;
use sphaera_spheretree::export::{SphDefect, SphFile, read_sph, write_sph};
use sphaera_spheretree::{DVec3, Sphere, SphereTreeError};

/// The line and message of a syntax error (panics on any other outcome).
fn format_error(text: &str) -> (usize, String) {
    match read_sph(text, DVec3::ZERO) {
        Err(SphereTreeError::SphSyntax { line, defect }) => (line, defect.to_string()),
        other => panic!("expected a format error, got {other:?}"),
    }
}

#[test]
fn levels_include_the_root_and_nodes_are_level_by_level() {
    // 3 levels of branching factor 2: 1 + 2 + 4 nodes.
    let text = "3 2
0 0 0 4 1
-2 0 0 2 1
2 0 0 2 1
-3 0 0 1 1
-1 0 0 1 1
0 0 0 -1 1
3 0 0 1 1
";
    let tree = read_sph(text, DVec3::ZERO).unwrap();
    assert_eq!((tree.levels, tree.branch, tree.nodes.len()), (3, 2, 7));
    assert_eq!(tree.level(0), vec![Sphere::new(DVec3::ZERO, 4.0)]);
    assert_eq!(tree.level(1).len(), 2);
    assert_eq!(tree.level(2).len(), 3);
    assert_eq!(tree.level_range(2), 3..7);
    assert_eq!(tree.children(1), 3..5);
    assert_eq!(tree.children(2), 5..7);
    assert_eq!(tree.nodes[5], None);
    assert_eq!(tree.children(3), 7..7);
}

#[test]
fn offset_is_added_to_every_center() {
    let text = "2 1\n1 2 3 4 1\n0 0 0 1 1\n";
    let tree = read_sph(text, DVec3::new(10.0, 20.0, 30.0)).unwrap();
    assert_eq!(tree.level(0)[0].center, DVec3::new(11.0, 22.0, 33.0));
    assert_eq!(tree.level(1)[0].center, DVec3::new(10.0, 20.0, 30.0));
    let back = write_sph(&tree, DVec3::new(10.0, 20.0, 30.0)).unwrap();
    assert_eq!(back, "2 1\n1 2 3 4 1\n0 0 0 1 1\n");
}

#[test]
fn zero_radius_is_an_unused_slot_as_in_the_toolkit() {
    let tree = read_sph("2 1\n0 0 0 1 1\n0 0 0 0 1\n", DVec3::ZERO).unwrap();
    assert_eq!(tree.nodes[1], None);
    assert!(tree.level(1).is_empty());
}

#[test]
fn toolkit_variants_are_accepted() {
    // Blank lines, a 4-field line (importance 1), a 10-field line (auxiliary sphere
    // ignored), the importance kept, Windows line endings, 6-decimal "%f" numbers.
    let text = "\r\n2 2\r\n\r\n0.000000 0.000000 0.000000 2.500000 1.000000\r\n1 0 0 1\r\n-1 0 0 1 0.5 -1 0 0 1.1 0.25\r\n";
    let tree = read_sph(text, DVec3::ZERO).unwrap();
    assert_eq!(tree.nodes[0], Some((Sphere::new(DVec3::ZERO, 2.5), 1.0)));
    assert_eq!(tree.nodes[1], Some((Sphere::new(DVec3::X, 1.0), 1.0)));
    assert_eq!(tree.nodes[2], Some((Sphere::new(-DVec3::X, 1.0), 0.5)));
}

#[test]
fn trailing_unused_slots_are_accepted() {
    // The toolkit allocates 1 + B nodes even for a single level.
    let tree = read_sph("1 8\n0 0 0 1 1\n0 0 0 -1 1\n0 0 0 -1 1\n", DVec3::ZERO).unwrap();
    assert_eq!(tree.nodes.len(), 1);
}

#[test]
fn empty_file_is_an_error() {
    assert_eq!(format_error("").0, 1);
    assert_eq!(format_error(" \n\n").0, 1);
}

#[test]
fn bad_header_is_an_error() {
    for (text, needle) in [
        ("3\n", "two integers"),
        ("3 8 1\n", "two integers"),
        ("three 8\n", "number of levels"),
        ("3 -8\n", "branching factor"),
        ("2.5 8\n", "number of levels"),
        ("0 8\n", "at least one level"),
        ("3 0\n", "at least 1"),
    ] {
        let (line, message) = format_error(text);
        assert_eq!(line, 1, "{text:?}");
        assert!(message.contains(needle), "{text:?}: {message}");
    }
}

#[test]
fn header_of_a_huge_tree_is_an_error_not_an_allocation() {
    let (line, message) = format_error("40 8\n0 0 0 1 1\n");
    assert_eq!(line, 1);
    assert!(message.contains("more nodes"), "{message}");
    let (line, _) = format_error(&format!("{} 2\n", usize::MAX));
    assert_eq!(line, 1);
}

#[test]
fn non_numeric_field_is_an_error() {
    let (line, message) = format_error("2 1\n0 0 0 1 1\n0 0 x 1 1\n");
    assert_eq!(line, 3);
    assert!(message.contains("field 3"), "{message}");
}

#[test]
fn nan_and_infinite_fields_are_errors() {
    for bad in ["NaN", "inf", "-inf", "infinity"] {
        let (line, message) = format_error(&format!("1 2\n0 0 {bad} 1 1\n"));
        assert_eq!(line, 2);
        assert!(message.contains("not finite"), "{message}");
    }
}

#[test]
fn wrong_field_count_is_an_error() {
    for fields in [
        "0 0 1",
        "0 0 0 1 1 1",
        "0 0 0 1 1 0 0 0 1",
        "0 0 0 1 1 0 0 0 1 1 1",
    ] {
        let (line, message) = format_error(&format!("1 2\n{fields}\n"));
        assert_eq!(line, 2);
        assert!(message.contains("4, 5 or 10 fields"), "{message}");
    }
}

#[test]
fn too_few_lines_is_an_error() {
    let (line, message) = format_error("2 2\n0 0 0 2 1\n1 0 0 1 1\n");
    assert_eq!(line, 4);
    assert!(message.contains("after 2 of the 3 nodes"), "{message}");
}

#[test]
fn too_many_lines_is_an_error() {
    let (line, message) = format_error("2 1\n0 0 0 2 1\n1 0 0 1 1\n1 0 0 1 1\n");
    assert_eq!(line, 4);
    assert!(message.contains("beyond the 2 nodes"), "{message}");
}

#[test]
fn offset_overflow_is_an_error() {
    let text = "1 1\n1e308 0 0 1 1\n";
    assert!(matches!(
        read_sph(text, DVec3::new(1e308, 0.0, 0.0)),
        Err(SphereTreeError::SphSyntax {
            line: 2,
            defect: SphDefect::CentreNotFinite
        })
    ));
}

#[test]
fn writer_rejects_what_the_format_cannot_hold() {
    let good = Some((Sphere::new(DVec3::ZERO, 1.0), 1.0));
    let tree = |levels, branch, nodes| SphFile {
        levels,
        branch,
        nodes,
    };
    assert!(matches!(
        write_sph(&tree(2, 2, vec![good; 2]), DVec3::ZERO),
        Err(SphereTreeError::SphLayout(SphDefect::NodeCount {
            nodes: Some(3),
            found: 2,
            ..
        }))
    ));
    assert!(matches!(
        write_sph(&tree(0, 2, vec![]), DVec3::ZERO),
        Err(SphereTreeError::SphLayout(SphDefect::NoLevel))
    ));
    let zero = Some((Sphere::new(DVec3::ZERO, 0.0), 1.0));
    assert!(matches!(
        write_sph(&tree(2, 1, vec![good, zero]), DVec3::ZERO),
        Err(SphereTreeError::SphLayout(SphDefect::NonPositiveRadius {
            node: 1,
            level: 1,
            radius: 0.0
        }))
    ));
    let nan = Some((Sphere::new(DVec3::new(f64::NAN, 0.0, 0.0), 1.0), 1.0));
    assert!(matches!(
        write_sph(&tree(1, 1, vec![nan]), DVec3::ZERO),
        Err(SphereTreeError::SphLayout(SphDefect::NonFiniteSphere {
            node: 0,
            level: 0
        }))
    ));
    let bad_importance = Some((Sphere::new(DVec3::ZERO, 1.0), f64::INFINITY));
    assert!(matches!(
        write_sph(&tree(1, 1, vec![bad_importance]), DVec3::ZERO),
        Err(SphereTreeError::SphLayout(SphDefect::NonFiniteImportance {
            node: 0,
            ..
        }))
    ));
}

/// A random complete tree of 1 to 3 levels and branching factor 1 to 4.
fn arbitrary_tree() -> impl Strategy<Value = SphFile> {
    (1_usize..=3, 1_usize..=4).prop_flat_map(|(levels, branch)| {
        let count = SphFile::node_count(levels, branch).unwrap_or(1);
        let coordinate = prop_oneof![-1e6..1e6_f64, -1.0..1.0_f64, Just(0.0), Just(-0.0)];
        let node = prop::option::weighted(
            0.8,
            (
                (coordinate.clone(), coordinate.clone(), coordinate),
                prop_oneof![1e-9..1e3_f64, Just(f64::MIN_POSITIVE)],
                prop_oneof![Just(1.0), 0.0..10.0_f64],
            ),
        )
        .prop_map(|n| n.map(|((x, y, z), r, w)| (Sphere::new(DVec3::new(x, y, z), r), w)));
        prop::collection::vec(node, count).prop_map(move |nodes| SphFile {
            levels,
            branch,
            nodes,
        })
    })
}

proptest! {
    #[test]
    fn round_trip_is_exact(tree in arbitrary_tree()) {
        let text = write_sph(&tree, DVec3::ZERO).unwrap();
        let back = read_sph(&text, DVec3::ZERO).unwrap();
        // Exact equality of every number (-0.0 may come back as 0.0: the offset, zero
        // here, is added on reading).
        prop_assert_eq!(back.levels, tree.levels);
        prop_assert_eq!(back.branch, tree.branch);
        prop_assert_eq!(back.nodes.len(), tree.nodes.len());
        for (a, b) in back.nodes.iter().zip(&tree.nodes) {
            match (a, b) {
                (Some((sa, wa)), Some((sb, wb))) => {
                    prop_assert_eq!(sa, sb);
                    prop_assert_eq!(wa.to_bits(), wb.to_bits());
                }
                (None, None) => {}
                _ => prop_assert!(false, "slot changed: {:?} vs {:?}", a, b),
            }
        }
        for level in 0..tree.levels {
            prop_assert_eq!(back.level(level), tree.level(level));
        }
    }

    #[test]
    fn round_trip_with_offset_is_close(tree in arbitrary_tree(), ox in -1e3..1e3_f64) {
        let offset = DVec3::new(ox, -ox, 0.5 * ox);
        let back = read_sph(&write_sph(&tree, offset).unwrap(), offset).unwrap();
        for (a, b) in back.nodes.iter().zip(&tree.nodes) {
            match (a, b) {
                (Some((sa, _)), Some((sb, _))) => {
                    prop_assert!(sa.center.distance(sb.center) <= 1e-9 * (1.0 + sb.center.length() + ox.abs()));
                }
                (None, None) => {}
                _ => prop_assert!(false, "slot changed"),
            }
        }
    }

    #[test]
    fn reader_never_panics(text in "[0-9 .eE+\\-\nNa]{0,200}") {
        let _ = read_sph(&text, DVec3::ZERO);
    }
}
