//! Precomputed silhouette labels: a model takes labels of its own mesh computed with its
//! own settings, and refuses any other, naming itself and what differs; a scene file's
//! `labels` are read by the file policy and checked the same way.

#![cfg(feature = "silhouette")]

mod common;

use std::path::{Path, PathBuf};

use sphaera_io::FilePolicy;
use sphaera_mesh::{TriMesh, shapes};
use sphaera_scene::{ModelOptions, ObjectModel, SceneDescription, SceneError, SilhouetteOptions};
use sphaera_silhouette::{
    Contours, DistanceTransform, LabelOptions, Labels, SilhouetteError, ViewSet,
};

/// Fast labels: 18 views (45°), 32² cells, outlines.
fn silhouette() -> SilhouetteOptions {
    SilhouetteOptions::default()
        .with_step_degrees(45.0)
        .with_resolution(32)
}

fn options() -> ModelOptions {
    common::options().with_silhouette(silhouette())
}

fn ball() -> TriMesh {
    shapes::sphere(0.5, 10).expect("sphere")
}

/// The labels the model would compute, with one setting changed by `change`.
fn labels(mesh: &TriMesh, step: f64, change: impl Fn(LabelOptions) -> LabelOptions) -> Labels {
    let options = change(
        LabelOptions::default()
            .with_resolution(32)
            .with_contours(Contours::External),
    );
    Labels::compute(mesh, &ViewSet::regular(step).expect("views"), &options).expect("labels")
}

#[test]
fn a_model_takes_its_own_labels_and_refuses_others() {
    let mesh = ball();
    let model = ObjectModel::build("ball", mesh.clone(), &options()).expect("model");
    let own = labels(&mesh, 45.0, |o| o);
    let model = model.with_silhouette_labels(own.clone()).expect("its own");
    assert_eq!(model.silhouette_labels().expect("labels"), &own);
    // And they are what the model computes itself.
    let computed = ObjectModel::build("ball", mesh.clone(), &options()).expect("model");
    assert_eq!(computed.silhouette_labels().expect("labels"), &own);

    let refused = |labels: Labels, named: &str| {
        let model = ObjectModel::build("ball", mesh.clone(), &options()).expect("model");
        let error = model.with_silhouette_labels(labels).expect_err(named);
        let message = error.to_string();
        assert!(
            matches!(&error, SceneError::SilhouetteLabels { model, .. } if model == "ball"),
            "{message}"
        );
        assert!(message.contains("model `ball`"), "{message}");
        assert!(message.contains(named), "{named}: {message}");
    };
    refused(labels(&mesh, 30.0, |o| o), "step 30°, not 45°");
    refused(
        labels(&mesh, 45.0, |o| o.with_resolution(16)),
        "resolution 16, not 32",
    );
    refused(
        labels(&mesh, 45.0, |o| o.with_contours(Contours::All)),
        "contours all, not outline",
    );
    refused(
        labels(&mesh, 45.0, |o| {
            o.with_transform(DistanceTransform::Chamfer)
        }),
        "transform chamfer, not euclidean",
    );
    let perspective = ViewSet::regular(45.0)
        .and_then(|v| v.with_perspective(3.0))
        .expect("views");
    let options = LabelOptions::default()
        .with_resolution(32)
        .with_contours(Contours::External);
    refused(
        Labels::compute(&mesh, &perspective, &options).expect("labels"),
        "projection perspective at 3 radii, not orthographic",
    );
    let bigger = shapes::sphere(0.6, 10).expect("sphere");
    refused(labels(&bigger, 45.0, |o| o), "another mesh");
}

/// A folder with `ball.obj`, its labels in `ball.labels` (the model's settings), the
/// labels of other settings and of another mesh.
fn folder() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let mesh = ball();
    sphaera_io::write_obj(dir.path().join("ball.obj"), &mesh).expect("write");
    labels(&mesh, 45.0, |o| o)
        .save(&mesh, dir.path().join("ball.labels"))
        .expect("save");
    labels(&mesh, 90.0, |o| o)
        .save(&mesh, dir.path().join("coarse.labels"))
        .expect("save");
    let cube = shapes::cube(1.0, 2).expect("cube");
    labels(&cube, 45.0, |o| o)
        .save(&cube, dir.path().join("cube.labels"))
        .expect("save");
    dir
}

fn scene(dir: &Path, labels: &str) -> PathBuf {
    let path = dir.join("scene.json");
    let text = format!(
        r#"{{ "meshes": {{ "ball": "ball.obj" }}, "instances": [ {{ "mesh": "ball" }} ], "labels": {{ "ball": {labels} }} }}"#
    );
    std::fs::write(&path, text).expect("write");
    path
}

