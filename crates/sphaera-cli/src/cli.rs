//! The command line, declared with clap.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum, builder::PossibleValue};
use sphaera::mesh::Length;
use sphaera::simplify::{Order, Placement};
use sphaera::spheretree::{Effort, Method};

/// Hierarchical sphere-based approximation of triangle meshes.
///
/// Every MESH argument may be omitted: the embedded low-resolution Stanford bunny
/// (public domain, 3,674 triangles) is used instead. Supported formats: OBJ, PLY (ASCII
/// and binary), STL (ASCII and binary), OFF, glTF 2.0 (`.gltf` with its buffer files or
/// `data:` URIs, binary `.glb`; the default scene's triangle meshes, placed by their node
/// transforms and merged).
#[derive(Debug, Parser)]
#[command(name = "sphaera", version)]
pub struct Cli {
    /// Hide progress bars.
    #[arg(long, short, global = true)]
    pub quiet: bool,

    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands: one per capability.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Describe a mesh: counts, bounding box, topology (closed, manifold, genus,
    /// components, boundary loops), degenerate and duplicate triangles.
    Info(InfoArgs),
    /// Simplify a mesh by edge collapses, with an error bound that holds both ways: every
    /// input point is within the bound of the output and every output point within the
    /// bound of the input.
    Simplify(SimplifyArgs),
    /// Exact closest points on a mesh (Meshsweeper): for points read from a file or drawn
    /// at random in the mesh's bounding box scaled 1.5x.
    Distance(DistanceArgs),
    /// Certified Hausdorff distance between two meshes (Meshsweeper, section 6): a lower
    /// and an upper bound at most `--tolerance` apart, where the maximum is reached, and
    /// optionally a PLY of the first mesh coloured by its distance to the second.
    Hausdorff(HausdorffArgs),
    /// Spheres around a mesh from its medial axis. `--spheres N` gives exactly N spheres
    /// covering the whole surface (certified by construction): the minimax cover, whose
    /// centres are medial candidates moved on the exact surface; it also covers flat
    /// sheets. Otherwise the adaptive medial-axis approximation (Bradshaw and O'Sullivan
    /// 2004, section 4): spheres on the internal Voronoi vertices of surface samples, plus
    /// cover spheres, so that every sample is covered, improved by replacing the worst
    /// sphere until `--medial-target` spheres (500 by default; the set then has at least
    /// that many) or `--max-error` is reached, then certified to cover the whole surface,
    /// not only the samples, growing the few spheres that must grow (as every sphere-tree
    /// level is); `--samples-only` skips that.
    Medial(MedialArgs),
    /// Sphere-tree for collision detection: the root is the mesh's minimum enclosing ball
    /// and each node's part of the surface is divided between at most `--branch`
    /// children, to `--depth` levels, or only where needed until every leaf is within
    /// `--tolerance` (as deep as that takes), or into exactly `--spheres` N spheres in one
    /// level. The default method (auto, today minimax) also covers flat sheets and open
    /// patches; the paper's methods (Bradshaw and O'Sullivan 2004) need a solid. Every
    /// level is certified to cover the whole surface (not by the baselines, whose
    /// coverage is measured), and its certified worst error is reported. The main job:
    /// with no arguments it builds the embedded bunny's tree.
    Spheretree(SpheretreeArgs),
    /// HAL tree (Veltkamp): a polygon kept as a binary tree of approximations by its own
    /// vertices, each part bounded by the intersection of two discs through its ends.
    /// Reports vertices and covering width per level, an adaptive approximation to
    /// `--tolerance`, point inclusion for a file of points; draws the approximation with
    /// its bounding areas as SVG. A mesh file (OBJ, PLY, STL, OFF, glTF/GLB; closed, genus 0) gets
    /// the 3D tree: triangles and width per level, an adaptive approximation written as a
    /// mesh.
    Hal(HalArgs),
    /// Silhouette-preserving level of detail (Mata, Pastor and Rodríguez): distance labels
    /// from a camera every `--step` degrees say how far each vertex lies from the
    /// silhouette; the mesh's progressive hierarchy is refined for one view so that the
    /// contour region keeps `--factor` times the error allowed elsewhere, each region with
    /// its certified bound. Pictures: the labels as grey levels seen from the view, and the
    /// silhouettes of the original and the result overlaid.
    Silhouette(SilhouetteArgs),
    /// Model no more than a scene needs, and no less. Reads a scene file (JSON: meshes,
    /// instances with poses, a camera) or mesh files (one instance each, side by side),
    /// builds each mesh's model once (a base sphere-tree and a simplification
    /// hierarchy), then gives every instance the coarsest sphere-tree cut and mesh level
    /// whose certified error meets `--tolerance` (pixels on the camera's image, a
    /// percentage of each object, or world units): a model whose trees do not reach
    /// that builds a minimax tree to it, once, refined only where needed. Then finds
    /// every contact within `--budget` (a broad phase, then every close pair's finest
    /// trees descended together, level by level). Reports the choices, their certified
    /// errors, the trees built, and the spheres and triangles saved against full
    /// detail; a tolerance that cannot be met is an error naming the model and the
    /// figures. With no input: eight embedded bunnies going away from the camera, two
    /// of them touching.
    Scene(SceneArgs),
    /// Whole-robot sphere models for motion planners (also `sphaera robot`). Reads a URDF,
    /// loads every link's collision (or `--visual`) meshes in the link's frame with their
    /// origins and scales (`package://` against the URDF's folder, relative paths against
    /// the URDF), and spherizes the links in parallel: meshes (solids, or shells when open
    /// or flat) by a minimax sphere-tree whose spheres cover every point of the surface by
    /// construction and whose protrusion is certified, boxes, cylinders, spheres and
    /// capsules analytically. Exactly `--spheres-per-link N` spheres per link, a
    /// `--budget N` divided among the links summing to N, or a `--tolerance` every link
    /// meets with as few spheres as it needs (fewer spheres than asked only where a link
    /// cannot use them, and the report says why). Writes the spherized URDF, MoveIt's SRDF
    /// sphere approximations, cuRobo's collision-sphere YAML or JSON (`-o`, the format from
    /// the extension or `--format`), and reports per link the spheres, the certified worst
    /// and the 95th-percentile protrusion, the coverage and the time (`--json` for JSON).
    #[command(visible_alias = "robot")]
    Urdf(UrdfArgs),
    /// One self-contained HTML page (three.js inlined, opens offline in any browser)
    /// showing the mesh and its sphere-tree: a level slider, the spheres translucent,
    /// each level's worst sphere in red, and every level's certified error in a side
    /// panel. The tree is built as the main job builds it, or read with `--tree`. Also
    /// the rungs of a simplification (`--simplify`), HAL approximations (`--hal`), the
    /// distance to another mesh as colours (`--hausdorff`) and silhouette labels in grey
    /// levels (`--silhouette`). With no arguments: the embedded bunny.
    View(ViewArgs),
}

/// Arguments of `sphaera view`.
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted.
    pub mesh: Option<PathBuf>,

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
    #[arg(long, value_enum)]
    pub format: Option<UrdfFormat>,

