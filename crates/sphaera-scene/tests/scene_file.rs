//! Scene files: a good one builds with the poses it names; every bad one gives a clear
//! error naming the file and the entry.

use std::path::Path;

use sphaera_io as io;
use sphaera_io::FilePolicy;
use sphaera_mesh::{DVec3, shapes};
use sphaera_scene::{SceneDescription, SceneError, Tolerance};

mod common;

/// A folder with `meshes/ball.obj` and `cube.obj`.
fn folder() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("a temporary folder");
    std::fs::create_dir_all(dir.path().join("meshes")).expect("mkdir");
    io::write_obj(
        dir.path().join("meshes/ball.obj"),
        &shapes::sphere(0.5, 10).expect("sphere"),
    )
    .expect("write");
    io::write_obj(
        dir.path().join("cube.obj"),
        &shapes::cube(1.0, 2).expect("cube"),
    )
    .expect("write");
    dir
}

fn write(dir: &Path, text: &str) -> std::path::PathBuf {
    let path = dir.join("scene.json");
    std::fs::write(&path, text).expect("write");
    path
}

/// The message of a scene file's error, checked to name the file.
fn error_of(text: &str) -> (SceneError, String) {
    let dir = folder();
    let path = write(dir.path(), text);
    let error = match SceneDescription::read(&path) {
        Err(e) => e,
        Ok(description) => description
            .build(&common::options())
            .expect_err("an invalid scene"),
    };
    let message = error.to_string();
    assert!(message.contains("scene.json"), "{message}");
    (error, message)
}

const GOOD: &str = r#"{
  "meshes": { "ball": "meshes/ball.obj", "cube": "cube.obj" },
  "instances": [
    { "name": "front", "mesh": "ball", "position": [0, 0, 0] },
    { "mesh": "ball", "position": [3, 0, -2], "rotation_degrees": [0, 90, 0], "scale": 2 },
    { "mesh": "cube", "quaternion": [0, 0, 0.7071067811865476, 0.7071067811865476], "position": [0.9, 0, 0] }
  ],
  "camera": { "eye": [0, 0, 8], "target": [0, 0, 0], "fov_y_degrees": 60, "width": 640, "height": 480 }
}"#;

#[test]
fn a_good_scene_file_builds_with_its_poses() {
    let dir = folder();
    let path = write(dir.path(), GOOD);
    let description = SceneDescription::read(&path).expect("a valid scene");
    assert_eq!(description.used_meshes(), ["ball", "cube"]);
    let loaded = description.build(&common::options()).expect("built");
    assert_eq!(loaded.models.len(), 2);
    let names: Vec<&str> = loaded
        .scene
        .instances()
        .iter()
        .map(|i| i.name.as_str())
        .collect();
    assert_eq!(names, ["front", "ball-1", "cube-2"]);
    let second = &loaded.scene.instances()[1];
    assert_eq!(second.pose.scale().to_bits(), 2f64.to_bits());
    // 90° about y takes x to -z.
    let moved = second.pose.point(DVec3::X);
    assert!(
        moved.distance(DVec3::new(3.0, 0.0, -4.0)) < 1e-12,
        "{moved}"
    );
    let third = &loaded.scene.instances()[2];
    assert!(
        third
            .pose
            .point(DVec3::X)
            .distance(DVec3::new(0.9, 1.0, 0.0))
            < 1e-12
    );
    // The camera is there, so a tolerance in pixels works; the ball and the cube touch.
    let camera = loaded.camera.expect("a camera");
    let report = loaded
        .scene
        .detail(Some(&camera), Tolerance::Pixels(3.0))
        .expect("detail");
    assert_eq!(report.instances.len(), 3);
    let contacts = loaded
        .scene
        .collide(&sphaera_scene::Budget::Unlimited)
        .expect("collide");
    assert_eq!(
        contacts
            .pairs
            .iter()
            .map(|p| (p.a, p.b))
            .collect::<Vec<_>>(),
        [(0, 2)]
    );
}

#[test]
fn a_missing_mesh_file_names_the_mesh_and_the_file() {
    let (error, message) = error_of(
        r#"{ "meshes": { "gone": "nowhere/gone.obj" }, "instances": [ { "mesh": "gone" } ] }"#,
    );
    assert!(
        matches!(error, SceneError::InvalidEntry { .. }),
        "{error:?}"
    );
    assert!(
        message.contains("meshes.gone") && message.contains("gone.obj"),
        "{message}"
    );
}

