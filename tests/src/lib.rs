//! Sphaera's cross-crate tests, and the one home of the helpers that tests, benches,
//! examples and the fuzz target share.
//!
//! # The tests (`tests/tests/`)
//!
//! Where one crate's output is checked by another crate, or against brute force and
//! parry3d:
//!
//! | file | what checks what |
//! |---|---|
//! | `simplify_bound_vs_hausdorff.rs` | the simplifier's error bound against `sphaera-sweep`'s certified Hausdorff bracket, and the bracket against the parry-sampled distance, on every mesh of the shared data |
//! | `spheretree_vs_sweep.rs` | for every method, the certified and construction errors of every node against sweep's exact distances, and (medial methods) coverage against independent surface samples |
//! | `medial_vs_delaunay.rs` | the medial approximation's Delaunay `validate` after every step, its Voronoi spheres empty by brute force, its sphere errors against sweep's distances |
//! | `delaunay_fuzz_replay.rs` | the Delaunay fuzz body ([`delaunay_fuzz`]) on proptest's bytes |
//! | `facade.rs` | the `sphaera` facade used as a user writes it: a broken re-export fails to compile |
//! | `silhouette_image_reference.rs` | [`silhouette_image`] against pixel counts known in closed form: a cube's face, a disc, a perspective square |
//! | `regions_reference.rs` | [`regions`] against answers known in closed form: rectangles and boxes by their coordinates, a self-crossing star, boxes meeting by their intervals |
//! | `hausdorff_sampling.rs`, `geometry_real_meshes.rs`, `winding_real_meshes.rs`, `data_topology.rs`, `fixtures.rs` | `sphaera-mesh` and this crate's fixtures against parry3d, brute force and the data README |
//!
//! # The helpers
//!
//! | item | what | used by |
//! |---|---|---|
//! | [`data_dir`], [`mesh_files`], [`expected_stats`] | the shared real meshes | tests of every crate, benches, `sphaera-eval` |
//! | [`hausdorff`] | the sampled Hausdorff distance measured with parry3d-f64 (samples and maxima from `sphaera_query::measure`, plus a local refinement), a lower bound to check certified upper bounds against | the simplify, sweep and sphere-tree tests, this crate's tests, `sphaera-eval` |
//! | [`animal`] | a procedural horned quadruped with thin legs and a tail, the unseen mesh of issue 36 | `sphaera-eval`'s `spheres_vs_count` experiment |
//! | [`awkward`] | generated meshes users bring: a pinched vertex, slivers, a tiny detached component, far-apart components, a thin rod, horns, spikes | the sphere-tree's `awkward` tests (every method, every output format) |
//! | [`brute`] | brute-force point-to-mesh distances and the closeness of exact answers | the closest-point tests of mesh and sweep |
//! | [`random`] | [`SplitMix64`] and the MMIX [`random::Lcg64`], each caller's mapping of words to numbers named | unit tests of mesh (indexed heap), simplify (edge radius, quadric, queue, shared fan) and sweep (queue, polyline hierarchy, Hausdorff bounds); the sweep and sphere-tree integration tests; `sphaera-eval`'s query sets |
//! | [`pattern_search`] | the grid-then-pattern search over a triangle | [`hausdorff`]'s refinement; simplify's edge-radius unit tests |
//! | [`point_sets`] | reproducible and degenerate point sets for Delaunay codes | medial's unit tests (sample grid), integration tests, bench and example; `sphaera-eval`'s Delaunay bench |
//! | [`regions`] | where a point lies in a closed outline or mesh, and whether two outlines or solids meet, by routes independent of `sphaera-hal` (winding numbers with exact signs, parry3d's intersection test) | HAL's tests and the CLI's `hal` tests |
//! | [`silhouette_image`] | silhouette images (pixel centres covered) rasterised by edge functions on a frame of its own, not `sphaera-silhouette`'s | the silhouette tests and `sphaera-eval`'s `silhouette_vs_simplify` experiment |
//! | [`delaunay_fuzz`] | the body of the `delaunay` fuzz target | `fuzz/` (by path) and `delaunay_fuzz_replay.rs` |
//!
//! # Which helper may use which crate
//!
//! Every workspace crate has `sphaera-tests` as a dev-dependency, so a normal dependency of
//! this crate on a workspace crate `X` closes a cycle `X → sphaera-tests → X`. Cargo
//! allows it: `X`'s integration tests, benches and examples link the same `X` as this
//! crate does. But `X`'s **unit tests** (`#[cfg(test)]` in `src/`) are a second copy of
//! `X`, whose types differ from the ones this crate was built against. So:
//!
//! - [`random`], [`pattern_search`] and [`point_sets`] take and return only numbers and
//!   glam's `DVec3` (one glam for everyone): any unit test may use them;
//! - [`hausdorff`], [`brute`], [`awkward`], [`animal`], [`regions`] and [`silhouette_image`] take or return `sphaera-mesh`'s `TriMesh` and [`delaunay_fuzz`] drives
//!   `sphaera-medial`: they serve integration tests, benches, experiments and the fuzz
//!   target only.
//!
//! The normal dependencies are what the helpers need and no more: `sphaera-mesh`,
//! `parry3d-f64` and `rayon` ([`hausdorff`]), `rand` and `rand_chacha` ([`point_sets`]),
//! `sphaera-medial` and `robust` ([`delaunay_fuzz`]; `robust` and parry also [`regions`]). The crates the tests check against
//! each other (`sphaera-simplify`, `sphaera-sweep`, `sphaera-spheretree`, the facade)
//! are dev-dependencies.
//!
//! # The shared meshes
//!
//! The real meshes live outside the repository, in `../shared/data` beside the checkout
//! (override with `SPHAERA_DATA=/path/to/data`). Tests that need them call [`data_dir`]:
//! when the folder is absent they skip with a message, unless `SPHAERA_REQUIRE_DATA=1`
//! (CI sets it), in which case they fail.