fn build(path: &Path, policy: &FilePolicy) -> Result<Vec<Labels>, String> {
    SceneDescription::read_with(path, policy)
        .and_then(|d| d.build(&options()))
        .map(|loaded| {
            loaded
                .models
                .iter()
                .map(|m| m.silhouette_labels().expect("labels").clone())
                .collect()
        })
        .map_err(|e| e.to_string())
}

#[test]
fn a_scene_file_gives_models_their_label_files() {
    let dir = folder();
    let open = FilePolicy::default();
    let read = build(&scene(dir.path(), r#""ball.labels""#), &open).expect("a good scene");
    let saved = Labels::load(dir.path().join("ball.labels"), &ball()).expect("labels");
    assert_eq!(read, vec![saved]);
    // `build_with` reads them too, after the caller's model.
    let description =
        SceneDescription::read(scene(dir.path(), r#""ball.labels""#)).expect("description");
    assert_eq!(
        description.labels_path("ball"),
        Some(dir.path().join("ball.labels"))
    );
    let loaded = description
        .build_with(|name, path| {
            let mesh = sphaera_io::read_with(path, description.file_policy())?.mesh;
            ObjectModel::build(name, mesh, &options())
        })
        .expect("built");
    assert!(loaded.models[0].silhouette_labels().is_ok());
}

#[test]
fn label_files_that_do_not_fit_name_the_model_and_the_file() {
    let dir = folder();
    let open = FilePolicy::default();
    let refused = |labels: &str, policy: &FilePolicy| {
        build(&scene(dir.path(), labels), policy).expect_err(labels)
    };
    for (labels, named) in [
        (r#""coarse.labels""#, "step 90°, not 45°"),
        (r#""cube.labels""#, "another mesh"),
        (r#""ball.obj""#, "not a sphaera label file"),
        (r#""missing.labels""#, "missing.labels"),
        (r#""/dev/zero""#, "not a regular file"),
        (r#""""#, "not a regular file"),
    ] {
        if labels.contains("/dev") && !cfg!(unix) {
            continue;
        }
        let message = refused(labels, &open);
        for part in ["scene.json", "labels.ball", named] {
            assert!(message.contains(part), "{labels}: {part}: {message}");
        }
    }
    // A damaged file.
    let mut bytes = std::fs::read(dir.path().join("ball.labels")).expect("read");
    let middle = bytes.len() / 2;
    bytes[middle] ^= 4;
    std::fs::write(dir.path().join("damaged.labels"), bytes).expect("write");
    let message = refused(r#""damaged.labels""#, &open);
    assert!(message.contains("checksum"), "{message}");
    // With a root, a label file outside it is refused.
    let outside = folder();
    let root = FilePolicy::default().with_root(dir.path());
    let named = format!("{:?}", outside.path().join("ball.labels"));
    let message = refused(&named, &root);
    assert!(message.contains("outside the allowed folder"), "{message}");
    assert!(build(&scene(dir.path(), r#""ball.labels""#), &root).is_ok());
}

#[test]
fn labels_must_name_a_mesh_of_the_scene() {
    let dir = folder();
    let path = dir.path().join("scene.json");
    std::fs::write(
        &path,
        r#"{ "meshes": { "ball": "ball.obj" }, "instances": [], "labels": { "cube": "cube.labels" } }"#,
    )
    .expect("write");
    let error = SceneDescription::read(&path)
        .expect_err("undefined")
        .to_string();
    assert!(
        error.contains("labels.cube") && error.contains("not defined"),
        "{error}"
    );
    // A mesh no instance uses may have labels: they are not read.
    std::fs::write(
        &path,
        r#"{ "meshes": { "ball": "ball.obj", "cube": "cube.obj" }, "instances": [ { "mesh": "ball" } ], "labels": { "cube": "cube.labels" } }"#,
    )
    .expect("write");
    assert!(build(&path, &FilePolicy::default()).is_ok());
}

#[test]
fn a_model_without_labels_says_why_and_the_error_stays_small() {
    // A step that gives no labels: the model's own options are refused first.
    let model = ObjectModel::build(
        "odd",
        ball(),
        &common::options().with_silhouette(SilhouetteOptions::default().with_step_degrees(7.0)),
    )
    .expect("model");
    let error = model
        .with_silhouette_labels(labels(&ball(), 45.0, |o| o))
        .expect_err("no settings");
    assert!(matches!(
        error,
        SceneError::SilhouetteLabels { ref source, .. }
            if matches!(**source, SilhouetteError::InvalidStep { .. })
    ));
    assert!(size_of::<SceneError>() <= 128);
}