    /// How hard each link's sphere-tree works for tighter spheres: `quick`, `default` or
    /// `thorough`.
    #[arg(long, default_value = "default", value_parser = parse_effort)]
    pub effort: Effort,

    #[command(flatten)]
    pub print: OutputArgs,
}

fn parse_effort(text: &str) -> Result<Effort, String> {
    text.trim()
        .parse()
        .map_err(|_| format!("`{text}`: the effort must be quick, default or thorough"))
}

/// The formats `sphaera urdf` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum UrdfFormat {
    /// The same URDF with each link's collision geometry replaced by its spheres.
    Urdf,
    /// MoveIt's SRDF `<link_sphere_approximation>` sidecar.
    Srdf,
    /// cuRobo's `collision_spheres` YAML.
    Curobo,
    /// JSON: per link a tree (the bounding sphere, groups of nearby spheres, the
    /// spheres; each encloses its children) and the report.
    Json,
}

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
    /// default: they are built while you wait), `default` (about four times the time
    /// for 3–15 % fewer spheres) or `thorough`.
    #[arg(long, default_value = "quick", value_parser = parse_effort)]
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

/// Arguments of `sphaera silhouette`.
#[derive(Debug, Args)]
pub struct SilhouetteArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted.
    pub mesh: Option<PathBuf>,

    /// Degrees between cameras of the regular view set (it must divide 180; 15 gives 266
    /// views).
    #[arg(long, default_value_t = 15.0)]
    pub step: f64,

    /// Cells a side of every view's label grid.
    #[arg(long, default_value_t = 512)]
    pub resolution: usize,

    /// The contour region: triangles with a corner at most this many cells from the
    /// silhouette.
    #[arg(long, default_value_t = 2.0)]
    pub threshold: f32,

    /// The contour region's allowed error as a fraction of `--error` (0: exact there).
    #[arg(long, default_value_t = 0.25)]
    pub factor: f64,

    /// The error allowed away from the contour: a distance (`0.002`) or a percentage of
    /// the bounding-box diagonal (`1%`).
    #[arg(long, value_parser = parse_length, default_value = "1%")]
    pub error: Length,

    /// The view: the direction toward the camera, `x,y,z`.
    #[arg(long, value_parser = parse_direction, default_value = "0,0,1", allow_hyphen_values = true)]
    pub view: [f64; 3],

    /// Labels for the view: those of the nearest camera (1) or the average of this many
    /// nearest cameras.
    #[arg(long, default_value_t = 1)]
    pub nearest: usize,

    /// Which silhouettes the labels measure from.
    #[arg(long, value_enum, default_value_t = ContoursArg::Outline)]
    pub contours: ContoursArg,

    /// The distance transform of the label images.
    #[arg(long, value_enum, default_value_t = TransformArg::Euclidean)]
    pub transform: TransformArg,

    /// Perspective cameras this many bounding radii from the centre (more than 1);
    /// orthographic when omitted.
    #[arg(long)]
    pub perspective: Option<f64>,

    /// Write the extracted mesh, atomically (`.obj` or `.ply`).
    #[arg(long, short)]
    pub output: Option<PathBuf>,

    /// Write the labels seen from the view as grey levels (PNG, the paper's Fig. 3):
    /// black at the silhouette, lighter with distance.
    #[arg(long)]
    pub labels_png: Option<PathBuf>,

    /// Write the silhouettes of the original and the result overlaid (PNG): grey where
    /// both cover, red where only the original does, blue where only the result does.
    #[arg(long)]
    pub compare_png: Option<PathBuf>,

    #[command(flatten)]
    pub print: OutputArgs,
}

