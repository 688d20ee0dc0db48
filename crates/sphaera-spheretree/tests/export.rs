//! Exports: JSON round trips and validation errors, the YAML collision-sphere list read
//! back by a tiny reader, the parry compound (with the `parry` feature).

mod common;

use common::small_tree;
use std::sync::OnceLock;

use proptest::prelude::*;
use serde_json::Value;
use sphaera_mesh::{DVec3, Sphere, shapes};
use sphaera_spheretree::export::{
    CollisionLink, TreeFormat, TreeJson, collision_spheres_yaml, tree_from_json, tree_to_json,
    tree_to_text, write_collision_spheres_yaml, write_tree, write_tree_json,
};
use sphaera_spheretree::select::cut_for_tolerance;
use sphaera_spheretree::{SphereTree, SphereTreeError};

fn tree() -> &'static SphereTree {
    static TREE: OnceLock<SphereTree> = OnceLock::new();
    TREE.get_or_init(|| small_tree(&shapes::capsule(0.5, 2.0, 10).unwrap()))
}

#[test]
fn json_round_trip_is_exact() {
    let tree = tree();
    let text = tree_to_json(tree);
    assert_eq!(&tree_from_json(&text).unwrap(), tree);
    // Stable field names.
    let value: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(value["format"], "sphaera-spheretree");
    assert_eq!(value["version"], 1);
    assert_eq!(value["branch"], 4);
    assert_eq!(value["levels"].as_array().unwrap().len(), 3);
    let root = &value["nodes"][0];
    for key in [
        "center",
        "radius",
        "error",
        "level",
        "parent",
        "children",
        "region_samples",
    ] {
        assert!(root.get(key).is_some(), "{key}");
    }
    assert!(root["parent"].is_null());
    let mut written = Vec::new();
    write_tree_json(&mut written, tree).unwrap();
    assert_eq!(
        &tree_from_json(std::str::from_utf8(&written).unwrap()).unwrap(),
        tree
    );
    for format in [TreeFormat::Json, TreeFormat::Sph, TreeFormat::Yaml] {
        let mut written = Vec::new();
        write_tree(&mut written, tree, format, "capsule").unwrap();
        assert_eq!(
            std::str::from_utf8(&written).unwrap(),
            tree_to_text(tree, format, "capsule").unwrap()
        );
    }
}

/// Edits the JSON of the test tree and reads it back.
fn read_edited(edit: impl FnOnce(&mut Value)) -> Result<SphereTree, SphereTreeError> {
    let mut value: Value = serde_json::from_str(&tree_to_json(tree())).unwrap();
    edit(&mut value);
    tree_from_json(&value.to_string())
}

fn invalid_tree(result: Result<SphereTree, SphereTreeError>, needle: &str) {
    match result {
        Err(SphereTreeError::InvalidTree(defect)) => {
            let message = defect.to_string();
            assert!(message.contains(needle), "{message:?} lacks {needle:?}");
        }
        other => panic!("expected an invalid tree ({needle}), got {other:?}"),
    }
}

#[test]
fn malformed_json_is_a_format_error_with_its_line() {
    let text = tree_to_json(tree());
    let cut = &text[..text.len() / 2];
    // The parser stops at the end: on the line after the last when the cut ends one.
    let lines = cut.lines().count() + usize::from(cut.ends_with('\n'));
    match tree_from_json(cut) {
        Err(SphereTreeError::Json { line, .. }) => assert_eq!(line, lines),
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        tree_from_json(""),
        Err(SphereTreeError::Json { .. })
    ));
    assert!(matches!(
        tree_from_json("[]"),
        Err(SphereTreeError::Json { .. })
    ));
    // A missing field, a wrong type, a NaN written as null.
    assert!(matches!(
        read_edited(|v| {
            v.as_object_mut().unwrap().remove("branch");
        }),
        Err(SphereTreeError::Json { .. })
    ));
    assert!(matches!(
        read_edited(|v| v["nodes"][1]["radius"] = Value::Null),
        Err(SphereTreeError::Json { .. })
    ));
    assert!(matches!(
        read_edited(|v| v["nodes"][0]["center"] = serde_json::json!([0, 0])),
        Err(SphereTreeError::Json { .. })
    ));
}