use std::path::{Path, PathBuf};

pub mod animal;
pub mod awkward;
pub mod brute;
pub mod delaunay_fuzz;
pub mod hausdorff;
pub mod input_fuzz;
pub mod pattern_search;
pub mod point_sets;
pub mod random;
pub mod regions;
pub mod silhouette_image;

pub use hausdorff::{ReferenceHausdorff, reference_hausdorff};
pub use random::SplitMix64;

/// Where the shared meshes are: `$SPHAERA_DATA`, or `../shared/data` beside the workspace.
pub fn data_root() -> PathBuf {
    match std::env::var_os("SPHAERA_DATA") {
        Some(dir) => PathBuf::from(dir),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/data"),
    }
}

/// The number of cases a property test runs: `ci`, the count sized for the 2-core CI
/// machine, unless `PROPTEST_CASES` is set (a deep run: `PROPTEST_CASES=5000 cargo xtask
/// test`), which then applies to every property of the workspace, as it does to those
/// on proptest's default configuration.
///
/// ```
/// assert!(sphaera_tests::cases(48) > 0);
/// ```
pub fn cases(ci: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.trim().parse::<u32>().ok())
        .filter(|&n| n > 0)
        .unwrap_or(ci)
}

/// Whether a missing data folder must fail the run (`SPHAERA_REQUIRE_DATA=1`).
pub fn data_required() -> bool {
    std::env::var("SPHAERA_REQUIRE_DATA").is_ok_and(|v| v == "1")
}

/// The shared data folder, or `None` (with a message on stderr) when it is absent and not
/// required.
///
/// # Panics
///
/// When the folder is absent and `SPHAERA_REQUIRE_DATA=1`.
pub fn data_dir(test_name: &str) -> Option<PathBuf> {
    let dir = data_root();
    if dir.is_dir() {
        return Some(dir);
    }
    assert!(
        !data_required(),
        "{test_name}: the shared meshes are required (SPHAERA_REQUIRE_DATA=1) but {} is missing",
        dir.display()
    );
    #[allow(clippy::print_stderr)] // a skipped test says why
    {
        eprintln!(
            "{test_name}: skipped, no shared meshes at {} (set SPHAERA_DATA)",
            dir.display()
        );
    }
    None
}

/// The folder of the robot descriptions (URDFs with the meshes they reference), relative
/// to the data folder. Its meshes are assets of the robots rather than catalogued meshes:
/// copies of `robots/franka_panda/` and the KUKA collision STLs, described by the data
/// README apart from its table; [`mesh_files`] leaves them out.
pub const URDF_ASSETS: &str = "robots/urdf";

