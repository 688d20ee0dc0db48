//! `spheretree_similarity`: how stable the default sphere-tree is under similarity
//! transforms. A sphere-tree's certified worst error, relative to the mesh's size, should
//! not depend on where the mesh sits, how it is turned or what unit it is in; the issue
//! asks that it vary by at most a factor [`TARGET_SPREAD`].
//!
//! For each mesh of [`MESHES`] (a unit cube and a cylinder, both procedural, and
//! `fandisk.obj` and `bunny_lowres.obj` from `shared/data`, skipped with a message when
//! absent), the library's default tree — `Method::default()` with
//! `SphereTreeOptions::default()` at depth [`DEPTH`], branch [`BRANCH`] and seed
//! [`SEED`] — is built on the mesh itself (transform 0, the identity) and on
//! [`TRANSFORMS`] random similarity transforms of it ([`random_similarity`]; the same
//! seeded sequence, [`TRANSFORM_SEED`], for every mesh):
//!
//! - a uniformly random rotation (Shoemake's uniform unit quaternion);
//! - a uniform scale `10^u`, `u` uniform in `[-3, 3]`;
//! - a translation uniform in `[-1000 d, 1000 d]` on each axis, `d` the untransformed
//!   mesh's bounding-box diagonal ([`OFFSET_DIAGONALS`]; after a scale of `10⁻³` the mesh
//!   sits up to √3·10⁶ of its own diagonals from the origin).
//!
//! The transform maps the positions and keeps the triangles ([`transformed`]). Measured
//! per tree: the build time (one run: the surface's preparation and the build, wall-clock
//! with the `parallel` feature), and per level 1 to [`DEPTH`] the certified worst error,
//! `evaluate_set` at a tolerance of [`EVALUATION_TOLERANCE`] of the size, in % of the
//! **size**: the untransformed mesh's bounding-box diagonal times the transform's scale.
//! (Not the transformed mesh's own diagonal: its bounding box turns with it, and a turned
//! cube's box is up to √3 times larger, which alone would swing the figures by that much.)
//! The **spread** of a mesh and level is the largest upper bound over the trees divided
//! by the smallest.
//!
//! Files: `spheretree_similarity.csv` (one row per mesh, transform and level: the scale,
//! the translation in the transformed mesh's diagonals, the spheres, the worst error's
//! lower and upper bounds and the build time; a tree that failed has one row with the
//! error) and `spheretree_similarity.svg` (one panel per mesh: the worst errors per level
//! as points, the identity highlighted, the spread written above each level).

use std::path::Path;

use anyhow::{Context, Result};
use plotters::style::RGBColor;
use sphaera::{
    mesh::{
        DVec3, Length, Surface, TriMesh,
        geometry::Similarity,
        glam::{DAffine3, DQuat},
        shapes,
    },
    spheretree::{EvaluationOptions, Method, evaluate_set},
};
use sphaera_tests::random::SplitMix64;

use super::{BRANCH, DEPTH, EVALUATION_TOLERANCE, SEED, build_tree, tree_options};
use crate::chart::{
    ChartSpec, LegendEntry, Marker, Note, Series, Style, StyledPanel, StyledSeries, XAxis, palette,
    titled_panels, write_csv,
};
use crate::experiments::{load_or_skip, min_time};

/// The experiment's name (`--only spheretree_similarity`) and its chart's.
pub const NAME: &str = "spheretree_similarity";

/// Random similarity transforms per mesh (besides the identity).
pub const TRANSFORMS: usize = 20;

/// Seed of the transforms (the same sequence for every mesh).
pub const TRANSFORM_SEED: u64 = 16;

/// The scale is `10^u` with `u` uniform in `[-LOG_SCALE, LOG_SCALE]`.
pub const LOG_SCALE: f64 = 3.0;

/// The translation is uniform in `[-OFFSET_DIAGONALS · d, OFFSET_DIAGONALS · d]` on each
/// axis, `d` the untransformed mesh's bounding-box diagonal.
pub const OFFSET_DIAGONALS: f64 = 1e3;

