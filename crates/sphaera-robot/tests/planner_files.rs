//! The complete planner files read back: the cuRobo robot file against the keys and types
//! of cuRobo's documented template (`robot_cfg: kinematics:`), the MJCF against the
//! robot's tree, on the two real robots and on generated arms with mimic, continuous,
//! prismatic, fixed and floating joints.

use std::collections::{BTreeMap, BTreeSet};

use sphaera_robot::{
    CuroboOptions, DisableReason, KinematicChain, MeshResolver, MjcfOptions, RobotSpheres,
    SelfCollisionMatrix, SelfCollisionOptions, SphereBudget, SpherizeOptions, Urdf,
    curobo_robot_yaml, mjcf, spherize,
};
use yaml_rust2::Yaml;

/// A generated robot: a world link, a floating base, a continuous joint, a revolute chain,
/// a prismatic finger and a mimic finger, a fixed flange.
fn generated() -> Urdf {
    let link = |name: &str| {
        format!(
            r#"<link name="{name}"><inertial><origin xyz="0 0 0.05" rpy="0.3 0 0"/><mass value="0.5"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/></inertial><collision><origin xyz="0 0 0.05"/><geometry><box size="0.04 0.04 0.1"/></geometry></collision></link>"#
        )
    };
    let joint = |name: &str, kind: &str, parent: &str, child: &str, extra: &str| {
        format!(
            r#"<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/><origin xyz="0 0 0.11" rpy="0 0.2 0"/><axis xyz="0 1 0"/>{extra}</joint>"#
        )
    };
    let limit = r#"<limit lower="-1" upper="1"/>"#;
    let text = [
        "<robot name=\"generated\"><link name=\"world\"/>".to_owned(),
        link("base"),
        link("turntable"),
        link("upper"),
        link("fore"),
        "<link name=\"flange\"/>".to_owned(),
        link("finger_a"),
        link("finger_b"),
        joint("float", "floating", "world", "base", ""),
        joint("turn", "continuous", "base", "turntable", ""),
        joint("shoulder", "revolute", "turntable", "upper", limit),
        joint("elbow", "revolute", "upper", "fore", limit),
        joint("flange_joint", "fixed", "fore", "flange", ""),
        joint(
            "grip_a",
            "prismatic",
            "flange",
            "finger_a",
            r#"<limit lower="0" upper="0.04"/>"#,
        ),
        joint(
            "grip_b",
            "prismatic",
            "flange",
            "finger_b",
            r#"<limit lower="-0.04" upper="0"/><mimic joint="grip_a" multiplier="-1" offset="0"/>"#,
        ),
        "</robot>".to_owned(),
    ]
    .concat();
    Urdf::parse(&text, "generated.urdf").expect("the generated robot parses")
}

fn spherized(urdf: &Urdf) -> (RobotSpheres, SelfCollisionMatrix) {
    let options = SpherizeOptions::default()
        .with_budget(SphereBudget::PerLink(6))
        .with_self_collision(SelfCollisionOptions::default().with_samples(2_000));
    let robot = spherize(urdf, &MeshResolver::new(urdf.folder()), &options).expect("spherize");
    let matrix = robot.self_collision.clone().expect("the matrix");
    (robot, matrix)
}

fn strings(yaml: &Yaml) -> Vec<String> {
    yaml.as_vec()
        .expect("a list")
        .iter()
        .map(|v| v.as_str().expect("a string").to_owned())
        .collect()
}

fn floats(yaml: &Yaml) -> Vec<f64> {
    yaml.as_vec()
        .expect("a list")
        .iter()
        .map(|v| v.as_f64().expect("a float"))
        .collect()
}

