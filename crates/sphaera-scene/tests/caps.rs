//! The caps on parameters that size work or memory (issue 38): each is refused just above
//! its cap, before anything is built, with an error naming the parameter and the cap.

mod common;

use sphaera_mesh::shapes;
use sphaera_scene::{MAX_MESH_LADDER_LEVELS, ObjectModel, SceneError};

#[test]
fn more_ladder_levels_than_the_cap_are_refused_before_building() {
    for levels in [MAX_MESH_LADDER_LEVELS + 1, usize::MAX] {
        let options = common::options().with_mesh_ladder_levels(levels);
        let error = ObjectModel::build("ball", shapes::sphere(1.0, 8).expect("sphere"), &options)
            .expect_err("too many levels");
        assert!(
            matches!(
                error,
                SceneError::InvalidOption {
                    name: "mesh_ladder_levels",
                    ..
                }
            ),
            "{error:?}"
        );
        assert!(
            error.to_string().contains("MAX_MESH_LADDER_LEVELS"),
            "{error}"
        );
    }
    // The cap itself is accepted: the ladder stops where the hierarchy does.
    let options = common::options().with_mesh_ladder_levels(MAX_MESH_LADDER_LEVELS);
    let model = ObjectModel::build("ball", shapes::sphere(1.0, 8).expect("sphere"), &options)
        .expect("the cap is accepted");
    assert!(model.mesh_level(0).is_some());
}

/// Silhouette options beyond the silhouette crate's caps leave the model without labels,
/// and the reason names the cap.
#[cfg(feature = "silhouette")]
#[test]
fn silhouette_options_beyond_their_caps_leave_the_model_without_labels() {
    use sphaera_scene::SilhouetteOptions;
    for (silhouette, cap) in [
        (
            SilhouetteOptions::default().with_step_degrees(0.00001),
            "MAX_VIEWS",
        ),
        (
            SilhouetteOptions::default().with_resolution(4_000_000_000),
            "MAX_RESOLUTION",
        ),
    ] {
        let options = common::options().with_silhouette(silhouette);
        let model = ObjectModel::build("ball", shapes::sphere(1.0, 8).expect("sphere"), &options)
            .expect("the model builds without labels");
        let error = model.silhouette_labels().expect_err("beyond the cap");
        assert!(error.to_string().contains(cap), "{error}");
    }
}
