//! Exports of a sphere-tree: JSON (the whole tree, read back with validation), the
//! YAML "collision spheres" list robot motion planners take, and (with the `parry`
//! feature) a `parry3d-f64` compound of balls; and the classic `.sph` text format of
//! the original toolkit ([`SphFile`], [`read_sph`], [`write_sph`]).
//!
//! Files are written atomically: to a temporary file in the same directory, renamed over
//! the target.

mod json;
#[cfg(feature = "parry")]
mod parry;
mod sph;
mod yaml;

pub use json::{
    JSON_FORMAT, JSON_VERSION, LevelJson, NodeJson, TreeJson, tree_from_json, tree_to_json,
    write_tree_json,
};
#[cfg(feature = "parry")]
pub use parry::to_parry_compound;
pub use sph::{SphDefect, SphFile, read_sph, write_sph};
pub use yaml::{CollisionLink, collision_spheres_yaml, write_collision_spheres_yaml};