/// The largest spread (largest / smallest worst error of a level) the issue accepts.
pub const TARGET_SPREAD: f64 = 1.1;

/// Where a mesh comes from.
#[derive(Debug, Clone, Copy)]
pub enum Source {
    /// A procedural shape: [`procedural`] builds it.
    Procedural,
    /// A file of `shared/data`.
    File,
}

/// The meshes: name (the CSV's first column: the file, or the shape), label, source.
pub const MESHES: &[(&str, &str, Source)] = &[
    ("cube", "unit cube (procedural)", Source::Procedural),
    ("fandisk.obj", "fandisk", Source::File),
    ("cylinder", "cylinder (procedural)", Source::Procedural),
    ("bunny_lowres.obj", "bunny low-res", Source::File),
];

/// The procedural mesh `name`: the unit cube (`shapes::cube(1.0, 4)`) or a cylinder of
/// radius ½ and height 2 (`shapes::cylinder(0.5, 2.0, 32)`).
pub fn procedural(name: &str) -> Result<TriMesh> {
    Ok(match name {
        "cube" => shapes::cube(1.0, 4)?,
        "cylinder" => shapes::cylinder(0.5, 2.0, 32)?,
        other => anyhow::bail!("no procedural mesh `{other}`"),
    })
}

/// A random similarity transform for a mesh of bounding-box diagonal `diagonal`: a
/// uniformly random rotation, a scale `10^u` (`u` uniform in `[-LOG_SCALE, LOG_SCALE]`),
/// a translation uniform in `[-OFFSET_DIAGONALS · diagonal, OFFSET_DIAGONALS · diagonal]`
/// on each axis.
pub fn random_similarity(rng: &mut SplitMix64, diagonal: f64) -> Result<Similarity> {
    // Shoemake's uniform unit quaternion.
    let (u1, u2, u3) = (rng.unit(), rng.unit(), rng.unit());
    let tau = std::f64::consts::TAU;
    let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
    let rotation = DQuat::from_xyzw(
        a * (tau * u2).sin(),
        a * (tau * u2).cos(),
        b * (tau * u3).sin(),
        b * (tau * u3).cos(),
    )
    .normalize();
    let scale = 10f64.powf(rng.range(-LOG_SCALE, LOG_SCALE));
    let reach = OFFSET_DIAGONALS * diagonal;
    let translation = DVec3::new(
        rng.range(-reach, reach),
        rng.range(-reach, reach),
        rng.range(-reach, reach),
    );
    Similarity::new(DAffine3::from_scale_rotation_translation(
        DVec3::splat(scale),
        rotation,
        translation,
    ))
    .context("not a similarity")
}

/// `mesh` with every position mapped by `map`, the same triangles.
pub fn transformed(mesh: &TriMesh, map: &Similarity) -> Result<TriMesh> {
    let positions = mesh.positions().iter().map(|&p| map.point(p)).collect();
    TriMesh::new(positions, mesh.triangles().to_vec()).context("cannot transform the mesh")
}

/// One evaluated level; errors in % of the untransformed mesh's diagonal times the scale.
#[derive(Debug, Clone, PartialEq)]
struct Level {
    level: usize,
    spheres: usize,
    lower_pct: f64,
    upper_pct: f64,
}

/// One tree: transform `transform` (0: the identity) of mesh `mesh`.
#[derive(Debug, Clone, PartialEq)]
struct Tree {
    mesh: &'static str,
    transform: usize,
    scale: f64,
    /// Length of the translation, in the transformed mesh's diagonals.
    offset_diagonals: f64,
    seconds: f64,
    levels: Vec<Level>,
    /// Why the tree could not be built or evaluated.
    failure: Option<String>,
}

impl Tree {
    /// The worst error (upper end) of `level`, in % of the diagonal.
    fn upper_pct(&self, level: usize) -> Option<f64> {
        self.levels
            .iter()
            .find(|l| l.level == level)
            .map(|l| l.upper_pct)
    }
}

/// A charted mesh: name, panel title.
struct Charted {
    mesh: &'static str,
    title: String,
}

