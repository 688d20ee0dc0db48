//! Arguments of `sphaera hal`.

use std::path::PathBuf;

use clap::Args;
use sphaera::mesh::Length;

use super::{OutputArgs, parse_length};
/// Arguments of `sphaera hal`.
#[derive(Debug, Args)]
pub struct HalArgs {
    /// The polygon: a text file of `x y` lines (`#` comments allowed), closed implicitly;
    /// GeoJSON (`.geojson`, `.json`) or WKT (`.wkt`) polygons with holes and
    /// multipolygons (a country with its islands: one tree per ring, one answer); or a
    /// closed genus-0 mesh (`.obj`, `.ply`, `.stl`, `.off`, `.gltf`, `.glb`) for the 3D
    /// tree.
    pub polygon: PathBuf,

    /// Read the file as an open polyline (no closing edge, no inside).
    #[arg(long)]
    pub open: bool,

    /// Adaptive approximation: refine only parts whose bounding area is wider than this,
    /// an absolute width (`0.01`) or a percentage of the bounding-box diagonal (`0.5%`).
    #[arg(long, value_parser = parse_length)]
    pub tolerance: Option<Length>,

    /// The approximation of this level (without `--tolerance`; the full outline at the
    /// tree's depth).
    #[arg(long)]
    pub level: Option<usize>,

    /// Write the approximation, atomically: `.txt` (`x y` lines) or `.svg` (the outline,
    /// the approximation and its bounding areas) for a polygon; a mesh file for a mesh.
    #[arg(long, short)]
    pub output: Option<PathBuf>,

    /// Locate every point of this file (`x y` lines for a polygon, `x y z` for a mesh):
    /// inside, outside or boundary, in file order; for GeoJSON and WKT also where (the
    /// polygon or hole holding it, the nearest edge and its distance).
    #[arg(long)]
    pub contains: Option<PathBuf>,

    /// Intersect with this outline (a text file of `x y` lines read as a polygon, or
    /// GeoJSON or WKT polygons and lines): whether they meet, as GEOS's `intersects` (a
    /// line inside a polygon meets it), and every pair of crossing or touching edges. For
    /// a mesh, another closed genus-0 mesh: whether the solids meet, and every pair of
    /// faces that do.
    #[arg(long, value_name = "OTHER")]
    pub intersect: Option<PathBuf>,

    #[command(flatten)]
    pub print: OutputArgs,
}
