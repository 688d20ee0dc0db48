//! The two real robots (Franka Panda, KUKA iiwa): every output format read back with an
//! XML, a YAML and a JSON parser; the spheres moved by forward kinematics cover the posed
//! collision meshes at several joint configurations (an independent dense check); frames
//! right (budgets and tolerances: `budgets.rs`).

#![allow(clippy::float_cmp)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use glam::{DAffine3, DQuat, DVec3, EulerRot};
use sphaera_robot::{
    Geometry, GeometrySource, MeshResolver, PlannerFormat, RobotSpheres, Sphere, SphereBudget,
    SpherizeOptions, Urdf, spherize,
};
use sphaera_tests::SplitMix64;

fn robot_path(name: &str, test: &str) -> Option<PathBuf> {
    let data = sphaera_tests::data_dir(test)?;
    let dir = data.join(sphaera_tests::URDF_ASSETS);
    Some(match name {
        "panda" => dir.join("franka_panda/panda.urdf"),
        _ => dir.join("kuka_iiwa/model.urdf"),
    })
}

fn spheres_of(path: &Path, budget: SphereBudget) -> (Urdf, RobotSpheres) {
    let urdf = Urdf::read(path).expect("the URDF reads");
    let options = SpherizeOptions::default().with_budget(budget);
    let robot = spherize(&urdf, &MeshResolver::new(urdf.folder()), &options).expect("spherize");
    (urdf, robot)
}

/// The element's placement computed here, independently of the crate: URDF's fixed-axis
/// roll, pitch, yaw are intrinsic z-y'-x'' Euler angles.
fn element_pose(xyz: DVec3, rpy: DVec3) -> DAffine3 {
    DAffine3::from_rotation_translation(DQuat::from_euler(EulerRot::ZYX, rpy.z, rpy.y, rpy.x), xyz)
}

/// Dense points of every collision mesh of `link`, in the link's frame: the vertices and
/// random surface samples, each mesh loaded from its file and placed here.
fn link_points(urdf: &Urdf, link: &str) -> Vec<DVec3> {
    let link = urdf.link(link).expect("a link");
    let mut points = Vec::new();
    for element in &link.collisions {
        let Geometry::Mesh { filename, scale } = &element.geometry else {
            continue;
        };
        let relative = filename.strip_prefix("package://").unwrap_or(filename);
        let mesh = sphaera_io::load(urdf.folder().join(relative)).expect("the mesh loads");
        let pose = element_pose(element.origin.xyz, element.origin.rpy);
        let samples = sphaera_query::sampling::random(&mesh, 4_000, 7).expect("samples");
        points.extend(
            mesh.positions()
                .iter()
                .copied()
                .chain(samples.iter().map(|s| s.position))
                .map(|p| pose.transform_point3(p * *scale)),
        );
    }
    points
}

fn covered(spheres: &[Sphere], p: DVec3) -> bool {
    spheres
        .iter()
        .any(|s| s.center.distance(p) <= s.radius * (1.0 + 1e-9) + 1e-12)
}

#[test]
fn posed_spheres_cover_the_posed_robot_at_any_configuration() {
    for name in ["panda", "kuka"] {
        let Some(path) = robot_path(name, "posed_spheres_cover_the_posed_robot") else {
            return;
        };
        let (urdf, robot) = spheres_of(&path, SphereBudget::PerLink(12));
        let mut random = SplitMix64::new(5);
        let mut configurations = vec![BTreeMap::new()];
        for _ in 0..3 {
            let q: BTreeMap<String, f64> = urdf
                .joints
                .iter()
                .filter(|j| j.mimic.is_none())
                .map(|j| {
                    let (lo, hi) = j.limits.unwrap_or((-3.0, 3.0));
                    (j.name.clone(), random.range(lo, hi.max(lo)))
                })
                .collect();
            configurations.push(q);
        }
        for q in &configurations {
            let poses = urdf.link_poses(q).expect("forward kinematics");
            for link in &robot.links {
                let pose = poses[&link.link];
                let posed: Vec<Sphere> = link
                    .spheres
                    .iter()
                    .map(|s| Sphere::new(pose.transform_point3(s.center), s.radius))
                    .collect();
                let points = link_points(&urdf, &link.link);
                assert!(!points.is_empty(), "{name} {}", link.link);
                for p in points {
                    let p = pose.transform_point3(p);
                    assert!(
                        covered(&posed, p),
                        "{name} {} at {q:?}: {p} uncovered",
                        link.link
                    );
                }
            }
        }
        // Every link has exactly its budget; the links without collision meshes are
        // listed.
        assert!(robot.links.iter().all(|l| l.spheres.len() == 12));
        if name == "panda" {
            assert_eq!(robot.links.len(), 11);
            assert_eq!(
                robot.links_without_geometry,
                ["panda_link8", "panda_grasptarget"]
            );
        }
    }
}

