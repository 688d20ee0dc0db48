//! Arguments of `sphaera scene`: the scene, its camera and image, the tolerance.

use std::path::PathBuf;

use clap::Args;
use sphaera::mesh::Length;
use sphaera::spheretree::Effort;

use super::choice::Choice;
use super::spheretree::EFFORTS;
use super::{OutputArgs, parse_length};
/// Arguments of `sphaera scene`.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// A scene file (JSON, see `sphaera_scene`'s documentation), or one or more mesh
    /// files (each an instance of its own model, side by side along x); the demo scene
    /// of embedded bunnies when omitted.
    #[arg(value_name = "SCENE.json | MESH...")]
    pub inputs: Vec<PathBuf>,

    /// The error each instance may have: pixels on the camera's image (`2px`), a
    /// percentage of each object's bounding-box diagonal (`0.5%`), or world units
    /// (`0.01`). Default: `2px` with a camera, `1%` without.
    #[arg(long, value_parser = parse_scene_tolerance, allow_hyphen_values = true)]
    pub tolerance: Option<sphaera::scene::Tolerance>,

    /// The camera, replacing the scene file's: the eye and the point looked at, six
    /// numbers `EX,EY,EZ,TX,TY,TZ`.
    #[arg(long, value_parser = parse_camera, allow_hyphen_values = true)]
    pub camera: Option<[f64; 6]>,

    /// The camera's vertical field of view in degrees (with `--camera`).
    #[arg(long, default_value_t = 60.0)]
    pub fov: f64,

    /// The camera's image size in pixels, `WIDTHxHEIGHT` (with `--camera`).
    #[arg(long, default_value = "1920x1080", value_parser = parse_image_size)]
    pub image: (u32, u32),

    /// The collision budget in the paper's cost model (2 per sphere placed, 1 per sphere
    /// pair tested); every pair's trees are descended to their leaves when omitted.
    #[arg(long)]
    pub budget: Option<f64>,

    /// A collision budget in milliseconds of wall time (instead of `--budget`).
    #[arg(long, conflicts_with = "budget", allow_hyphen_values = true)]
    pub time_budget_ms: Option<f64>,

    /// With a camera, also choose silhouette-aware meshes: each instance's outline
    /// within the tolerance, its interior within this many times it (at least 1).
    #[arg(long, default_value_t = 4.0)]
    pub silhouette: f64,

    /// Levels below the root of each model's base sphere-tree, built with the model
    /// (0: the root alone). Finer trees are built to the tolerance when it needs them.
    #[arg(long, default_value_t = 0)]
    pub depth: usize,

    /// Children per node of the base sphere-tree at most (the trees built to the
    /// tolerance take 16).
    #[arg(long, default_value_t = 8)]
    pub branch: usize,

    /// Surface samples per sphere-tree (the paper's medial methods; the minimax trees
    /// work on the exact surface).
    #[arg(long, default_value_t = 10_000)]
    pub samples: usize,

    /// The finest tolerance a model builds a sphere-tree to: a percentage of its
    /// diagonal (`0.1%`) or model units. A tolerance needing a finer one is an error
    /// naming the model and the figures.
    #[arg(long, default_value = "0.1%", value_parser = parse_length)]
    pub finest: Length,

    /// How hard the trees built to the tolerance work for few spheres: `quick` (the
    /// default: they are built while you wait), `default` (several times the time for
    /// somewhat fewer spheres) or `thorough`.
    #[arg(long, default_value = "quick", value_parser = Choice::of(EFFORTS))]
    pub effort: Effort,

    #[command(flatten)]
    pub print: OutputArgs,
}

fn parse_scene_tolerance(text: &str) -> Result<sphaera::scene::Tolerance, String> {
    text.parse()
        .map_err(|e: sphaera::scene::SceneError| e.to_string())
}

fn parse_camera(text: &str) -> Result<[f64; 6], String> {
    let numbers: Vec<f64> = text
        .split(',')
        .map(|p| p.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("`{text}`: {e}; expected six numbers EX,EY,EZ,TX,TY,TZ"))?;
    let array: [f64; 6] = numbers.try_into().map_err(|v: Vec<f64>| {
        format!(
            "`{text}`: {} numbers; expected six, EX,EY,EZ,TX,TY,TZ",
            v.len()
        )
    })?;
    if array.iter().all(|v| v.is_finite()) {
        Ok(array)
    } else {
        Err(format!("`{text}`: every number must be finite"))
    }
}

fn parse_image_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{text}`: expected WIDTHxHEIGHT, e.g. 1920x1080"))?;
    let parse = |s: &str| {
        s.trim()
            .parse::<u32>()
            .ok()
            .filter(|&v| v > 0)
            .ok_or_else(|| format!("`{text}`: sizes must be positive whole numbers of pixels"))
    };
    Ok((parse(w)?, parse(h)?))
}
