//! Exports of a sphere-tree: JSON (the whole tree, read back with validation), the
//! YAML "collision spheres" list robot motion planners take, and (with the `parry`
//! feature) a `parry3d-f64` compound of balls; and the classic `.sph` text format of
//! the original toolkit ([`SphFile`], [`read_sph`], [`write_sph`]).
//!
//! Writers take any [`std::io::Write`]; a front end writes files atomically with
//! `sphaera_io::write_atomic` (this crate reads and writes no files itself).

mod format;
mod json;
#[cfg(feature = "parry")]
mod parry;
mod sph;
mod yaml;

pub use format::{ParseTreeFormatError, TreeFormat, tree_to_text, write_tree};
pub use json::{
    JSON_FORMAT, JSON_VERSION, LevelJson, NodeJson, TreeJson, tree_from_json, tree_to_json,
    write_tree_json,
};
#[cfg(feature = "parry")]
pub use parry::to_parry_compound;
pub use sph::{SphDefect, SphFile, read_sph, write_sph};
pub use yaml::{CollisionLink, collision_spheres_yaml, write_collision_spheres_yaml, yaml_float};