pub fn run(data: &Path, out: &Path) -> Result<()> {
    let started = std::time::Instant::now();
    let method = Method::default();
    eprintln!(
        "default method: {}; {TRANSFORMS} similarity transforms per mesh",
        method.name()
    );
    let mut trees = Vec::new();
    let mut charted = Vec::new();
    for &(name, label, source) in MESHES {
        let mesh = match source {
            Source::Procedural => procedural(name)?,
            Source::File => match load_or_skip(data, name)? {
                Some(mesh) => mesh,
                None => continue,
            },
        };
        charted.push(Charted {
            mesh: name,
            title: format!("{label} ({} triangles)", mesh.triangle_count()),
        });
        measure_mesh(name, &mesh, &mut trees)?;
    }
    let spreads = spreads(&trees);
    eprintln!("spread = largest / smallest certified worst error (target ≤ {TARGET_SPREAD}):");
    for s in &spreads {
        eprintln!(
            "  {:<17} level {}: {:.3} ({:.3}–{:.3} %, {} trees)",
            s.mesh, s.level, s.spread, s.smallest_pct, s.largest_pct, s.trees
        );
    }
    write_table(out, &trees)?;
    draw(out, &trees, &charted, &spreads)?;
    eprintln!("{NAME}: {:.0} s", started.elapsed().as_secs_f64());
    Ok(())
}

/// The identity and [`TRANSFORMS`] random similarity transforms of `mesh`: build,
/// evaluate levels 1 to [`DEPTH`].
fn measure_mesh(name: &'static str, mesh: &TriMesh, trees: &mut Vec<Tree>) -> Result<()> {
    let diagonal = mesh.bounding_box_diagonal();
    let mut rng = SplitMix64::new(TRANSFORM_SEED);
    for transform in 0..=TRANSFORMS {
        let map = if transform == 0 {
            Similarity::IDENTITY
        } else {
            random_similarity(&mut rng, diagonal)?
        };
        let moved = if transform == 0 {
            mesh.clone()
        } else {
            transformed(mesh, &map)?
        };
        let moved_diagonal = moved.bounding_box_diagonal();
        let mut tree = Tree {
            mesh: name,
            transform,
            scale: map.scale(),
            offset_diagonals: map.translation().length() / moved_diagonal,
            seconds: f64::NAN,
            levels: Vec::new(),
            failure: None,
        };
        // The size every error is relative to: the untransformed diagonal, scaled. (The
        // transformed mesh's own bounding box turns with it: a turned cube's box is up
        // to √3 times larger, which would swing the figures by itself.)
        let size = diagonal * map.scale();
        if let Err(e) = measure_tree(&moved, size, &mut tree) {
            tree.failure = Some(format!("{e:#}"));
        }
        report(&tree);
        trees.push(tree);
    }
    Ok(())
}

/// Builds the default tree of `mesh` (timed) and evaluates its levels into `tree`, at a
/// tolerance of [`EVALUATION_TOLERANCE`] times `size`, errors in % of `size`.
fn measure_tree(mesh: &TriMesh, size: f64, tree: &mut Tree) -> Result<()> {
    let options = tree_options(Method::default());
    let (seconds, built) = min_time(1, || build_tree(&options, mesh))?;
    tree.seconds = seconds;
    let surface = Surface::new(mesh).context("cannot prepare the surface")?;
    let evaluation =
        EvaluationOptions::default().with_tolerance(Length::Absolute(EVALUATION_TOLERANCE * size));
    for level in 1..built.level_count().min(DEPTH + 1) {
        let spheres = built.level_spheres(level);
        let result = evaluate_set(&surface, &spheres, &evaluation)
            .with_context(|| format!("cannot evaluate level {level}"))?;
        tree.levels.push(Level {
            level,
            spheres: spheres.len(),
            lower_pct: 100.0 * result.worst_lower / size,
            upper_pct: 100.0 * result.worst_upper / size,
        });
    }
    Ok(())
}

