//! Arguments of `sphaera view`.

use std::path::PathBuf;

use clap::Args;
use sphaera::mesh::Length;

use super::{OutputArgs, parse_length};
/// Arguments of `sphaera view`.
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted. A
    /// robot's `.urdf` instead gives the robot page: every link's collision meshes and
    /// spheres, a slider per joint moving them, links coloured by their certified
    /// protrusion, the self-collision pairs listed.
    pub mesh: Option<PathBuf>,

    /// With a URDF: spheres per link (default 16).
    #[arg(long, default_value_t = 16)]
    pub spheres_per_link: usize,

    /// With a URDF: a joint's value when the page opens, `NAME=VALUE` (radians or the
    /// URDF's units; repeat for more joints; the others at MoveIt's default, 0 where the
    /// limits allow).
    #[arg(long = "joint", value_parser = parse_joint, allow_hyphen_values = true)]
    pub joints: Vec<(String, f64)>,

    /// A sphere-tree of this mesh to show (`.json` from `sphaera spheretree -o`, or
    /// `.sph`); built with the default options when omitted.
    #[arg(long)]
    pub tree: Option<PathBuf>,

    /// Also show the mesh simplified: the rungs of its simplification hierarchy from half
    /// its triangles down to this fraction, in (0, 1], halving each time, each with its
    /// certified error bound (error spheres: every point of either surface is within the
    /// bound of the other).
    #[arg(long, value_parser = parse_view_ratio)]
    pub simplify: Option<f64>,

    /// Colour the mesh by its certified distance to this other mesh (blue 0 to red at the
    /// bound), with a legend, the other mesh as wires, and the place where the symmetric
    /// Hausdorff distance is reached marked.
    #[arg(long, value_name = "OTHER")]
    pub hausdorff: Option<PathBuf>,

    /// Also show HAL approximations (closed genus-0 meshes): the HAL tree's levels down to
    /// the first with half the triangles, and the adaptive approximation whose lenses are
    /// at most this wide, an absolute width (`0.01`) or a percentage of the bounding-box
    /// diagonal (`1%`).
    #[arg(long, value_name = "T", value_parser = parse_length)]
    pub hal: Option<Length>,

    /// Colour the mesh by its silhouette labels in grey levels (black on the outline),
    /// those of the camera nearest the viewing direction, updated as the view turns: 62
    /// cameras every 30°, 128² cells, the outline only.
    #[arg(long)]
    pub silhouette: bool,

    /// The page to write (default `view.html`).
    #[arg(long, short)]
    pub output: Option<PathBuf>,

    #[command(flatten)]
    pub print: OutputArgs,
}

fn parse_view_ratio(text: &str) -> Result<f64, String> {
    text.trim()
        .parse::<f64>()
        .ok()
        .filter(|r| *r > 0.0 && *r <= 1.0)
        .ok_or_else(|| format!("`{text}`: the ratio must be a number in (0, 1]"))
}

fn parse_joint(text: &str) -> Result<(String, f64), String> {
    let (name, value) = text
        .rsplit_once('=')
        .ok_or_else(|| format!("`{text}`: expected NAME=VALUE, e.g. panda_joint4=-1.5"))?;
    let value: f64 = value
        .trim()
        .parse()
        .ok()
        .filter(|v: &f64| v.is_finite())
        .ok_or_else(|| format!("`{text}`: the value must be a finite number"))?;
    Ok((name.trim().to_owned(), value))
}
