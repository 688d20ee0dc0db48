//! Every generated table, by subject.

mod filters;
mod hal;
mod queries;
mod scene_silhouette;
mod spheres;

use super::spec::Table;

/// Every generated table.
pub fn all() -> impl Iterator<Item = &'static Table> {
    spheres::TABLES
        .iter()
        .chain(scene_silhouette::TABLES)
        .chain(queries::TABLES)
        .chain(hal::TABLES)
}