fn report(tree: &Tree) {
    let levels: Vec<String> = tree
        .levels
        .iter()
        .map(|l| {
            format!(
                "L{} {:>3} sph {:7.4}–{:7.4} %",
                l.level, l.spheres, l.lower_pct, l.upper_pct
            )
        })
        .collect();
    eprintln!(
        "{:<17} #{:<2} scale {:9.3e} offset {:9.3e} diag  build {:6.2} s  {}{}",
        tree.mesh,
        tree.transform,
        tree.scale,
        tree.offset_diagonals,
        tree.seconds,
        levels.join("  "),
        tree.failure
            .as_deref()
            .map(|f| format!("FAILED: {f}"))
            .unwrap_or_default()
    );
}

/// The spread of one mesh and level.
#[derive(Debug, Clone, PartialEq)]
struct Spread {
    mesh: &'static str,
    level: usize,
    /// Trees with this level.
    trees: usize,
    smallest_pct: f64,
    largest_pct: f64,
    /// `largest_pct / smallest_pct`.
    spread: f64,
}

/// Per mesh (in the order of `trees`) and level 1 to [`DEPTH`]: the spread of the worst
/// errors' upper bounds over the trees that have the level.
fn spreads(trees: &[Tree]) -> Vec<Spread> {
    let mut meshes: Vec<&'static str> = trees.iter().map(|t| t.mesh).collect();
    meshes.dedup();
    let mut spreads = Vec::new();
    for mesh in meshes {
        for level in 1..=DEPTH {
            let errors: Vec<f64> = trees
                .iter()
                .filter(|t| t.mesh == mesh)
                .filter_map(|t| t.upper_pct(level))
                .collect();
            if errors.is_empty() {
                continue;
            }
            let smallest = errors.iter().copied().fold(f64::INFINITY, f64::min);
            let largest = errors.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            spreads.push(Spread {
                mesh,
                level,
                trees: errors.len(),
                smallest_pct: smallest,
                largest_pct: largest,
                spread: largest / smallest,
            });
        }
    }
    spreads
}

/// One row per mesh, transform and level (one row with the error for a failed tree).
fn write_table(out: &Path, trees: &[Tree]) -> Result<()> {
    let mut table = Vec::new();
    for t in trees {
        let seconds = if t.seconds.is_finite() {
            format!("{:.4}", t.seconds)
        } else {
            String::new()
        };
        let row = |level: String, measured: [String; 3], failure: String| {
            let [spheres, lower, upper] = measured;
            vec![
                t.mesh.to_owned(),
                t.transform.to_string(),
                level,
                format!("{:.6e}", t.scale),
                format!("{:.6e}", t.offset_diagonals),
                spheres,
                lower,
                upper,
                seconds.clone(),
                failure,
            ]
        };
        for l in &t.levels {
            table.push(row(
                l.level.to_string(),
                [
                    l.spheres.to_string(),
                    format!("{:.4}", l.lower_pct),
                    format!("{:.4}", l.upper_pct),
                ],
                String::new(),
            ));
        }
        if let Some(failure) = &t.failure {
            table.push(row(
                String::new(),
                Default::default(),
                failure.replace([',', '\n'], ";"),
            ));
        }
    }
    write_csv(
        &out.join(format!("{NAME}.csv")),
        &[
            "mesh",
            "transform",
            "level",
            "scale",
            "offset_diagonals",
            "spheres",
            "worst_error_lower_pct_diag",
            "worst_error_upper_pct_diag",
            "build_seconds",
            "failure",
        ],
        &table,
    )
}

/// The x of transform `transform` at `level`: the identity on the level, the others
/// spread a little either side so that equal errors stay visible.
fn dodge(level: usize, transform: usize) -> f64 {
    if transform == 0 {
        level as f64
    } else {
        level as f64 + 0.012 * (transform as f64 - (TRANSFORMS as f64 + 1.0) / 2.0)
    }
}

/// Colour of a spread that meets [`TARGET_SPREAD`], and of one that does not.
fn spread_color(spread: f64) -> RGBColor {
    if spread <= TARGET_SPREAD {
        palette(2)
    } else {
        palette(1)
    }
}