#[test]
fn inconsistent_trees_are_named_errors() {
    invalid_tree(read_edited(|v| v["format"] = "other".into()), "format");
    invalid_tree(read_edited(|v| v["version"] = 2.into()), "version 2");
    invalid_tree(read_edited(|v| v["branch"] = 0.into()), "branch");
    invalid_tree(
        read_edited(|v| v["branch"] = 1.into()),
        "more than the branching factor",
    );
    invalid_tree(
        read_edited(|v| v["nodes"] = serde_json::json!([])),
        "no nodes",
    );
    invalid_tree(
        read_edited(|v| v["levels"][0]["count"] = 2.into()),
        "level 0",
    );
    invalid_tree(
        read_edited(|v| v["levels"][1]["first"] = 2.into()),
        "level 1 starts",
    );
    invalid_tree(
        read_edited(|v| {
            v["levels"].as_array_mut().unwrap().pop();
        }),
        "the levels hold",
    );
    invalid_tree(
        read_edited(|v| v["nodes"][1]["level"] = 2.into()),
        "node 1: level is 2",
    );
    invalid_tree(
        read_edited(|v| v["nodes"][1]["parent"] = 1.into()),
        "node 0: child 1 does not name it as its parent",
    );
    invalid_tree(
        read_edited(|v| {
            let last = v["nodes"][0]["children"]
                .as_array_mut()
                .unwrap()
                .pop()
                .unwrap();
            let last = last.as_u64().unwrap() as usize;
            v["nodes"][last]["parent"] = last.into();
        }),
        "parent",
    );
    invalid_tree(
        read_edited(|v| {
            let last = v["nodes"][0]["children"]
                .as_array_mut()
                .unwrap()
                .pop()
                .unwrap();
            let last = last.as_u64().unwrap() as usize;
            v["nodes"][last]["parent"] = 0.into();
        }),
        "parent 0 does not list it as a child",
    );
    invalid_tree(
        read_edited(|v| {
            let last = v["nodes"][0]["children"]
                .as_array_mut()
                .unwrap()
                .pop()
                .unwrap();
            v["nodes"][last.as_u64().unwrap() as usize]["parent"] = Value::Null;
        }),
        "only the root",
    );
    invalid_tree(
        read_edited(|v| v["nodes"][0]["parent"] = 0.into()),
        "the root cannot",
    );
    invalid_tree(
        read_edited(|v| {
            let kids = v["nodes"][0]["children"].as_array_mut().unwrap();
            kids.reverse();
        }),
        "consecutive",
    );
    invalid_tree(
        read_edited(|v| {
            let first = v["levels"][2]["first"].as_u64().unwrap();
            v["nodes"][0]["children"] = serde_json::json!([first]);
        }),
        "node 0: child",
    );
    invalid_tree(
        read_edited(|v| v["levels"][1]["worst_error"] = 1e9.into()),
        "worst_error",
    );
    assert!(matches!(
        read_edited(|v| v["nodes"][2]["radius"] = (-1.0).into()),
        Err(SphereTreeError::InvalidSphere { index: 2 })
    ));
}

/// A tiny reader of the YAML shape `collision_spheres_yaml` writes: link name lines,
/// `- center: [x, y, z]` lines and `radius: r` lines.
fn read_yaml(text: &str) -> Vec<(String, Vec<Sphere>)> {
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    if header == "collision_spheres: {}" {
        return Vec::new();
    }
    assert_eq!(header, "collision_spheres:");
    let mut links: Vec<(String, Vec<Sphere>)> = Vec::new();
    let mut center = None;
    for line in lines {
        if let Some(rest) = line.strip_prefix("    - center: [") {
            let numbers: Vec<f64> = rest
                .trim_end_matches(']')
                .split(", ")
                .map(|x| x.parse().unwrap())
                .collect();
            assert_eq!(numbers.len(), 3, "{line}");
            center = Some(DVec3::new(numbers[0], numbers[1], numbers[2]));
        } else if let Some(rest) = line.strip_prefix("      radius: ") {
            let radius = rest.parse().unwrap();
            let c = center.take().expect("a radius follows a center");
            links.last_mut().unwrap().1.push(Sphere::new(c, radius));
        } else if let Some(rest) = line.strip_prefix("  ") {
            assert!(!rest.starts_with(' '), "{line}");
            let name = rest
                .strip_suffix(": []")
                .or_else(|| rest.strip_suffix(':'))
                .expect("a link line ends with ':' or ': []'");
            let name: String = serde_json::from_str(name).unwrap();
            links.push((name, Vec::new()));
        } else {
            panic!("unexpected line {line:?}");
        }
    }
    assert!(center.is_none());
    links
}