#[test]
fn an_undefined_mesh_name_lists_the_defined_ones() {
    let (_, message) = error_of(
        r#"{ "meshes": { "ball": "meshes/ball.obj" }, "instances": [ { "name": "x", "mesh": "bal" } ] }"#,
    );
    assert!(
        message.contains(r#"instances[0] ("x")"#)
            && message.contains("`bal`")
            && message.contains("ball"),
        "{message}"
    );
}

#[test]
fn unknown_keys_are_errors_with_their_line() {
    for (text, key) in [
        (
            "{ \"meshes\": {},\n \"instances\": [],\n \"lights\": [] }",
            "lights",
        ),
        (
            "{ \"meshes\": { \"ball\": \"meshes/ball.obj\" },\n \"instances\": [\n { \"mesh\": \"ball\", \"rotation_degree\": [0, 0, 0] } ] }",
            "rotation_degree",
        ),
        (
            "{ \"meshes\": {}, \"instances\": [],\n \"camera\": { \"eye\": [0,0,1], \"target\": [0,0,0], \"fov\": 60, \"width\": 1, \"height\": 1 } }",
            "fov",
        ),
    ] {
        let (error, message) = error_of(text);
        assert!(matches!(error, SceneError::ParseFile { .. }), "{error:?}");
        assert!(
            message.contains(key) && message.contains("line"),
            "{message}"
        );
    }
}

#[test]
fn a_mesh_name_given_twice_is_an_error_with_its_line() {
    let text = "{ \"meshes\": {\n \"ball\": \"meshes/ball.obj\",\n \"ball\": \"meshes/torus.obj\" },\n \"instances\": [] }";
    let (error, message) = error_of(text);
    assert!(matches!(error, SceneError::ParseFile { .. }), "{error:?}");
    assert!(
        message.contains("mesh name `ball` is given twice") && message.contains("line 3"),
        "{message}"
    );
}

#[test]
fn nan_and_infinite_numbers_are_refused() {
    // JSON has no NaN: the reader refuses the literal, and numbers beyond f64.
    for text in [
        r#"{ "meshes": { "ball": "meshes/ball.obj" }, "instances": [ { "mesh": "ball", "position": [NaN, 0, 0] } ] }"#,
        r#"{ "meshes": { "ball": "meshes/ball.obj" }, "instances": [ { "mesh": "ball", "position": [1e400, 0, 0] } ] }"#,
    ] {
        let (error, message) = error_of(text);
        assert!(matches!(error, SceneError::ParseFile { .. }), "{message}");
        assert!(message.contains("line 1"), "{message}");
    }
}

#[test]
fn bad_poses_and_cameras_name_their_entry() {
    for (text, needle) in [
        (
            r#"{ "meshes": { "ball": "meshes/ball.obj" }, "instances": [ { "mesh": "ball", "scale": 0 } ] }"#,
            "`scale` must be positive",
        ),
        (
            r#"{ "meshes": { "ball": "meshes/ball.obj" }, "instances": [ { "mesh": "ball", "scale": -1 } ] }"#,
            "`scale` must be positive",
        ),
        (
            r#"{ "meshes": { "ball": "meshes/ball.obj" }, "instances": [ { "mesh": "ball", "quaternion": [0, 0, 0, 0] } ] }"#,
            "unit quaternion",
        ),
        (
            r#"{ "meshes": { "ball": "meshes/ball.obj" }, "instances": [ { "mesh": "ball", "quaternion": [0, 0, 0, 1], "rotation_degrees": [0, 0, 0] } ] }"#,
            "not both",
        ),
        (
            r#"{ "meshes": {}, "instances": [], "camera": { "eye": [0,0,1], "target": [0,0,0], "fov_y_degrees": 0, "width": 1, "height": 1 } }"#,
            "camera",
        ),
        (
            r#"{ "meshes": {}, "instances": [], "camera": { "eye": [0,0,1], "target": [0,0,1], "fov_y_degrees": 60, "width": 1, "height": 1 } }"#,
            "away from the eye",
        ),
    ] {
        let (error, message) = error_of(text);
        assert!(
            matches!(error, SceneError::InvalidEntry { .. }),
            "{message}"
        );
        assert!(message.contains(needle), "{message}");
    }
}

#[test]
fn malformed_json_and_missing_files_are_clear() {
    let (error, message) = error_of(
        "{ \"meshes\": { \"ball\": \"meshes/ball.obj\" },\n \"instances\": [ { \"mesh\": \"ball\" } ",
    );
    assert!(matches!(error, SceneError::ParseFile { .. }), "{message}");
    assert!(message.contains("line 2"), "{message}");
    let missing = SceneDescription::read("/nonexistent/scene.json").expect_err("no file");
    assert!(matches!(missing, SceneError::ReadFile { .. }));
    assert!(missing.to_string().contains("/nonexistent/scene.json"));
    // A mesh with no inside (an open sheet) gets a model (the minimax trees cover
    // shells), but not from a medial method, which needs an inside: named.
    let dir = folder();
    let sheet = sphaera_mesh::TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]])
        .expect("a triangle");
    io::write_obj(dir.path().join("sheet.obj"), &sheet).expect("write");
    let path = write(
        dir.path(),
        r#"{ "meshes": { "sheet": "sheet.obj" }, "instances": [ { "mesh": "sheet" } ] }"#,
    );
    let description = SceneDescription::read(&path).expect("valid");
    let loaded = description
        .build(&common::options())
        .expect("a sheet's model");
    assert!(!loaded.models[0].surface().has_inside());
    let medial = common::options().with_tree(
        sphaera_spheretree::SphereTreeOptions::default()
            .with_method(sphaera_spheretree::Method::Combined)
            .with_depth(1),
    );
    let error = description.build(&medial).expect_err("no inside");
    let message = error.to_string();
    assert!(
        message.contains("meshes.sheet") && message.contains("inside"),
        "{message}"
    );
}