/// One panel per charted mesh: worst error against level, the identity as a black
/// square, the transforms as blue dots, the spread above each level (green if it meets
/// [`TARGET_SPREAD`], red if not).
fn draw(out: &Path, trees: &[Tree], charted: &[Charted], spreads: &[Spread]) -> Result<()> {
    let identity_style = Style {
        color: RGBColor(0, 0, 0),
        marker: Marker::Square,
        filled: true,
        line: false,
    };
    let moved_style = Style {
        color: palette(0),
        marker: Marker::Circle,
        filled: true,
        line: false,
    };
    let mut series = Vec::new();
    let mut notes = Vec::new();
    for c in charted {
        let mut moved = Series::new("transformed");
        let mut identity = Series::new("identity");
        for t in trees.iter().filter(|t| t.mesh == c.mesh) {
            let points = t
                .levels
                .iter()
                .map(|l| (dodge(l.level, t.transform), l.upper_pct));
            if t.transform == 0 {
                identity.points.extend(points);
            } else {
                moved.points.extend(points);
            }
        }
        series.push(vec![
            StyledSeries::new(moved, moved_style),
            StyledSeries::new(identity, identity_style),
        ]);
        notes.push(
            spreads
                .iter()
                .filter(|s| s.mesh == c.mesh)
                .map(|s| {
                    let verdict = if s.spread <= TARGET_SPREAD {
                        '≤'
                    } else {
                        '>'
                    };
                    Note {
                        at: (s.level as f64, 1.15 * s.largest_pct),
                        text: format!("spread {:.3} ({verdict} {TARGET_SPREAD})", s.spread),
                        color: spread_color(s.spread),
                    }
                })
                .collect::<Vec<_>>(),
        );
    }
    let sizes: Vec<String> = (1..=DEPTH)
        .map(|l| BRANCH.pow(l as u32).to_string())
        .collect();
    let x_label = format!("tree level (at most {} spheres)", sizes.join(", "));
    let panels: Vec<StyledPanel<'_>> = charted
        .iter()
        .zip(series.iter().zip(&notes))
        .map(|(c, (series, notes))| StyledPanel {
            spec: ChartSpec {
                title: &c.title,
                x_label: &x_label,
                y_label: "certified worst error, % of diagonal × scale",
            },
            x_axis: XAxis::Integers(0.5..DEPTH as f64 + 0.5),
            series,
            notes,
        })
        .collect();
    let title = format!(
        "Default sphere-tree ({}, depth {DEPTH}, branch {BRANCH}, seed {SEED}) under \
         {TRANSFORMS} random similarities (uniform rotation, scale 10^±{LOG_SCALE}, offset \
         ≤ {OFFSET_DIAGONALS:.0e} diagonals): spread = largest / smallest worst error per \
         level, target ≤ {TARGET_SPREAD}",
        Method::default().name()
    );
    let legend = [
        LegendEntry {
            label: "the mesh as given".to_owned(),
            style: identity_style,
        },
        LegendEntry {
            label: format!("{TRANSFORMS} random similarities"),
            style: moved_style,
        },
    ];
    titled_panels(&out.join(format!("{NAME}.svg")), &title, &panels, &legend)
}

#[cfg(test)]
mod tests {
    use super::super::tests::scratch;
    use super::*;

    #[test]
    fn random_similarities_are_seeded_rotations_scales_and_offsets() -> Result<()> {
        let mut rng = SplitMix64::new(TRANSFORM_SEED);
        let mut again = SplitMix64::new(TRANSFORM_SEED);
        for _ in 0..50 {
            let map = random_similarity(&mut rng, 2.0)?;
            assert_eq!(map, random_similarity(&mut again, 2.0)?);
            let scale = map.scale();
            assert!((1e-3..=1e3).contains(&scale), "{scale}");
            // A rotation times the scale: orthogonal columns of length `scale`, det > 0.
            let m = map.affine().matrix3 * (1.0 / scale);
            assert!((m.determinant() - 1.0).abs() < 1e-12);
            let t = map.translation();
            assert!(t.abs().max_element() <= OFFSET_DIAGONALS * 2.0);
        }
        Ok(())
    }

