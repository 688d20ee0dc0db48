//! The CSV rows and labels the tables pick.

use super::super::spec::Filter;

/// The colliders of `scene_time_vs_error.csv`, as the table names them.
pub(super) const SCENE_COLLIDERS: &[(&str, &str)] = &[
    ("sphaera 10%", "Sphaera, tree level for 10%"),
    ("sphaera 5%", "Sphaera, tree level for 5%"),
    ("sphaera 2%", "Sphaera, tree level for 2%"),
    (
        "sphaera 1%",
        "Sphaera, tree level for 1% (the 2 % run's colliders)",
    ),
    (
        "sphaera 0.5%",
        "Sphaera, tree level for 0.5% (the 2 % run's colliders)",
    ),
    ("sphaera 2px", "Sphaera, tree level for 2px"),
    ("sphaera cut 10%", "Sphaera, smallest tree cut for 10%"),
    ("sphaera cut 5%", "Sphaera, smallest tree cut for 5%"),
    ("sphaera cut 2%", "Sphaera, smallest tree cut for 2%"),
];
/// The silhouette labellings of `silhouette_error_vs_triangles.csv`.
pub(super) const OUTLINE_NEAREST: Filter = &[("method", "outline, nearest camera, 2 cells")];
/// With the internal silhouettes (the paper's default).
pub(super) const OUTLINE_AND_INTERNAL: Filter =
    &[("method", "outline and internal, nearest camera, 2 cells")];
/// The outline, the mean of the 4 nearest cameras.
pub(super) const OUTLINE_MEAN_4: Filter = &[("method", "outline, mean of 4 nearest, 2 cells")];
/// The engines of `hausdorff_gap_vs_time.csv`.
pub(super) const HAUSDORFF_ENGINES: &[(&str, &str)] = &[
    ("sphaera", "Sphaera, all told, 2 cores"),
    ("meshsweeper", "Meshsweeper (paper), hierarchies not timed"),
    ("cascading_upper_bounds", "cascading-upper-bounds"),
];
/// The methods of `medial_static_vs_adaptive.csv`.
pub(super) const MEDIAL_METHODS: &[(&str, &str)] = &[("static+cover", "static + coverage")];
/// The outlines of the HAL experiments.
pub(super) const HAL_OUTLINES: &[(&str, &str)] = &[
    ("polygons/luxembourg.txt", "Luxembourg"),
    ("polygons/netherlands.txt", "Netherlands"),
    ("polygons/belgium.txt", "Belgium"),
    ("polygons/united-kingdom.txt", "United Kingdom"),
    ("polygons/norway.txt", "Norway"),
    ("polygons/afro-eurasia.txt", "Afro-Eurasia"),
    ("polygons/americas.txt", "Americas"),
    ("polygons/americas.txt refined ×16", "Americas refined ×16"),
];
/// The HAL tree's rows of `hal_query_speed.csv`.
pub(super) const HAL_TREE: Filter = &[("method", "HAL tree")];
/// The HAL trees' rows of `hal_multipolygon_speed.csv`.
pub(super) const HAL_MULTIPOLYGON: Filter = &[("method", "HAL multipolygon")];
/// Brute force's.
pub(super) const BRUTE_FORCE: Filter = &[("method", "brute force")];
/// The uniform levels of `hal_width_vs_size.csv`.
pub(super) const UNIFORM: Filter = &[("approximation", "uniform")];

/// The Panda's rows of `robot_budgets.csv`.
pub(super) const PANDA: Filter = &[("robot", "robots/urdf/franka_panda/panda.urdf")];
/// The KUKA's.
pub(super) const KUKA: Filter = &[("robot", "robots/urdf/kuka_iiwa/model.urdf")];
/// Sphaera's rows of `robot_protrusion_vs_spheres.csv`.
pub(super) const ROBOT_SPHAERA: Filter = &[("method", "sphaera")];
/// The voxel baseline's.
pub(super) const VOXELS: Filter = &[("method", "voxel_kmeans")];
/// morphit-rs's rows of `robot_vs_morphit.csv`, as returned.
pub(super) const MORPHIT_RAW: Filter = &[("method", "morphit_raw")];
/// Grown to cover.
pub(super) const MORPHIT_GROWN: Filter = &[("method", "morphit_grown")];

/// The meshes of `spheretree_similarity.csv`, as the table names them.
pub(super) const SIMILARITY_MESHES: &[(&str, &str)] = &[
    ("cube", "unit cube (`shapes::cube(1.0, 4)`)"),
    ("fandisk.obj", "`fandisk.obj`"),
    ("cylinder", "cylinder (`shapes::cylinder(0.5, 2.0, 32)`)"),
    ("bunny_lowres.obj", "`bunny_lowres.obj`"),
];

/// The CSV row of tree level 1 (2, 3) of the sphere-tree tables.
pub(super) const LEVEL_1: Filter = &[("level", "1")];
/// Level 2.
pub(super) const LEVEL_2: Filter = &[("level", "2")];
/// Level 3.
pub(super) const LEVEL_3: Filter = &[("level", "3")];
/// The defaults of `silhouette_vs_simplify.csv` (widened region, ¼ e and ¼ cell).
pub(super) const GUIDED_DEFAULT: Filter = &[("method", "default: widened, f = 0.25, 1/4 cell")];
/// The paper's rule there (corners, `e · f` alone): the defaults before issue 40.
pub(super) const GUIDED_PAPER: Filter = &[("method", "paper: corners, f = 0.25")];
/// The other variants of `silhouette_vs_simplify.csv`.
pub(super) const GUIDED_CORNERS_CELL: Filter = &[("method", "corners, 1/4 cell")];
/// The certified region.
pub(super) const GUIDED_CERTIFIED: Filter = &[("method", "certified, 1/4 cell")];
/// With the internal silhouettes the camera sees.
pub(super) const GUIDED_INTERNAL: Filter =
    &[("method", "internal silhouettes too, widened, 1/4 cell")];
/// The paper's factor swept with the widened region, no cap in cells.
pub(super) const GUIDED_F_01: Filter = &[("method", "widened, f = 0.1")];
/// See [`GUIDED_F_01`].
pub(super) const GUIDED_F_05: Filter = &[("method", "widened, f = 0.5")];
/// The scene's coarser labels.
pub(super) const GUIDED_SCENE_LABELS: Filter = &[(
    "method",
    "the scene's labels (30°, 128²), widened, 1/4 cell",
)];