/// The cuRobo file holds every key of cuRobo's template with the right type, and its
/// lists agree with the robot and the matrix.
fn check_curobo(urdf: &Urdf, robot: &RobotSpheres, matrix: &SelfCollisionMatrix) {
    let name = &urdf.name;
    let text = curobo_robot_yaml(urdf, robot, matrix, &CuroboOptions::default()).expect("the file");
    let documents = yaml_rust2::YamlLoader::load_from_str(&text).expect("the YAML parses");
    let k = &documents[0]["robot_cfg"]["kinematics"];
    for key in [
        "use_usd_kinematics",
        "urdf_path",
        "asset_root_path",
        "base_link",
        "ee_link",
        "link_names",
        "lock_joints",
        "extra_links",
        "collision_link_names",
        "collision_spheres",
        "collision_sphere_buffer",
        "extra_collision_spheres",
        "self_collision_ignore",
        "self_collision_buffer",
        "use_global_cumul",
        "mesh_link_names",
        "cspace",
    ] {
        assert!(!k[key].is_badvalue(), "{name}: no {key}");
    }
    assert_eq!(k["base_link"].as_str(), Some(urdf.root().expect("a root")));
    assert!(urdf.link(k["ee_link"].as_str().expect("ee_link")).is_some());
    let links: Vec<String> = robot.links.iter().map(|l| l.link.clone()).collect();
    assert_eq!(strings(&k["collision_link_names"]), links, "{name}");
    let known: BTreeSet<&String> = links.iter().collect();
    for link in &robot.links {
        let list = k["collision_spheres"][link.link.as_str()]
            .as_vec()
            .expect("spheres");
        assert_eq!(list.len(), link.spheres.len(), "{name}: {}", link.link);
    }
    // Every pair left out, once, under the first of its links; nothing else.
    let mut ignored = BTreeSet::new();
    for (first, others) in k["self_collision_ignore"].as_hash().expect("a map") {
        let first = first.as_str().expect("a link").to_owned();
        assert!(known.contains(&first), "{name}: {first}");
        for second in strings(others) {
            assert!(known.contains(&second), "{name}: {second}");
            assert!(ignored.insert((first.clone(), second)), "{name}: twice");
        }
    }
    let expected: BTreeSet<(String, String)> = matrix
        .disabled()
        .map(|p| (p.first.clone(), p.second.clone()))
        .collect();
    assert_eq!(ignored, expected, "{name}");
    let buffers = k["self_collision_buffer"].as_hash().expect("a map");
    assert_eq!(buffers.len(), links.len(), "{name}");
    // The joint space: one name, retract value and weight per active joint, the retract
    // configuration within the limits, the locked joints among them.
    let chain = KinematicChain::new(urdf).expect("the chain");
    let cspace = &k["cspace"];
    let joints = strings(&cspace["joint_names"]);
    let active: Vec<String> = chain.joints().iter().map(|j| j.name.clone()).collect();
    assert_eq!(joints, active, "{name}");
    let retract = floats(&cspace["retract_config"]);
    assert_eq!(retract.len(), joints.len());
    for (j, v) in chain.joints().iter().zip(&retract) {
        assert!(j.lower <= *v && *v <= j.upper, "{name}: {} {v}", j.name);
    }
    for key in ["null_space_weight", "cspace_distance_weight"] {
        assert_eq!(floats(&cspace[key]).len(), joints.len(), "{name}: {key}");
    }
    assert!(cspace["max_jerk"].as_f64().is_some() && cspace["max_acceleration"].as_f64().is_some());
    if let Some(locked) = k["lock_joints"].as_hash() {
        for (joint, value) in locked {
            assert!(
                joints.contains(&joint.as_str().expect("a joint").to_owned()),
                "{name}"
            );
            assert!(value.as_f64().is_some(), "{name}");
        }
    }
}

/// The MJCF: one body per link (a bare root is the world), one joint per moving URDF joint,
/// a sphere geom per sphere, an exclusion per pair left out, an equality per mimic.
fn check_mjcf(urdf: &Urdf, robot: &RobotSpheres, matrix: &SelfCollisionMatrix) {
    let name = &urdf.name;
    let text = mjcf(urdf, robot, matrix, &MjcfOptions::default()).expect("the MJCF");
    let document = roxmltree::Document::parse(&text).expect("the XML parses");
    let count = |tag: &str| {
        document
            .descendants()
            .filter(|n| n.has_tag_name(tag))
            .count()
    };
    let root = urdf.root().expect("a root");
    let bare_root =
        robot.link(root).is_none() && urdf.link(root).is_some_and(|l| l.inertial.is_none());
    assert_eq!(
        count("body"),
        urdf.links.len() - usize::from(bare_root),
        "{name}"
    );
    let moving = urdf
        .joints
        .iter()
        .filter(|j| {
            matches!(
                j.kind,
                sphaera_robot::JointKind::Revolute
                    | sphaera_robot::JointKind::Continuous
                    | sphaera_robot::JointKind::Prismatic
            )
        })
        .count();
    let joints: Vec<_> = document
        .descendants()
        .filter(|n| n.has_tag_name("joint") && n.parent().is_some_and(|p| p.has_tag_name("body")))
        .collect();
    assert_eq!(joints.len(), moving, "{name}");
    let spheres = document
        .descendants()
        .filter(|n| n.attribute("type") == Some("sphere"))
        .count();
    assert_eq!(spheres, robot.sphere_count(), "{name}");
    assert_eq!(count("exclude"), matrix.disabled().count(), "{name}");
    let mimics = urdf.joints.iter().filter(|j| j.mimic.is_some()).count();
    assert_eq!(
        document
            .descendants()
            .filter(|n| n.has_attribute("polycoef"))
            .count(),
        mimics,
        "{name}"
    );
    // Every body under its URDF parent.
    let parents: BTreeMap<&str, &str> = urdf
        .joints
        .iter()
        .map(|j| (j.child.as_str(), j.parent.as_str()))
        .collect();
    for body in document.descendants().filter(|n| n.has_tag_name("body")) {
        let link = body.attribute("name").expect("a name");
        let parent = body.parent().and_then(|p| p.attribute("name"));
        match parents.get(link) {
            Some(&p) if !(bare_root && p == root) => assert_eq!(parent, Some(p), "{name}: {link}"),
            _ => assert!(
                body.parent().is_some_and(|p| p.has_tag_name("worldbody")),
                "{name}: {link}"
            ),
        }
    }
}

