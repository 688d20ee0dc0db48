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
    /// `.srdf`, `.yml`/`.yaml` for cuRobo's robot file, `.xml`/`.mjcf` for MuJoCo,
    /// `.json`).
    #[arg(long, short)]
    pub output: Option<PathBuf>,

    /// The output format.
    #[arg(long, value_parser = Choice::of(FORMATS))]
    pub format: Option<PlannerFormat>,

    /// Random joint configurations sampled for the self-collision matrix (MoveIt's
    /// 10,000 by default): pairs of links whose spheres never meet in them are left out of
    /// self-collision checks, as are adjacent pairs, pairs in contact at the default
    /// configuration and pairs in contact in 95 % of the samples. 0 keeps only the
    /// adjacent and default rules.
    #[arg(long, default_value_t = 10_000)]
    pub self_collision_samples: usize,

    /// The random sequence of those configurations.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,

    /// A clearance, in the URDF's units: pairs whose spheres come closer than this count
    /// as in contact (so a pair left out as "Never" keeps it).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub self_collision_padding: f64,

    /// The end-effector link of the cuRobo file (default: where the main chain ends; the
    /// joints below it are locked).
    #[arg(long)]
    pub ee_link: Option<String>,

    /// With the cuRobo robot file: write the spheres to this file (cuRobo's
    /// `collision_spheres` YAML) and name it in the robot file, instead of inline.
    #[arg(long, value_name = "FILE")]
    pub curobo_spheres: Option<PathBuf>,

    /// Also write the links' meshes (STL and OBJ files) as visual geoms into the MJCF.
    #[arg(long)]
    pub mjcf_meshes: bool,

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
        "MoveIt's SRDF sidecar: `<link_sphere_approximation>` per link, `<disable_collisions>` per pair left out",
    ),
    (
        PlannerFormat::Curobo,
        "A complete cuRobo robot file: URDF, base and end-effector links, spheres, self-collision ignore lists, joint space",
    ),
    (
        PlannerFormat::CuroboSpheres,
        "cuRobo's `collision_spheres` block alone",
    ),
    (
        PlannerFormat::Mjcf,
        "MuJoCo's MJCF: bodies, joints and limits, the spheres as geoms, the pairs left out excluded",
    ),
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
