//! Arguments of `sphaera urdf` and the formats it writes.

use std::path::PathBuf;

use clap::Args;
use sphaera::mesh::Length;
use sphaera::robot::PlannerFormat;
use sphaera::spheretree::Effort;

use super::choice::Choice;
use super::spheretree::EFFORTS;
use super::{OutputArgs, parse_length};
/// Arguments of `sphaera urdf`.
#[derive(Debug, Args)]
pub struct UrdfArgs {
    /// The robot's URDF.
    pub urdf: PathBuf,

    /// Spheres for the whole robot, exactly: divided among the links in proportion to what
    /// each needs (surface area times 1 + ¼·log2(triangles / 12)), at least one each
    /// (`--per-link` counts are taken out first).
    #[arg(long, conflicts_with_all = ["spheres_per_link", "tolerance"])]
    pub budget: Option<usize>,

    /// Exactly this many spheres for every link (the default: 16).
    #[arg(long, conflicts_with = "tolerance")]
    pub spheres_per_link: Option<usize>,

    /// Spheres for one link, `NAME=N`, overriding the budget (repeat for more links).
    #[arg(long = "per-link", value_parser = parse_link_count)]
    pub per_link: Vec<(String, usize)>,

    /// Instead of a count: every link's spheres within this of its surface (certified),
    /// with as few spheres as that needs (a minimax tolerance tree's leaves), in the
    /// URDF's units (`0.005`) or as a percentage of each link's bounding-box diagonal
    /// (`2%`).
    #[arg(long, value_parser = parse_length, allow_hyphen_values = true)]
    pub tolerance: Option<Length>,

    /// The most spheres a `--tolerance` may give a link: a link that needs more is an
    /// error.
    #[arg(long, default_value_t = 1_000)]
    pub max_spheres_per_link: usize,

    /// Spherize the visual geometry instead of the collision geometry.
    #[arg(long, conflicts_with = "collision")]
    pub visual: bool,

    /// Spherize the collision geometry (the default).
    #[arg(long)]
    pub collision: bool,

    /// Where `package://NAME/...` resolves, `NAME=FOLDER` (repeat for more packages);
    /// tried before the URDF's own folder.
    #[arg(long = "package", value_parser = parse_package)]
    pub packages: Vec<(String, PathBuf)>,

    /// The output file; its format follows `--format`, else the extension (`.urdf`,
    /// `.srdf`, `.yml`/`.yaml` for cuRobo, `.json`).
    #[arg(long, short)]
    pub output: Option<PathBuf>,

    /// The output format.
    #[arg(long, value_parser = Choice::of(FORMATS))]
    pub format: Option<PlannerFormat>,

    /// How hard each link's sphere-tree works for tighter spheres: `quick`, `default` or
    /// `thorough`.
    #[arg(long, default_value = "default", value_parser = Choice::of(EFFORTS))]
    pub effort: Effort,

    #[command(flatten)]
    pub print: OutputArgs,
}

/// `--format`: the formats `sphaera urdf` writes (every [`PlannerFormat`]).
pub const FORMATS: &[(PlannerFormat, &str)] = &[
    (
        PlannerFormat::Urdf,
        "The same URDF with each link's collision geometry replaced by its spheres",
    ),
    (
        PlannerFormat::Srdf,
        "MoveIt's SRDF `<link_sphere_approximation>` sidecar",
    ),
    (PlannerFormat::Curobo, "cuRobo's `collision_spheres` YAML"),
    (
        PlannerFormat::Json,
        "JSON: per link a tree (the bounding sphere, groups of nearby spheres, the \
         spheres; each encloses its children) and the report",
    ),
];

fn parse_link_count(text: &str) -> Result<(String, usize), String> {
    let (name, count) = text
        .rsplit_once('=')
        .ok_or_else(|| format!("`{text}`: expected NAME=N, e.g. panda_hand=24"))?;
    let count: usize = count
        .trim()
        .parse()
        .ok()
        .filter(|&n| n > 0)
        .ok_or_else(|| format!("`{text}`: the count must be a positive whole number"))?;
    Ok((name.trim().to_owned(), count))
}

fn parse_package(text: &str) -> Result<(String, PathBuf), String> {
    let (name, folder) = text.split_once('=').ok_or_else(|| {
        format!("`{text}`: expected NAME=FOLDER, e.g. franka_description=./franka")
    })?;
    Ok((name.trim().to_owned(), PathBuf::from(folder)))
}