#[test]
fn every_format_reads_back_with_the_same_spheres() {
    let Some(path) = robot_path("panda", "every_format_reads_back") else {
        return;
    };
    let (urdf, robot) = spheres_of(&path, SphereBudget::PerLink(6));
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + a.abs());

    // SRDF, with an XML parser.
    let srdf = PlannerFormat::Srdf.render(&urdf, &robot).expect("srdf");
    let document = roxmltree::Document::parse(&srdf).expect("the SRDF is XML");
    let approximations: Vec<_> = document
        .descendants()
        .filter(|n| n.has_tag_name("link_sphere_approximation"))
        .collect();
    assert_eq!(approximations.len(), robot.links.len());
    for (node, link) in approximations.iter().zip(&robot.links) {
        assert_eq!(node.attribute("link"), Some(link.link.as_str()));
        let spheres: Vec<_> = node
            .children()
            .filter(|n| n.has_tag_name("sphere"))
            .collect();
        assert_eq!(spheres.len(), link.spheres.len());
        for (s, expected) in spheres.iter().zip(&link.spheres) {
            let center: Vec<f64> = s
                .attribute("center")
                .expect("center")
                .split_whitespace()
                .map(|v| v.parse().expect("a number"))
                .collect();
            let radius: f64 = s
                .attribute("radius")
                .expect("radius")
                .parse()
                .expect("a number");
            assert_eq!(DVec3::from_slice(&center), expected.center);
            assert_eq!(radius, expected.radius);
        }
    }

    // The spherized URDF, with our reader and an XML parser: every spherized link's
    // collisions are its spheres, everything else is as it was.
    let spherized = PlannerFormat::Urdf.render(&urdf, &robot).expect("urdf");
    assert!(roxmltree::Document::parse(&spherized).is_ok());
    let back = Urdf::parse(&spherized, &urdf.path).expect("the spherized URDF reads");
    let unlined = |joints: &[sphaera_robot::Joint]| {
        joints
            .iter()
            .map(|j| sphaera_robot::Joint {
                line: 0,
                ..j.clone()
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(unlined(&back.joints), unlined(&urdf.joints));
    for link in &robot.links {
        let read = back.link(&link.link).expect("the link");
        assert_eq!(read.collisions.len(), link.spheres.len(), "{}", link.link);
        for (element, s) in read.collisions.iter().zip(&link.spheres) {
            assert_eq!(element.origin.xyz, s.center);
            assert_eq!(element.geometry, Geometry::Sphere { radius: s.radius });
        }
        let original = urdf.link(&link.link).expect("link");
        let placed = |elements: &[sphaera_robot::Element]| {
            elements
                .iter()
                .map(|e| (e.origin, e.geometry.clone()))
                .collect::<Vec<_>>()
        };
        assert_eq!(placed(&read.visuals), placed(&original.visuals));
    }

    // cuRobo's YAML, with a YAML parser.
    let yaml = PlannerFormat::CuroboSpheres
        .render(&urdf, &robot)
        .expect("yaml");
    let documents = yaml_rust2::YamlLoader::load_from_str(&yaml).expect("the YAML parses");
    let spheres = &documents[0]["collision_spheres"];
    for link in &robot.links {
        let list = spheres[link.link.as_str()]
            .as_vec()
            .expect("a list per link");
        assert_eq!(list.len(), link.spheres.len());
        for (entry, expected) in list.iter().zip(&link.spheres) {
            let center: Vec<f64> = entry["center"]
                .as_vec()
                .expect("center")
                .iter()
                .map(|v| v.as_f64().expect("a float"))
                .collect();
            assert_eq!(DVec3::from_slice(&center), expected.center);
            assert!(close(
                entry["radius"].as_f64().expect("radius"),
                expected.radius
            ));
        }
    }

    // JSON.
    let json: serde_json::Value =
        serde_json::from_str(&PlannerFormat::Json.render(&urdf, &robot).expect("json"))
            .expect("the JSON parses");
    assert_eq!(json["robot"], "panda");
    let links = json["links"].as_array().expect("links");
    assert_eq!(links.len(), robot.links.len());
    for (entry, link) in links.iter().zip(&robot.links) {
        assert_eq!(entry["link"], link.link.as_str());
        let levels: Vec<Vec<(Sphere, Option<[usize; 2]>)>> = entry["levels"]
            .as_array()
            .expect("levels")
            .iter()
            .map(|level| {
                level
                    .as_array()
                    .expect("a level")
                    .iter()
                    .map(|s| {
                        let c = &s["center"];
                        let at = |k: usize| c[k].as_f64().expect("a coordinate");
                        let sphere = Sphere::new(
                            DVec3::new(at(0), at(1), at(2)),
                            s["radius"].as_f64().expect("radius"),
                        );
                        let children = s
                            .get("children")
                            .map(|r| [0, 1].map(|k| r[k].as_u64().expect("an index") as usize));
                        (sphere, children)
                    })
                    .collect()
            })
            .collect();
        // The bounding sphere, groups when there are more than eight spheres, then the
        // spheres themselves, in some order.
        assert_eq!(levels[0].len(), 1);
        assert_eq!(levels.len(), if link.spheres.len() > 8 { 3 } else { 2 });
        let last = levels.last().expect("the spheres");
        assert!(last.iter().all(|(_, c)| c.is_none()));
        let key = |s: &Sphere| (s.center.to_array().map(f64::to_bits), s.radius.to_bits());
        let mut written: Vec<_> = last.iter().map(|(s, _)| key(s)).collect();
        let mut spheres: Vec<_> = link.spheres.iter().map(key).collect();
        written.sort_unstable();
        spheres.sort_unstable();
        assert_eq!(written, spheres);
        // Each level's children ranges tile the next level, and every sphere encloses its
        // children (brute force).
        for pair in levels.windows(2) {
            let mut next = 0;
            for (parent, children) in &pair[0] {
                let [first, end] = children.expect("children");
                assert!(first == next && end > first && end <= pair[1].len());
                next = end;
                for (child, _) in &pair[1][first..end] {
                    // Exactly: every radius is computed so.
                    assert!(
                        parent.center.distance(child.center) + child.radius <= parent.radius,
                        "{}: a child sticks out of its parent",
                        link.link
                    );
                }
            }
            assert_eq!(next, pair[1].len());
        }
        assert_eq!(entry["report"]["spheres"], link.spheres.len());
    }
}

/// A mesh placed by a rotated origin and a scale: every vertex placed independently lies
/// in the link's spheres, and the spheres sit on the placed mesh, not on the file's.
#[test]
fn frames_are_right() {
    let dir = tempfile::tempdir().expect("a folder");
    let mesh = sphaera_mesh::shapes::capsule(0.05, 0.3, 10).expect("capsule");
    sphaera_io::save(dir.path().join("rod.obj"), &mesh).expect("write");
    let (xyz, rpy, scale) = (
        DVec3::new(0.4, -0.2, 0.3),
        DVec3::new(0.3, -0.5, 1.2),
        DVec3::new(1.0, 2.0, 0.5),
    );
    let text = format!(
        r#"<robot name="r"><link name="arm"><collision>
             <origin xyz="{} {} {}" rpy="{} {} {}"/>
             <geometry><mesh filename="rod.obj" scale="{} {} {}"/></geometry>
           </collision></link></robot>"#,
        xyz.x, xyz.y, xyz.z, rpy.x, rpy.y, rpy.z, scale.x, scale.y, scale.z
    );
    let path = dir.path().join("r.urdf");
    std::fs::write(&path, text).expect("write");
    let (_, robot) = spheres_of(&path, SphereBudget::PerLink(10));
    let link = &robot.links[0];
    let pose = element_pose(xyz, rpy);
    let placed: Vec<DVec3> = mesh
        .positions()
        .iter()
        .map(|&p| pose.transform_point3(p * scale))
        .collect();
    for &p in &placed {
        assert!(covered(&link.spheres, p), "{p} uncovered");
    }
    let center = placed.iter().copied().sum::<DVec3>() / placed.len() as f64;
    assert!(
        link.bounding_sphere.center.distance(center) < 0.05,
        "{} against {center}",
        link.bounding_sphere.center
    );
    assert!(link.bounding_sphere.center.distance(DVec3::ZERO) > 0.3);
}

/// Visual geometry: the Panda's visual meshes, finer than the collision ones.
#[test]
fn visual_geometry_is_spherized_on_request() {
    let Some(path) = robot_path("panda", "visual_geometry") else {
        return;
    };
    let urdf = Urdf::read(&path).expect("read");
    let options = SpherizeOptions::default()
        .with_budget(SphereBudget::PerLink(4))
        .with_source(GeometrySource::Visual);
    let robot = spherize(&urdf, &MeshResolver::new(urdf.folder()), &options).expect("visual");
    let link1 = robot.link("panda_link1").expect("link1");
    assert!(
        link1.report.files[0].contains("visual"),
        "{:?}",
        link1.report.files
    );
    assert!(link1.report.triangles > 10_000);
}