/// `sphaera hausdorff --engine`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum HausdorffEngineArg {
    /// `sphaera_sweep::hausdorff`: triangle trees, every core.
    Trees,
    /// `sphaera_sweep::meshsweeper_hausdorff`: the paper's engine on hierarchies.
    Meshsweeper,
}

/// `--order`: the simplifier's collapse order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum OrderArg {
    /// Strict below 32,768 vertices, batched above.
    Auto,
    /// The greedy order: the smallest radius first, always (one core).
    Strict,
    /// Stale candidates re-evaluated in batches on every core (faster on large meshes).
    Batched,
}

impl OrderArg {
    /// The simplifier's order.
    pub fn order(self) -> Order {
        match self {
            Self::Auto => Order::Auto,
            Self::Strict => Order::Strict,
            Self::Batched => Order::Batched,
        }
    }

    /// The name on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Strict => "strict",
            Self::Batched => "batched",
        }
    }
}

/// `--contours`: which silhouettes labels measure from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ContoursArg {
    /// The outline only (the better silhouette per triangle on scanned meshes).
    Outline,
    /// The outline and the internal silhouettes (the paper's Fig. 2).
    All,
}

/// `--transform`: the distance transform of the label images.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TransformArg {
    /// Exact Euclidean distances.
    Euclidean,
    /// The paper's two-pass 3–4 chamfer (within 8 % of Euclidean).
    Chamfer,
}

/// A direction on the command line: `x,y,z`, finite and not zero.
fn parse_direction(text: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = text.split(',').collect();
    let [x, y, z] = parts.as_slice() else {
        return Err(format!("`{text}` is not a direction `x,y,z`"));
    };
    let mut out = [0.0_f64; 3];
    for (o, part) in out.iter_mut().zip([x, y, z]) {
        *o = part
            .trim()
            .parse()
            .map_err(|e| format!("`{part}` in `{text}` is not a number: {e}"))?;
    }
    if out.iter().any(|c| !c.is_finite()) || out.iter().all(|&c| c == 0.0) {
        return Err(format!("`{text}` must be finite and not zero"));
    }
    Ok(out)
}