/// A scene naming a device, a named pipe or a folder as a mesh fails at once with the
/// reason (it used to read `/dev/zero` until memory ran out, and to wait on a pipe
/// forever); with a root, a mesh outside it is refused however it is named (absolute,
/// `..`, a link), and the scene file itself must lie inside.
#[test]
fn meshes_named_by_a_scene_are_read_by_the_file_policy() {
    let dir = folder();
    let started = std::time::Instant::now();
    let build = |meshes: &str, policy: &FilePolicy| {
        let path = write(
            dir.path(),
            &format!(r#"{{ "meshes": {{ "m": {meshes} }}, "instances": [ {{ "mesh": "m" }} ] }}"#),
        );
        SceneDescription::read_with(&path, policy)
            .and_then(|d| d.build(&common::options()))
            .map(|_| ())
            .map_err(|e| e.to_string())
    };
    let refused = |meshes: &str, policy: &FilePolicy| build(meshes, policy).unwrap_err();
    let open = FilePolicy::default();
    #[cfg(unix)]
    {
        let message = refused(r#""/dev/zero""#, &open);
        assert!(
            message.contains("meshes.m") && message.contains("it is a device, not a regular file"),
            "{message}"
        );
        let pipe = dir.path().join("pipe.obj");
        let made = std::process::Command::new("mkfifo").arg(&pipe).status();
        assert!(
            made.is_ok_and(|s| s.success()),
            "mkfifo is part of coreutils"
        );
        let message = refused(r#""pipe.obj""#, &open);
        assert!(message.contains("a named pipe"), "{message}");
    }
    let message = refused(r#""meshes""#, &open);
    assert!(message.contains("it is a folder"), "{message}");
    assert!(started.elapsed() < std::time::Duration::from_secs(10));

    // Confined: the ball inside is read; the same ball outside is refused.
    let outside = folder();
    io::write_obj(
        outside.path().join("ball.obj"),
        &shapes::sphere(1.0, 16).unwrap(),
    )
    .unwrap();
    let root = FilePolicy::default().with_root(dir.path());
    let absolute = format!("{:?}", outside.path().join("ball.obj"));
    let outside_name = outside.path().file_name().unwrap().to_string_lossy();
    let climbing = format!(r#""meshes/../../{outside_name}/ball.obj""#);
    for named in [absolute.as_str(), climbing.as_str()] {
        let message = refused(named, &root);
        assert!(
            message.contains("outside the allowed folder"),
            "{named}: {message}"
        );
    }
    assert_eq!(build(r#""meshes/ball.obj""#, &root), Ok(()));
    // The scene file itself too.
    let elsewhere = write(outside.path(), r#"{ "meshes": {}, "instances": [] }"#);
    let error = SceneDescription::read_with(&elsewhere, &root).unwrap_err();
    assert!(matches!(error, SceneError::ReadFile { .. }), "{error}");
    assert!(
        error.to_string().contains("outside the allowed folder"),
        "{error}"
    );
}