#[test]
fn yaml_lists_the_spheres_of_a_level_and_a_cut_per_link() {
    let tree = tree();
    let cut = cut_for_tolerance(tree, tree.level(1)[0].error);
    let links = [
        CollisionLink::from_level("panda_link0", tree, 2),
        CollisionLink::from_cut("link \"1\": ü", tree, &cut),
        CollisionLink::new("empty", vec![]),
    ];
    let yaml = collision_spheres_yaml(&links).unwrap();
    assert!(yaml.starts_with("collision_spheres:\n  \"panda_link0\":\n    - center: ["));
    assert!(yaml.contains("  \"empty\": []\n"));
    let read = read_yaml(&yaml);
    assert_eq!(read.len(), 3);
    for (link, (name, spheres)) in links.iter().zip(&read) {
        assert_eq!(&link.name, name);
        assert_eq!(&link.spheres, spheres);
    }
    let mut written = Vec::new();
    write_collision_spheres_yaml(&mut written, &links).unwrap();
    assert_eq!(std::str::from_utf8(&written).unwrap(), yaml);
}

#[test]
fn yaml_refuses_duplicate_names_and_invalid_spheres() {
    let s = Sphere::new(DVec3::ZERO, 1.0);
    let twice = [
        CollisionLink::new("a", vec![s]),
        CollisionLink::new("a", vec![]),
    ];
    assert!(matches!(
        collision_spheres_yaml(&twice),
        Err(SphereTreeError::DuplicateLink { name }) if name == "a"
    ));
    let bad = [
        CollisionLink::new("a", vec![s]),
        CollisionLink::new("b", vec![s, Sphere::new(DVec3::ZERO, f64::NAN)]),
    ];
    assert!(matches!(
        collision_spheres_yaml(&bad),
        Err(SphereTreeError::InvalidSphere { index: 2 })
    ));
    assert_eq!(
        collision_spheres_yaml(&[]).unwrap(),
        "collision_spheres: {}\n"
    );
    assert!(read_yaml("collision_spheres: {}\n").is_empty());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    #[test]
    fn yaml_numbers_read_back_exactly(
        values in prop::collection::vec(
            (-1e6..1e6_f64, -1e-9..1e-9_f64, 1e15..1e25_f64, 0.0..1e-6_f64), 1..6),
    ) {
        let spheres: Vec<Sphere> = values
            .iter()
            .map(|&(x, y, z, r)| Sphere::new(DVec3::new(x, y, z), r))
            .collect();
        let yaml = collision_spheres_yaml(&[CollisionLink::new("l", spheres.clone())]).unwrap();
        // Every number has a decimal point (YAML 1.1 readers need it for a float).
        for line in yaml.lines().skip(2) {
            let numbers = line.trim_start_matches([' ', '-']).trim_start_matches("center: [")
                .trim_start_matches("radius: ").trim_end_matches(']');
            for n in numbers.split(", ") {
                prop_assert!(n.contains('.'), "{}", n);
            }
        }
        prop_assert_eq!(&read_yaml(&yaml)[0].1, &spheres);
    }

    #[test]
    fn json_round_trip_of_edited_numbers_is_exact(scale in 1e-6..1e6_f64) {
        let tree = tree();
        let mut json = TreeJson::from_tree(tree);
        for node in &mut json.nodes {
            node.center = node.center.map(|c| c * scale);
            node.radius *= scale;
        }
        let text = serde_json::to_string(&json).unwrap();
        let back: TreeJson = serde_json::from_str(&text).unwrap();
        prop_assert_eq!(&back, &json);
        prop_assert!(back.to_tree().is_ok());
    }
}

#[cfg(feature = "parry")]
#[test]
fn parry_compound_holds_the_spheres() {
    use parry3d_f64::math::Pose;
    use parry3d_f64::query::PointQuery;
    use sphaera_spheretree::export::to_parry_compound;

    let spheres = tree().level_spheres(2);
    let compound = to_parry_compound(&spheres).unwrap();
    assert_eq!(compound.shapes().len(), spheres.len());
    for ((pose, shape), s) in compound.shapes().iter().zip(&spheres) {
        assert_eq!(pose.translation, s.center);
        assert_eq!(shape.as_ball().map(|b| b.radius), Some(s.radius));
        // The compound contains points just inside each sphere, not just outside the
        // union.
        let inside = s.center + DVec3::X * (s.radius * 0.99);
        assert!(compound.contains_point(&Pose::IDENTITY, inside));
    }
    let far = DVec3::splat(100.0);
    assert!(!compound.contains_point(&Pose::IDENTITY, far));
    assert!(matches!(
        to_parry_compound(&[]),
        Err(SphereTreeError::EmptySphereSet)
    ));
    assert!(matches!(
        to_parry_compound(&[Sphere::new(DVec3::ZERO, -1.0)]),
        Err(SphereTreeError::InvalidSphere { index: 0 })
    ));
}
