//! Where a URDF must not fail: every broken input is a clear error naming the link and
//! the file (or the line), or the right answer.

#![allow(clippy::float_cmp)]

use std::path::Path;

use sphaera_io::FilePolicy;
use sphaera_robot::{
    Geometry, GeometrySource, LinkGeometry, MeshResolver, RobotError, SphereBudget,
    SpherizeOptions, Urdf, spherize,
};

/// A small closed box mesh as OBJ text, `scale` times a 0.2 × 0.1 × 0.05 box.
fn box_obj(scale: f64) -> String {
    let mesh = sphaera_mesh::shapes::cube(1.0, 2).expect("cube");
    let mut text = String::new();
    for p in mesh.positions() {
        let q = p * glam::DVec3::new(0.2, 0.1, 0.05) * scale;
        text.push_str(&format!("v {} {} {}\n", q.x, q.y, q.z));
    }
    for t in mesh.triangles() {
        text.push_str(&format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1));
    }
    text
}

fn robot(link_body: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
<robot name="test">
  <link name="base">
    {link_body}
  </link>
</robot>
"#
    )
}

fn mesh_collision(filename: &str, scale: Option<&str>) -> String {
    let scale = scale.map_or(String::new(), |s| format!(" scale=\"{s}\""));
    format!(r#"<collision><geometry><mesh filename="{filename}"{scale}/></geometry></collision>"#)
}

fn options() -> SpherizeOptions {
    SpherizeOptions::default().with_budget(SphereBudget::PerLink(8))
}

fn run(dir: &Path, urdf_text: &str) -> Result<sphaera_robot::RobotSpheres, RobotError> {
    let path = dir.join("robot.urdf");
    std::fs::write(&path, urdf_text).expect("write the URDF");
    let urdf = Urdf::read(&path)?;
    spherize(&urdf, &MeshResolver::new(urdf.folder()), &options())
}

#[test]
fn a_missing_mesh_file_names_the_link_the_file_and_every_path_tried() {
    let dir = tempfile::tempdir().expect("a folder");
    let error =
        run(dir.path(), &robot(&mesh_collision("meshes/gone.stl", None))).expect_err("missing");
    let message = error.to_string();
    assert!(
        matches!(error, RobotError::MeshNotFound { .. }),
        "{message}"
    );
    assert!(
        message.contains("\"base\"") && message.contains("meshes/gone.stl"),
        "{message}"
    );
}

#[test]
fn a_package_path_that_resolves_nowhere_lists_what_was_tried() {
    let dir = tempfile::tempdir().expect("a folder");
    let error = run(
        dir.path(),
        &robot(&mesh_collision("package://my_robot/meshes/base.obj", None)),
    )
    .expect_err("nowhere");
    let RobotError::MeshNotFound { tried, uri, link } = &error else {
        panic!("{error}");
    };
    assert_eq!(
        (link.as_str(), uri.as_str()),
        ("base", "package://my_robot/meshes/base.obj")
    );
    assert!(tried.len() >= 2, "{tried:?}");
    assert!(error.to_string().contains("my_robot/meshes/base.obj"));
    // Given the package's folder, it resolves.
    let package = dir.path().join("pkg");
    std::fs::create_dir_all(package.join("meshes")).expect("mkdir");
    std::fs::write(package.join("meshes/base.obj"), box_obj(1.0)).expect("write");
    let path = dir.path().join("robot.urdf");
    let urdf = Urdf::read(&path).expect("read");
    let resolver = MeshResolver::new(urdf.folder()).with_package("my_robot", &package);
    let spheres = spherize(&urdf, &resolver, &options()).expect("resolved");
    assert_eq!(spheres.links.len(), 1);
    // `package://` alone names no file, and the error says so.
    let error = run(dir.path(), &robot(&mesh_collision("package://", None))).expect_err("empty");
    assert_eq!(
        error.to_string(),
        "link \"base\": mesh `package://` not found (tried nothing: the URI names no file)"
    );
}

#[test]
fn an_unknown_mesh_format_names_the_link_and_the_file() {
    let dir = tempfile::tempdir().expect("a folder");
    std::fs::write(dir.path().join("base.dae"), "<COLLADA/>").expect("write");
    let error = run(dir.path(), &robot(&mesh_collision("base.dae", None))).expect_err("format");
    let message = error.to_string();
    assert!(matches!(error, RobotError::Mesh { .. }), "{message}");
    assert!(
        message.contains("\"base\"") && message.contains("base.dae"),
        "{message}"
    );
}

#[test]
fn a_malformed_mesh_file_names_the_link_and_the_file() {
    let dir = tempfile::tempdir().expect("a folder");
    std::fs::write(dir.path().join("base.obj"), "v 0 0 0\nv 1 0 0\nf 1 2 7\n").expect("write");
    let error = run(dir.path(), &robot(&mesh_collision("base.obj", None))).expect_err("malformed");
    let message = error.to_string();
    assert!(matches!(error, RobotError::Mesh { .. }), "{message}");
    assert!(message.contains("base.obj"), "{message}");
}

#[test]
fn a_malformed_xml_line_is_named() {
    let dir = tempfile::tempdir().expect("a folder");
    let text = "<robot name=\"r\">\n  <link name=\"a\">\n    <collision>\n  </link>\n</robot>\n";
    let error = run(dir.path(), text).expect_err("malformed");
    let message = error.to_string();
    assert!(matches!(error, RobotError::Xml { .. }), "{message}");
    assert!(
        message.contains("robot.urdf") && message.contains("4:"),
        "{message}"
    );
}

#[test]
fn a_scale_of_zero_names_the_line_the_link_and_the_file() {
    let dir = tempfile::tempdir().expect("a folder");
    std::fs::write(dir.path().join("base.obj"), box_obj(1.0)).expect("write");
    let error = run(
        dir.path(),
        &robot(&mesh_collision("base.obj", Some("1 0 1"))),
    )
    .expect_err("zero");
    let message = error.to_string();
    let RobotError::Invalid { line, .. } = &error else {
        panic!("{message}");
    };
    assert_eq!(*line, 4);
    assert!(
        message.contains("\"base\"")
            && message.contains("base.obj")
            && message.contains("scale of zero"),
        "{message}"
    );
}

#[test]
fn bad_numbers_radii_and_geometry_are_refused_with_the_place() {
    for (body, needle) in [
        (
            r#"<collision><geometry><sphere radius="-1"/></geometry></collision>"#,
            "must be positive",
        ),
        (
            r#"<collision><geometry><box size="1 1"/></geometry></collision>"#,
            "has 2 numbers, not 3",
        ),
        (
            r#"<collision><origin xyz="0 0 nan"/><geometry><sphere radius="1"/></geometry></collision>"#,
            "not finite",
        ),
        (
            r#"<collision><geometry><cone radius="1"/></geometry></collision>"#,
            "unknown geometry <cone>",
        ),
        (r#"<collision></collision>"#, "no <geometry>"),
    ] {
        let error = Urdf::parse(&robot(body), "r.urdf").expect_err(body);
        let message = error.to_string();
        assert!(
            message.contains("link \"base\" collision[0]") && message.contains(needle),
            "{body}: {message}"
        );
    }
    let error = Urdf::parse("<model/>", "r.urdf").expect_err("not a robot");
    assert!(error.to_string().contains("not <robot>"));
    let joint = r#"<robot name="r"><link name="a"/><joint name="j" type="revolute"><parent link="a"/><child link="ghost"/></joint></robot>"#;
    let error = Urdf::parse(joint, "r.urdf").expect_err("ghost");
    assert!(
        error.to_string().contains("\"ghost\" is not a link"),
        "{error}"
    );
}

/// A link without geometry is the right answer, not an error: it gets no spheres and is
/// listed; naming it for a count is an error that says it has no geometry.
#[test]
fn a_link_with_no_geometry_gets_no_spheres() {
    let text = r#"<robot name="r">
      <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
      <link name="empty"/>
      <joint name="j" type="fixed"><parent link="base"/><child link="empty"/></joint>
    </robot>"#;
    let urdf = Urdf::parse(text, "r.urdf").expect("parse");
    let resolver = MeshResolver::new(urdf.folder());
    let robot = spherize(&urdf, &resolver, &options()).expect("spherize");
    assert_eq!(robot.links.len(), 1);
    assert_eq!(robot.links_without_geometry, ["empty"]);
    let error = spherize(&urdf, &resolver, &options().with_link("empty", 4)).expect_err("empty");
    assert!(
        matches!(
            error,
            RobotError::UnknownLink {
                without_geometry: true,
                ..
            }
        ),
        "{error}"
    );
    assert!(error.to_string().contains("with geometry"));
    let error = spherize(&urdf, &resolver, &options().with_link("nope", 4)).expect_err("nope");
    assert!(matches!(
        error,
        RobotError::UnknownLink {
            without_geometry: false,
            ..
        }
    ));
    for bad in [SphereBudget::PerLink(0), SphereBudget::Total(0)] {
        let error = spherize(&urdf, &resolver, &options().with_budget(bad)).expect_err("zero");
        assert!(matches!(error, RobotError::InvalidParameter { .. }));
    }
}

/// A mesh in millimetres with a scale of 0.001 gives the spheres of the same mesh in
/// metres (to rounding: the vertices are scaled by 0.001 either way).
#[test]
fn a_mesh_in_millimetres_with_a_scale_gives_the_answer_in_metres() {
    let dir = tempfile::tempdir().expect("a folder");
    std::fs::write(dir.path().join("metres.obj"), box_obj(1.0)).expect("write");
    std::fs::write(dir.path().join("millimetres.obj"), box_obj(1000.0)).expect("write");
    let metres = run(dir.path(), &robot(&mesh_collision("metres.obj", None))).expect("metres");
    let millimetres = run(
        dir.path(),
        &robot(&mesh_collision(
            "millimetres.obj",
            Some("0.001 0.001 0.001"),
        )),
    )
    .expect("millimetres");
    let (a, b) = (&metres.links[0], &millimetres.links[0]);
    assert_eq!(a.spheres.len(), b.spheres.len());
    let scale = a.report.diagonal;
    assert!((a.report.diagonal - b.report.diagonal).abs() < 1e-9 * scale);
    assert!(
        (a.report.worst_protrusion - b.report.worst_protrusion).abs() < 1e-6 * scale,
        "{} against {}",
        a.report.worst_protrusion,
        b.report.worst_protrusion
    );
    assert!(b.bounding_sphere.radius < 0.2, "{:?}", b.bounding_sphere);
}

/// A mirroring scale flips the triangles, so the inside stays inside: the spheres still
/// cover the mirrored mesh.
#[test]
fn a_mirroring_scale_keeps_the_inside() {
    let dir = tempfile::tempdir().expect("a folder");
    std::fs::write(dir.path().join("base.obj"), box_obj(1.0)).expect("write");
    let robot_spheres = run(
        dir.path(),
        &robot(&mesh_collision("base.obj", Some("-1 1 1"))),
    )
    .expect("mirror");
    let link = &robot_spheres.links[0];
    assert_eq!(link.report.coverage, 1.0);
    let urdf = Urdf::read(dir.path().join("robot.urdf")).expect("read");
    let geometry = LinkGeometry::load(
        &urdf.links[0],
        GeometrySource::Collision,
        &MeshResolver::new(urdf.folder()),
    )
    .expect("geometry");
    let mesh = geometry.mesh.expect("a mesh");
    let surface = sphaera_query::Surface::new(&mesh).expect("a closed mesh");
    assert!(surface.is_inside(glam::DVec3::ZERO));
    assert!(matches!(
        urdf.links[0].collisions[0].geometry,
        Geometry::Mesh { .. }
    ));
}

/// A mesh file of no triangles (an STL of only its 84-byte header) is an error naming
/// the link and the file: dropping the link would hide it from the planner.
#[test]
fn an_empty_mesh_file_names_the_link_and_the_file() {
    let dir = tempfile::tempdir().expect("a folder");
    let mut header = vec![0u8; 84];
    header[..5].copy_from_slice(b"empty");
    std::fs::write(dir.path().join("empty.stl"), header).expect("write the STL");
    let error = run(dir.path(), &robot(&mesh_collision("empty.stl", None))).expect_err("empty");
    let message = error.to_string();
    assert!(
        matches!(error, RobotError::Mesh { .. })
            && message.contains("link \"base\"")
            && message.contains("empty.stl")
            && message.contains("no triangles"),
        "{message}"
    );
}

/// Links and joints must form one tree: an empty robot, two roots, a link with two
/// parents and a cycle cut off from the root are each refused, naming the place.
#[test]
fn links_and_joints_that_are_not_one_tree_are_refused() {
    let joint = |name: &str, parent: &str, child: &str| {
        format!(
            r#"<joint name="{name}" type="fixed"><parent link="{parent}"/><child link="{child}"/></joint>"#
        )
    };
    let links = |names: &[&str]| {
        names
            .iter()
            .map(|n| format!(r#"<link name="{n}"/>"#))
            .collect::<String>()
    };
    for (body, needle) in [
        (String::new(), "the robot has no <link>".to_owned()),
        (
            links(&["a", "b"]),
            "exactly one root link (one that is no joint's child); found a, b".to_owned(),
        ),
        (
            format!(
                "{}{}{}{}",
                links(&["a", "b", "c"]),
                joint("j1", "a", "b"),
                joint("j2", "a", "c"),
                joint("j3", "b", "c")
            ),
            "link \"c\" is reached twice".to_owned(),
        ),
        (
            format!(
                "{}{}{}",
                links(&["a", "b", "c"]),
                joint("j1", "b", "c"),
                joint("j2", "c", "b")
            ),
            "link \"b\": it is not connected to the root link \"a\"".to_owned(),
        ),
    ] {
        let text = format!(r#"<robot name="r">{body}</robot>"#);
        let error = Urdf::parse(&text, "r.urdf").expect_err(&text);
        let message = error.to_string();
        assert!(
            message.starts_with("r.urdf:") && message.contains(&needle),
            "{text}: {message}"
        );
    }
}

/// A negative capsule length is refused (0 is a sphere, and accepted).
#[test]
fn a_negative_capsule_length_is_refused() {
    let capsule = |length: &str| {
        robot(&format!(
            r#"<collision><geometry><capsule radius="0.1" length="{length}"/></geometry></collision>"#
        ))
    };
    let message = Urdf::parse(&capsule("-0.2"), "r.urdf")
        .expect_err("negative")
        .to_string();
    assert!(
        message.contains("link \"base\" collision[0] capsule")
            && message.contains("must not be negative"),
        "{message}"
    );
    Urdf::parse(&capsule("0"), "r.urdf").expect("a capsule of length 0 is a sphere");
}

/// No geometry of the kind asked for is an error (the output would be empty), and so are
/// sphere counts past [`sphaera_robot::MAX_SPHERES_PER_LINK`], which would exhaust time
/// and memory.
#[test]
fn no_geometry_and_huge_counts_are_refused() {
    let text = robot(r#"<collision><geometry><box size="0.4 0.4 0.4"/></geometry></collision>"#);
    let urdf = Urdf::parse(&text, "r.urdf").expect("parse");
    let resolver = MeshResolver::new(urdf.folder());
    let visual = options().with_source(GeometrySource::Visual);
    let error = spherize(&urdf, &resolver, &visual).expect_err("no visual geometry");
    assert_eq!(
        error.to_string(),
        "no link of robot \"test\" has visual geometry, so there is nothing to spherize"
    );
    for budget in [
        SphereBudget::PerLink(1_000_000_000),
        SphereBudget::Total(usize::MAX),
    ] {
        let error = spherize(&urdf, &resolver, &options().with_budget(budget)).expect_err("huge");
        assert!(
            matches!(error, RobotError::InvalidParameter { .. })
                && error.to_string().contains("at most 10,000 per link"),
            "{error}"
        );
    }
    let error = spherize(&urdf, &resolver, &options().with_link("base", 20_000)).expect_err("huge");
    assert!(error.to_string().contains("at most 10,000"), "{error}");
}

/// Primitives whose spheres lie exactly on their surface (a sphere link is its own
/// sphere) report the coverage they have, 1, not a figure lowered by rounding, and a
/// 95th percentile no larger than the worst protrusion.
#[test]
fn primitives_on_their_own_surface_report_full_coverage() {
    for geometry in [
        r#"<sphere radius="0.1"/>"#,
        r#"<sphere radius="0.000001"/>"#,
        r#"<capsule radius="0.05" length="0"/>"#,
        r#"<cylinder radius="0.2" length="0.002"/>"#,
    ] {
        let text = robot(&format!(
            "<collision><geometry>{geometry}</geometry></collision>"
        ));
        let urdf = Urdf::parse(&text, "r.urdf").expect("parse");
        let robot = spherize(&urdf, &MeshResolver::new(urdf.folder()), &options()).expect(geometry);
        let report = &robot.links[0].report;
        assert!(
            report.coverage == 1.0 && report.coverage_certified,
            "{geometry}: coverage {}",
            report.coverage
        );
        assert!(
            report.p95_protrusion <= report.worst_protrusion,
            "{geometry}: {} > {}",
            report.p95_protrusion,
            report.worst_protrusion
        );
    }
}

/// A `package://` or `file://` URI with percent-escapes names the decoded path (ROS's
/// resource retriever decodes them); a file whose name holds a literal `%20` is still
/// found as written, and a plain relative path is never decoded.
#[test]
fn percent_escapes_in_mesh_uris_are_decoded() {
    let dir = tempfile::tempdir().expect("a folder");
    let folder = dir.path().join("my meshes");
    std::fs::create_dir_all(&folder).expect("mkdir");
    std::fs::write(folder.join("bøx é.obj"), box_obj(1.0)).expect("write");
    let encoded = "package://pkg/my%20meshes/b%C3%B8x%20%C3%A9.obj";
    let spheres = run(dir.path(), &robot(&mesh_collision(encoded, None))).expect("decoded");
    assert_eq!(spheres.links.len(), 1);
    let resolver = MeshResolver::new(dir.path());
    let tried = resolver.candidates(encoded);
    assert!(tried.contains(&folder.join("bøx é.obj")), "{tried:?}");
    assert!(
        tried[0].to_string_lossy().contains("%20"),
        "as written first: {tried:?}"
    );
    // A literal `%20` in a file name, as written.
    std::fs::write(dir.path().join("a%20b.obj"), box_obj(1.0)).expect("write");
    run(dir.path(), &robot(&mesh_collision("a%20b.obj", None))).expect("literal");
    assert_eq!(
        resolver.candidates("a%20b.obj"),
        [dir.path().join("a%20b.obj")]
    );
    // A malformed escape is tried as written only.
    assert_eq!(resolver.candidates("file:///x%zz.obj").len(), 1);
}

/// A URDF naming a device, a folder or a named pipe as a link's mesh fails at once with
/// the reason; with a root, a mesh (or the URDF) outside it is refused however it is named
/// (`file://`, `..`, `package://`), and the ones inside are read.
#[test]
fn meshes_named_by_a_urdf_are_read_by_the_file_policy() {
    let outer = tempfile::tempdir().expect("a folder");
    let dir = outer.path().join("robot");
    std::fs::create_dir_all(dir.join("meshes")).expect("mkdir");
    std::fs::write(dir.join("meshes/box.obj"), box_obj(1.0)).expect("write");
    std::fs::write(outer.path().join("secret.obj"), box_obj(1.0)).expect("write");
    let started = std::time::Instant::now();
    let refused = |filename: &str, policy: &FilePolicy| {
        let path = dir.join("robot.urdf");
        std::fs::write(&path, robot(&mesh_collision(filename, None))).expect("write");
        let result = Urdf::read_with(&path, policy).and_then(|urdf| {
            let resolver = MeshResolver::new(urdf.folder()).with_policy(policy.clone());
            spherize(&urdf, &resolver, &options())
        });
        result.map(|_| ()).map_err(|e| e.to_string())
    };
    let open = FilePolicy::default();
    #[cfg(unix)]
    {
        let message = refused("file:///dev/zero", &open).unwrap_err();
        assert!(
            message.contains("\"base\"") && message.contains("it is a device, not a regular file"),
            "{message}"
        );
        let made = std::process::Command::new("mkfifo")
            .arg(dir.join("meshes/pipe.stl"))
            .status();
        assert!(
            made.is_ok_and(|s| s.success()),
            "mkfifo is part of coreutils"
        );
        let message = refused("meshes/pipe.stl", &open).unwrap_err();
        assert!(message.contains("a named pipe"), "{message}");
    }
    let message = refused("meshes", &open).unwrap_err();
    assert!(message.contains("it is a folder"), "{message}");
    assert!(started.elapsed() < std::time::Duration::from_secs(10));

    let root = FilePolicy::default().with_root(&dir);
    let secret = outer.path().join("secret.obj");
    for filename in [
        format!("file://{}", secret.display()),
        "../secret.obj".to_owned(),
        "package://meshes/../../secret.obj".to_owned(),
    ] {
        let message = refused(&filename, &root).unwrap_err();
        assert!(
            message.contains("outside the allowed folder"),
            "{filename}: {message}"
        );
    }
    assert_eq!(refused("package://meshes/box.obj", &root), Ok(()));
    assert_eq!(refused("meshes/box.obj", &root), Ok(()));
    // The URDF itself must lie inside the root too.
    std::fs::write(outer.path().join("outer.urdf"), robot("")).expect("write");
    let error = Urdf::read_with(outer.path().join("outer.urdf"), &root).unwrap_err();
    assert!(matches!(error, RobotError::ReadFile { .. }), "{error}");
    assert!(
        error.to_string().contains("outside the allowed folder"),
        "{error}"
    );
}

/// A chain of `n` links, each joint revolute about z and 1 cm up.
fn chain_urdf(n: usize) -> String {
    let mut text = String::from("<robot name=\"chain\">\n");
    for i in 0..n {
        text.push_str(&format!("<link name=\"l{i}\"/>\n"));
    }
    for i in 1..n {
        text.push_str(&format!(
            "<joint name=\"j{i}\" type=\"revolute\"><parent link=\"l{}\"/><child link=\"l{i}\"/><origin xyz=\"0 0 0.01\"/><axis xyz=\"0 0 1\"/></joint>\n",
            i - 1
        ));
    }
    text.push_str("</robot>\n");
    text
}

/// Checking and posing a URDF is linear in its links and joints: a 100,000-link chain
/// parses, checks and poses in seconds even in the test profile (the release build takes
/// a fraction of a second; a quadratic check took minutes). Its last link sits 1 km up.
#[test]
fn a_hundred_thousand_link_chain_is_checked_and_posed_in_linear_time() {
    let n = 100_000;
    let text = chain_urdf(n);
    let started = std::time::Instant::now();
    let urdf = Urdf::parse(&text, "chain.urdf").expect("a chain");
    let poses = urdf
        .link_poses(&std::collections::BTreeMap::new())
        .expect("poses");
    let seconds = started.elapsed().as_secs_f64();
    assert_eq!(poses.len(), n);
    let tip = poses[&format!("l{}", n - 1)].translation;
    assert!((tip.z - 0.01 * (n - 1) as f64).abs() < 1e-6, "{tip}");
    assert!(seconds < 20.0, "{seconds} s for {n} links");
    // A cycle deep in a long chain is still found, and named.
    let cyclic = text.replace(
        "<parent link=\"l0\"/><child link=\"l1\"/>",
        &format!("<parent link=\"l{}\"/><child link=\"l1\"/>", n - 1),
    );
    let error = Urdf::parse(&cyclic, "cyclic.urdf").expect_err("a cycle");
    assert!(error.to_string().contains("root link"), "{error}");
}

/// A chain of mimics is followed to the joint that drives it; a cycle of mimics has no
/// driver and is refused when the URDF is read.
#[test]
fn mimic_chains_are_followed_and_mimic_cycles_refused() {
    let robot = |mimics: &str| {
        format!(
            r#"<robot name="r">
      <link name="a"/><link name="b"/><link name="c"/><link name="d"/>
      <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>{}</joint>
      <joint name="j2" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/>{}</joint>
      <joint name="j3" type="revolute"><parent link="c"/><child link="d"/><axis xyz="0 0 1"/>{}</joint>
    </robot>"#,
            mimics.split('|').next().unwrap_or(""),
            mimics.split('|').nth(1).unwrap_or(""),
            mimics.split('|').nth(2).unwrap_or(""),
        )
    };
    // j3 mimics j2 mimics j1: j2 = 2 j1 + 0.1, j3 = -1 j2 + 0.3.
    let chained = robot(
        r#"|<mimic joint="j1" multiplier="2" offset="0.1"/>|<mimic joint="j2" multiplier="-1" offset="0.3"/>"#,
    );
    let urdf = Urdf::parse(&chained, "r.urdf").expect("a chain of mimics");
    let q1 = 0.4;
    let poses = urdf
        .link_poses(&std::collections::BTreeMap::from([("j1".to_owned(), q1)]))
        .expect("poses");
    let q2 = 2.0 * q1 + 0.1;
    let q3 = -q2 + 0.3;
    let angle = |name: &str| {
        let x = poses[name].transform_vector3(glam::DVec3::X);
        x.y.atan2(x.x)
    };
    assert!((angle("b") - q1).abs() < 1e-12);
    assert!((angle("c") - (q1 + q2)).abs() < 1e-12);
    assert!((angle("d") - (q1 + q2 + q3)).abs() < 1e-12);

    let cyclic = robot(r#"<mimic joint="j3"/>|<mimic joint="j1"/>|<mimic joint="j2"/>"#);
    let error = Urdf::parse(&cyclic, "r.urdf").expect_err("a cycle of mimics");
    assert!(
        error.to_string().contains("its mimics form a cycle"),
        "{error}"
    );
    let own = robot(r#"<mimic joint="j1"/>"#);
    let error = Urdf::parse(&own, "r.urdf").expect_err("a joint mimicking itself");
    assert!(error.to_string().contains("joint \"j1\""), "{error}");
}

/// A link's `<inertial>` is read (MJCF writes it) and checked: a negative mass, a missing
/// `<mass>` or `<inertia>`, an inertia that is not a number name the link and the line; a
/// zero mass (the KUKA iiwa's base) is accepted.
#[test]
fn inertials_are_read_and_bad_ones_named() {
    let inertial = |mass: &str, inertia: &str| {
        robot(&format!(
            r#"<inertial><origin xyz="0 0 0.1" rpy="0 0 1.5707963267948966"/>{mass}{inertia}</inertial>"#
        ))
    };
    let good_inertia = r#"<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3"/>"#;
    let urdf =
        Urdf::parse(&inertial(r#"<mass value="2.5"/>"#, good_inertia), "r.urdf").expect("reads");
    let read = urdf.links[0].inertial.expect("an inertial");
    assert_eq!(
        (read.mass, read.inertia),
        (2.5, [0.1, 0.0, 0.0, 0.2, 0.0, 0.3])
    );
    assert_eq!(read.origin.xyz, glam::DVec3::new(0.0, 0.0, 0.1));
    assert!(Urdf::parse(&inertial(r#"<mass value="0"/>"#, good_inertia), "r.urdf").is_ok());
    for (mass, inertia, needle) in [
        (r#"<mass value="-1"/>"#, good_inertia, "negative"),
        ("", good_inertia, "no <mass>"),
        (r#"<mass value="1"/>"#, "", "no <inertia>"),
        (
            r#"<mass value="1"/>"#,
            r#"<inertia ixx="x" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>"#,
            "ixx",
        ),
        (
            r#"<mass value="1"/>"#,
            r#"<inertia ixx="1" ixy="0" ixz="0" iyy="0" iyz="0"/>"#,
            "izz",
        ),
    ] {
        let error = Urdf::parse(&inertial(mass, inertia), "r.urdf").expect_err(needle);
        let text = error.to_string();
        assert!(
            text.contains(needle)
                && text.contains("link \"base\" inertial")
                && text.starts_with("r.urdf:"),
            "{text}"
        );
    }
}