/// Arguments of `sphaera hal`.
#[derive(Debug, Args)]
pub struct HalArgs {
    /// The polygon: a text file of `x y` lines (`#` comments allowed), closed implicitly;
    /// or a closed genus-0 mesh (`.obj`, `.ply`, `.stl`, `.off`, `.gltf`, `.glb`) for the
    /// 3D tree.
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
    /// inside, outside or boundary, in file order.
    #[arg(long)]
    pub contains: Option<PathBuf>,

    #[command(flatten)]
    pub print: OutputArgs,
}

/// Arguments of `sphaera spheretree`.
#[derive(Debug, Args)]
pub struct SpheretreeArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted. A
    /// mesh that encloses a volume is a solid (holes and non-manifold edges are fine); one
    /// that does not (a flat sheet, an open patch) is a shell, which only the minimax
    /// method (auto) covers.
    pub mesh: Option<PathBuf>,

    /// How the tree is built.
    #[arg(long, value_enum, default_value_t = MethodArg::Auto)]
    pub method: MethodArg,

    /// Levels below the root.
    #[arg(long, default_value_t = 3)]
    pub depth: usize,

    /// Children per node at most.
    #[arg(long, default_value_t = 8)]
    pub branch: usize,

    /// Exactly N spheres in one level: a one-level minimax tree (depth 1, branch N, at
    /// most 10,000), reported with its certified error (minimax and auto only).
    #[arg(long, value_name = "N", conflicts_with_all = ["depth", "tolerance", "branch"])]
    pub spheres: Option<usize>,

    /// Surface samples standing for the surface (Poisson-disk, reproducible; the medial
    /// methods and the baselines: minimax works on the triangles themselves).
    #[arg(long, default_value_t = 10_000)]
    pub samples: usize,

    /// Spheres of the initial medial approximation (merge, burst, expand, combined).
    #[arg(long, default_value_t = 500)]
    pub initial_spheres: usize,

    /// Medial spheres each node's region is refined to before reduction (merge, burst,
    /// expand, combined).
    #[arg(long, default_value_t = 100)]
    pub min_spheres_per_node: usize,

    /// A node's medial spheres are refined until their worst error is at most this
    /// fraction of the parent's (merge, burst, expand, combined; the paper: ½ to ¼).
    /// Smaller is tighter at levels 2 and 3 and slower.
    #[arg(long, default_value_t = 0.125)]
    pub error_fraction: f64,

    /// Forming points of Hubbard's static medial approximation (hubbard only).
    #[arg(long, default_value_t = 600)]
    pub forming_points: usize,

    /// Build until every leaf's certified error is at most this, refining only the nodes
    /// that exceed it, each into the fewest children (at most `--branch`) that meet it,
    /// as deep as needed (minimax and auto only; instead of `--depth`): an absolute
    /// distance (`0.002`) or a percentage of the bounding-box diagonal (`2%`). Leaves
    /// then end at different depths, so each level is reported as its cut: the level's
    /// nodes and the leaves above it, which together cover the surface.
    #[arg(long, value_parser = parse_length, conflicts_with = "depth")]
    pub tolerance: Option<Length>,

    /// With `--tolerance`: the most nodes (spheres of every level together) the tree may
    /// have (at most 2^21). A tolerance that needs more is refused, before the work
    /// where the count is known in advance, with the figures reached; never more nodes.
    #[arg(long, value_name = "N", requires = "tolerance")]
    pub max_nodes: Option<usize>,

    /// How hard the minimax method works for tighter spheres (minimax and auto only):
    /// `quick`, `default` or `thorough`.
    #[arg(long, default_value = "default", value_parser = parse_effort)]
    pub effort: Effort,

    /// Skip the certified evaluation of every level (worst error by branch and bound,
    /// coverage on 100,000 independent samples); report the construction error only.
    #[arg(long)]
    pub no_evaluation: bool,

    /// Seed of the surface sampling.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,

    /// Write the tree, atomically: `.json` (levels, spheres, errors, parents, children,
    /// coverage certificates), `.sph` (the classic sphere-tree format: a complete
    /// `branch`-ary tree with a slot for every possible node, so a deep tree may not fit)
    /// or `.yaml` (a motion planner's `collision_spheres` list: the tree's leaves, which
    /// meet `--tolerance` when it is given).
    #[arg(long, short)]
    pub output: Option<PathBuf>,

    #[command(flatten)]
    pub print: OutputArgs,
}