    #[test]
    fn transformed_meshes_keep_triangles_and_scale_the_diagonal() -> Result<()> {
        let cube = procedural("cube")?;
        let mut rng = SplitMix64::new(3);
        let map = random_similarity(&mut rng, cube.bounding_box_diagonal())?;
        let moved = transformed(&cube, &map)?;
        assert_eq!(moved.triangles(), cube.triangles());
        let ratio = moved.surface_area() / cube.surface_area();
        assert!((ratio / (map.scale() * map.scale()) - 1.0).abs() < 1e-9);
        assert!(procedural("cylinder")?.triangle_count() > 0);
        assert!(procedural("sphere").is_err());
        Ok(())
    }

    fn tree(mesh: &'static str, transform: usize, uppers: [f64; 3]) -> Tree {
        Tree {
            mesh,
            transform,
            scale: 10f64.powi(transform as i32 - 1),
            offset_diagonals: 5.0 * transform as f64,
            seconds: 1.5,
            levels: uppers
                .iter()
                .enumerate()
                .map(|(i, &u)| Level {
                    level: i + 1,
                    spheres: BRANCH.pow(i as u32 + 1),
                    lower_pct: u - 0.01,
                    upper_pct: u,
                })
                .collect(),
            failure: None,
        }
    }

    #[test]
    fn spreads_table_and_chart() -> Result<()> {
        let mut failed = tree("cube", 2, [0.0; 3]);
        failed.levels.clear();
        failed.failure = Some("bad, very bad".to_owned());
        let trees = [
            tree("cube", 0, [10.0, 5.0, 2.0]),
            tree("cube", 1, [10.5, 6.0, 2.0]),
            failed,
            tree("fandisk.obj", 0, [8.0, 4.0, 2.0]),
        ];
        let s = spreads(&trees);
        assert_eq!(s.len(), 6);
        assert_eq!((s[0].mesh, s[0].level, s[0].trees), ("cube", 1, 2));
        assert!((s[0].spread - 1.05).abs() < 1e-12);
        assert!((s[1].spread - 1.2).abs() < 1e-12);
        assert!((s[3].spread - 1.0).abs() < 1e-12);
        let dir = scratch("similarity");
        write_table(&dir, &trees)?;
        let charted = [
            Charted {
                mesh: "cube",
                title: "cube title".to_owned(),
            },
            Charted {
                mesh: "fandisk.obj",
                title: "fandisk title".to_owned(),
            },
        ];
        draw(&dir, &trees, &charted, &s)?;
        let csv = std::fs::read_to_string(dir.join(format!("{NAME}.csv")))?;
        // 3 trees × 3 levels, one row for the failed tree.
        assert_eq!(csv.lines().count(), 1 + 9 + 1);
        let columns = csv.lines().next().map(|h| h.split(',').count());
        for line in csv.lines().skip(1) {
            assert_eq!(Some(line.split(',').count()), columns, "{line}");
        }
        assert!(csv.contains("cube,1,2,1.000000e0,5.000000e0,64,5.9900,6.0000,1.5000,\n"));
        assert!(csv.contains("cube,2,,1.000000e1,1.000000e1,,,,1.5000,bad; very bad\n"));
        let svg = std::fs::read_to_string(dir.join(format!("{NAME}.svg")))?;
        for text in [
            "cube title",
            "fandisk title",
            "spread 1.050 (≤ 1.1)",
            "spread 1.200 (&gt; 1.1)",
            Method::default().name(),
            "target ≤ 1.1",
        ] {
            assert!(svg.contains(text), "{text}");
        }
        std::fs::remove_dir_all(&dir)?;
        Ok(())
    }

    #[test]
    fn dodged_transforms_stay_near_their_level() {
        assert!((dodge(2, 0) - 2.0).abs() < 1e-15);
        for t in 1..=TRANSFORMS {
            let d = dodge(2, t) - 2.0;
            assert!(d.abs() < 0.15 && d.abs() > 0.0, "{t}");
        }
    }
}