/// The URDFs of the two shared robots, `(short name, path)`: the Franka Panda and the
/// KUKA iiwa, or nothing (said, or failing under `SPHAERA_REQUIRE_DATA=1`, as
/// [`data_dir`]) when the data folder is absent.
pub fn robot_urdfs(test_name: &str) -> Vec<(&'static str, PathBuf)> {
    let Some(data) = data_dir(test_name) else {
        return Vec::new();
    };
    let dir = data.join(URDF_ASSETS);
    vec![
        ("panda", dir.join("franka_panda/panda.urdf")),
        ("kuka", dir.join("kuka_iiwa/model.urdf")),
    ]
}

/// Every mesh file under `dir` (recursively), sorted by path, relative to `dir`, except
/// the robot descriptions' assets under [`URDF_ASSETS`].
pub fn mesh_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    collect(dir, dir, &mut files);
    files.sort();
    files
}

fn collect(root: &Path, dir: &Path, files: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let is_mesh = path.extension().and_then(|e| e.to_str()).is_some_and(|e| {
            matches!(
                e.to_ascii_lowercase().as_str(),
                "obj" | "ply" | "stl" | "off"
            )
        });
        if path.is_dir() {
            if path.ends_with(URDF_ASSETS) {
                continue;
            }
            collect(root, &path, files);
        } else if is_mesh && let Ok(relative) = path.strip_prefix(root) {
            files.push(relative.to_path_buf());
        }
    }
}

/// One row of the statistics table in `shared/data/README.md` (computed there by trimesh
/// and pymeshlab after merging bit-identical vertex positions).
#[derive(Clone, Debug, PartialEq)]
pub struct ExpectedStats {
    /// Path relative to the data folder, e.g. `robots/kuka_iiwa/link_0.obj`.
    pub file: String,
    /// Vertex records in the file.
    pub vertex_records: usize,
    /// Triangles after loading.
    pub triangles: usize,
    /// No boundary edge and no edge with more than two faces.
    pub closed: bool,
    /// No non-manifold edge and no non-manifold vertex.
    pub manifold: bool,
    /// Connected components.
    pub components: usize,
    /// Edges with a single face.
    pub boundary_edges: usize,
    /// Genus, given for 2-manifold meshes only.
    pub genus: Option<i64>,
    /// Euler characteristic V − E + F of the merged mesh.
    pub euler_characteristic: i64,
    /// Bounding-box diagonal of the referenced vertices (4 significant digits).
    pub bbox_diagonal: f64,
}

/// Parses the `## Files` table of `README.md` in the data folder.
///
/// # Panics
///
/// If the README is missing or a row does not parse: the fixture is broken.
pub fn expected_stats(data: &Path) -> Vec<ExpectedStats> {
    let readme = std::fs::read_to_string(data.join("README.md"))
        .unwrap_or_else(|e| panic!("cannot read {}/README.md: {e}", data.display()));
    let section = readme
        .split("## Files")
        .nth(1)
        .and_then(|rest| rest.split("\n## ").next())
        .unwrap_or_else(|| panic!("no `## Files` section in the data README"));
    let number = |s: &str| -> i64 {
        s.replace(',', "")
            .parse()
            .unwrap_or_else(|e| panic!("bad number {s:?} in the data README: {e}"))
    };
    section
        .lines()
        .filter(|line| line.starts_with("| `"))
        .map(|line| {
            let cells: Vec<&str> = line.trim_matches('|').split('|').map(str::trim).collect();
            assert_eq!(cells.len(), 12, "unexpected row in the data README: {line}");
            let count = |s: &str| usize::try_from(number(s)).unwrap_or(usize::MAX);
            ExpectedStats {
                file: cells[0].trim_matches('`').to_owned(),
                vertex_records: count(cells[3]),
                triangles: count(cells[4]),
                closed: cells[5] == "yes",
                manifold: cells[6] == "yes",
                components: count(cells[7]),
                boundary_edges: count(cells[8]),
                genus: (cells[9] != "n/a").then(|| number(cells[9])),
                euler_characteristic: number(cells[10]),
                bbox_diagonal: cells[11]
                    .replace(',', "")
                    .parse()
                    .unwrap_or_else(|e| panic!("bad diagonal in {line}: {e}")),
            }
        })
        .collect()
}