/// `--method`: the minimax construction, the paper's reducers, and the classic baselines
/// for comparison.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// The minimax construction: each region tiled by triangle pieces and divided
    /// between the children whose worst error is least; builds to a depth, a tolerance
    /// or a sphere count, and covers sheets (surfaces without inside).
    Minimax,
    /// The default: the best method for the surface, today minimax.
    Auto,
    /// The paper's reducer: merge neighbouring medial spheres, tightest result first.
    Merge,
    /// The paper's reducer: burst medial spheres, handing their points to the spheres
    /// closest to covering them.
    Burst,
    /// The paper's reducer: expand the medial spheres to a common standoff and select a
    /// covering subset.
    Expand,
    /// The paper's best: merge and expand per node, keeping the tighter.
    Combined,
    /// Baseline: an octree's occupied cells, each in its circumscribed sphere.
    Octree,
    /// Baseline: per level a regular grid of about branch^level occupied cells.
    Grid,
    /// Baseline: Hubbard's static medial spheres merged by enclosing spheres.
    Hubbard,
}

impl MethodArg {
    /// The library's method.
    pub fn method(self) -> Method {
        match self {
            Self::Minimax => Method::Minimax,
            Self::Auto => Method::Auto,
            Self::Merge => Method::Merge,
            Self::Burst => Method::Burst,
            Self::Expand => Method::Expand,
            Self::Combined => Method::Combined,
            Self::Octree => Method::Octree,
            Self::Grid => Method::Grid,
            Self::Hubbard => Method::Hubbard,
        }
    }
}

/// Arguments of `sphaera medial`.
#[derive(Debug, Args)]
pub struct MedialArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted. The
    /// adaptive approximation needs a mesh that encloses a volume (holes and non-manifold
    /// edges are fine; a flat sheet is not); `--spheres` covers sheets too.
    pub mesh: Option<PathBuf>,

    /// Exactly N spheres covering the whole surface (certified by construction), at most
    /// 10,000: the minimax cover (a one-level minimax sphere-tree), each sphere's centre a
    /// medial candidate moved on the exact surface so that the worst sphere's error is
    /// least. Without it: the adaptive approximation (`--medial-target`, `--max-error`).
    #[arg(
        long,
        value_name = "N",
        conflicts_with_all = [
            "medial_target", "max_error", "static_points", "samples", "cover",
            "samples_only", "seed",
        ]
    )]
    pub spheres: Option<usize>,

    /// The adaptive approximation: improve until the set has at least this many spheres
    /// (its cover spheres can add more; default 500 when neither `--spheres` nor
    /// `--max-error` is given).
    #[arg(long, value_name = "M", conflicts_with = "max_error")]
    pub medial_target: Option<usize>,

    /// The adaptive approximation: improve until no sphere reaches farther than this
    /// beyond the surface: an absolute distance (`0.002`) or a percentage of the
    /// bounding-box diagonal (`1%`). It bounds the medial spheres; the surface
    /// certificate's growth can add to a few of them (the report gives the error before
    /// and after; more `--samples` shrink the growth).
    #[arg(long, value_parser = parse_length)]
    pub max_error: Option<Length>,

    /// Surface samples that must be covered (Poisson-disk, reproducible).
    #[arg(long, default_value_t = 10_000)]
    pub samples: usize,

    /// How an uncovered sample chooses its cover sphere.
    #[arg(long, value_enum, default_value_t = CoverArg::SmallestError)]
    pub cover: CoverArg,

    /// Hubbard's static baseline instead: the Voronoi diagram of this many samples, no
    /// improvement, coverage of the samples not completed (the surface certificate still
    /// grows spheres to cover the whole surface, unless `--samples-only`).
    #[arg(long, conflicts_with_all = ["medial_target", "max_error"])]
    pub static_points: Option<usize>,

    /// Skip the surface certificate: the spheres then cover the surface samples only, and
    /// parts of the surface between samples may lie outside every sphere. By default every
    /// point of every triangle is certified to lie in some sphere: each triangle is split
    /// until every piece lies in one sphere, and where a piece 1/1000 of the bounding-box
    /// diagonal long lies in none, the sphere needing the least growth grows to contain
    /// it (raising that sphere's error, which can take the worst error past
    /// `--max-error`).
    #[arg(long)]
    pub samples_only: bool,

    /// Seed of the surface sampling.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,

    /// Write the spheres as JSON (the coverage guarantee and certificate; per sphere its
    /// centre, radius, error, kind, covered sample count and certificate growth),
    /// atomically.
    #[arg(long, short)]
    pub output: Option<PathBuf>,

    #[command(flatten)]
    pub print: OutputArgs,
}