#[test]
fn the_generated_robot_writes_complete_files() {
    let urdf = generated();
    let (robot, matrix) = spherized(&urdf);
    check_curobo(&urdf, &robot, &matrix);
    check_mjcf(&urdf, &robot, &matrix);
    // The floating base is a free body of the world; the fingers are locked below the
    // flange's parent, where the main chain ends.
    let text = mjcf(&urdf, &robot, &matrix, &MjcfOptions::default()).unwrap();
    assert!(text.contains("<freejoint/>"));
    let yaml = curobo_robot_yaml(&urdf, &robot, &matrix, &CuroboOptions::default()).unwrap();
    assert!(yaml.contains("    ee_link: \"flange\"\n"), "{yaml}");
    assert!(yaml.contains("lock_joints: {\"grip_a\": 0.0}"), "{yaml}");
    assert_eq!(matrix.count(DisableReason::Adjacent), 6, "{matrix:?}");
}

#[test]
fn the_real_robots_write_complete_files() {
    for (_, path) in sphaera_tests::robot_urdfs("the_real_robots_write_complete_files") {
        let urdf = Urdf::read(&path).expect("the URDF reads");
        let (robot, matrix) = spherized(&urdf);
        check_curobo(&urdf, &robot, &matrix);
        check_mjcf(&urdf, &robot, &matrix);
    }
}

#[test]
fn an_unknown_end_effector_is_refused() {
    let urdf = generated();
    let (robot, matrix) = spherized(&urdf);
    let error = curobo_robot_yaml(
        &urdf,
        &robot,
        &matrix,
        &CuroboOptions::default().with_ee_link("hand"),
    )
    .unwrap_err();
    assert!(error.to_string().contains("\"hand\""), "{error}");
}

/// A robot of one link has no pair: an empty matrix, an empty ignore map in the cuRobo file
/// (a YAML map, not nothing), no joint space, no `<contact>` in the MJCF; all still parse.
#[test]
fn a_one_link_robot_has_an_empty_matrix_and_valid_files() {
    let urdf = Urdf::parse(
        r#"<robot name="one"><link name="only"><collision><geometry><sphere radius="0.1"/></geometry></collision></link></robot>"#,
        "one.urdf",
    )
    .unwrap();
    let (robot, matrix) = spherized(&urdf);
    assert!(matrix.pairs.is_empty());
    let yaml = curobo_robot_yaml(&urdf, &robot, &matrix, &CuroboOptions::default()).unwrap();
    let documents = yaml_rust2::YamlLoader::load_from_str(&yaml).expect("the YAML parses");
    let k = &documents[0]["robot_cfg"]["kinematics"];
    assert!(
        k["self_collision_ignore"]
            .as_hash()
            .is_some_and(yaml_rust2::yaml::Hash::is_empty),
        "{yaml}"
    );
    assert_eq!(k["ee_link"].as_str(), Some("only"));
    assert!(
        k["cspace"]["joint_names"]
            .as_vec()
            .is_some_and(Vec::is_empty),
        "{yaml}"
    );
    let text = mjcf(&urdf, &robot, &matrix, &MjcfOptions::default()).unwrap();
    roxmltree::Document::parse(&text).expect("the MJCF parses");
    assert!(!text.contains("<contact>") && text.contains("<body name=\"only\">"));
}