/// `--cover`: the paper's two criteria.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum CoverArg {
    /// The candidate sphere with the smallest error (tighter).
    SmallestError,
    /// The candidate sphere covering the most uncovered samples (fewer cover spheres).
    LargestCoverage,
}

/// Arguments of `sphaera hausdorff`.
#[derive(Debug, Args)]
pub struct HausdorffArgs {
    /// The first mesh (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted.
    pub a: Option<PathBuf>,

    /// The second mesh; when omitted, the first mesh simplified to 15 % of its triangles
    /// (then the simplifier's certified error bound is reported beside the distance).
    pub b: Option<PathBuf>,

    /// Stop once `upper − lower` is at most this: an absolute distance (`1e-4`) or a
    /// percentage of the bounding-box diagonal of both meshes (`0.001%`).
    #[arg(long, value_parser = parse_length, default_value = "0.001%")]
    pub tolerance: Length,

    /// Only the one-sided distance from A to B (default: symmetric).
    #[arg(long)]
    pub one_sided: bool,

    /// Stop refining after this many samples (the bounds stay certified, only wider).
    #[arg(long, default_value_t = 20_000_000)]
    pub max_samples: usize,

    /// The engine: `trees` (exact queries from triangle trees, every core; the fastest)
    /// or `meshsweeper` (the paper's, on hierarchies of error spheres, one thread).
    #[arg(long, value_enum, default_value_t = HausdorffEngineArg::Trees)]
    pub engine: HausdorffEngineArg,

    /// Write mesh A as a PLY whose vertices are coloured by their distance to B, blue
    /// (0) to red (the largest), written atomically.
    #[arg(long)]
    pub colors: Option<PathBuf>,

    #[command(flatten)]
    pub print: OutputArgs,
}

/// Arguments of `sphaera distance`.
#[derive(Debug, Args)]
pub struct DistanceArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted.
    pub mesh: Option<PathBuf>,

    /// A text file of query points, one `x y z` per line (spaces or commas; `#` starts a
    /// comment).
    #[arg(long, conflicts_with = "random")]
    pub points: Option<PathBuf>,

    /// Query this many points drawn uniformly in the bounding box scaled 1.5x (the default,
    /// with 1,000, when no `--points` file is given).
    #[arg(long)]
    pub random: Option<usize>,

    /// The seed of `--random`.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,

    /// Stop each query once its certified interval is at most this wide: an absolute
    /// distance (`0.001`) or a percentage of the bounding-box diagonal (`0.1%`). Without
    /// it, every answer is exact.
    #[arg(long, value_parser = parse_length)]
    pub tolerance: Option<Length>,

    #[command(flatten)]
    pub print: OutputArgs,
}

/// Arguments of `sphaera simplify`.
#[derive(Debug, Args)]
pub struct SimplifyArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted.
    pub mesh: Option<PathBuf>,

    /// Where to write the simplified mesh (`.obj` or `.ply`, written atomically). Without
    /// it, only the figures are printed.
    #[arg(long, short)]
    pub output: Option<PathBuf>,

    /// Stop at this many triangles.
    #[arg(long, conflicts_with = "ratio")]
    pub triangles: Option<usize>,

    /// Stop at this fraction of the input's triangles, in (0, 1].
    #[arg(long)]
    pub ratio: Option<f64>,

    /// Stop before the error bound exceeds this: an absolute distance (`0.002`) or a
    /// percentage of the bounding-box diagonal (`0.5%`).
    #[arg(long, value_parser = parse_length)]
    pub max_error: Option<Length>,

    /// Keep every boundary vertex in place (the default; gives the tightest bound).
    #[arg(long, conflicts_with = "free_boundary")]
    pub lock_boundary: bool,

    /// Let boundary vertices collapse along boundary edges (looser bound near holes).
    #[arg(long)]
    pub free_boundary: bool,

    /// Where the kept vertex of each collapse goes.
    #[arg(long, value_enum, default_value = PLACEMENTS[0].0)]
    pub placement: PlacementArg,

    /// In which order collapses are applied (the bound is certified with each).
    #[arg(long, value_enum, default_value_t = OrderArg::Auto)]
    pub order: OrderArg,

    /// After simplifying, also measure the symmetric Hausdorff distance between input and
    /// output: the largest distance from every vertex, edge midpoint and 100,000 random
    /// points of each surface to the other. It is a sampled LOWER bound of the true
    /// distance (the error bound is the certified UPPER bound), and costs about as much as
    /// reading the mesh again.
    #[arg(long)]
    pub measure: bool,

    #[command(flatten)]
    pub print: OutputArgs,
}

/// The placements offered by `--placement`: name, placement, help. The first is the
/// default. One line per placement.
pub const PLACEMENTS: &[(&str, Placement, &str)] = &[
    (
        "subset",
        Placement::Subset,
        "half-edge collapses: every output vertex is an input vertex",
    ),
    (
        "optimal",
        Placement::Optimal,
        "full-edge collapses to the quadric-optimal position (when its certified error is smaller)",
    ),
];

/// A `--placement` value: an index into [`PLACEMENTS`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlacementArg(usize);

/// Every `--placement` value, in the order of [`PLACEMENTS`].
static PLACEMENT_ARGS: [PlacementArg; PLACEMENTS.len()] = {
    let mut all = [PlacementArg(0); PLACEMENTS.len()];
    let mut i = 0;
    while i < all.len() {
        all[i] = PlacementArg(i);
        i += 1;
    }
    all
};

impl PlacementArg {
    /// The placement's name on the command line and in reports.
    pub fn name(self) -> &'static str {
        PLACEMENTS.get(self.0).map_or(PLACEMENTS[0].0, |p| p.0)
    }

    /// The simplifier's placement.
    pub fn placement(self) -> Placement {
        PLACEMENTS.get(self.0).map_or(PLACEMENTS[0].1, |p| p.1)
    }
}

impl ValueEnum for PlacementArg {
    fn value_variants<'a>() -> &'a [Self] {
        &PLACEMENT_ARGS
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        PLACEMENTS
            .get(self.0)
            .map(|&(name, _, help)| PossibleValue::new(name).help(help))
    }
}

/// A length on the command line: an absolute distance (`0.002`) or a percentage of the
/// bounding-box diagonal (`2%`), as [`Length`]'s `FromStr` reads it.
fn parse_length(text: &str) -> Result<Length, String> {
    text.parse()
        .map_err(|e: sphaera::mesh::ParseLengthError| e.to_string())
}

/// Arguments of `sphaera info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// The mesh file (OBJ, PLY, STL, OFF, glTF/GLB); the embedded bunny when omitted.
    pub mesh: Option<PathBuf>,

    #[command(flatten)]
    pub output: OutputArgs,
}

/// How a result is printed; shared by every subcommand.
#[derive(Debug, Args)]
pub struct OutputArgs {
    /// Print the result as one JSON document on stdout instead of text.
    #[arg(long)]
    pub json: bool,
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    use super::*;

    #[test]
    fn command_line_is_well_formed() {
        Cli::command().debug_assert();
    }

    #[test]
    fn max_error_takes_distances_and_percentages() {
        assert_eq!(parse_length("0.002"), Ok(Length::Absolute(0.002)));
        assert_eq!(parse_length("0.5%"), Ok(Length::RelativeToDiagonal(0.005)));
        assert!(parse_length("abc").is_err());
        assert!(parse_length("-1").is_err());
        assert!(parse_length("NaN%").is_err());
    }

    #[test]
    fn directions_parse_as_three_numbers() {
        assert_eq!(parse_direction("0,0,1"), Ok([0.0, 0.0, 1.0]));
        assert_eq!(parse_direction(" -1, 0.5 ,2"), Ok([-1.0, 0.5, 2.0]));
        for bad in ["1,2", "1,2,3,4", "a,b,c", "0,0,0", "inf,0,1", "NaN,0,1"] {
            assert!(parse_direction(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn placements_parse_by_name() {
        for (i, &(name, placement, _)) in PLACEMENTS.iter().enumerate() {
            let parsed = PlacementArg::from_str(name, false).expect("a known placement");
            assert_eq!(parsed, PlacementArg(i));
            assert_eq!(parsed.name(), name);
            assert_eq!(parsed.placement(), placement);
        }
        assert!(PlacementArg::from_str("nowhere", false).is_err());
    }
}
