//! `sphaera hausdorff`: certified Hausdorff distance between two meshes.

use std::time::Instant;

use anyhow::{Context, Result};
use serde::Serialize;
use sphaera::{
    mesh::{
        Length, TriMesh,
        io::{self, PlyEncoding, colormap},
    },
    simplify::{SimplifyOptions, simplify},
    sweep::{
        DirectedHausdorff, Direction, HausdorffDistance, HausdorffOptions, HausdorffProgress,
        Sweeper, build_hierarchy, hausdorff_with_progress, meshsweeper_hausdorff_with_progress,
    },
};

use crate::{
    cli::{HausdorffArgs, HausdorffEngineArg},
    input::read_mesh,
    output::{print_report, thousands},
    progress,
};

/// The fraction of triangles kept when B is A's own simplification.
const DEFAULT_RATIO: f64 = 0.15;

/// Everything `sphaera hausdorff` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    /// The first mesh's file, or `<embedded bunny_lowres.obj>`.
    a: String,
    /// The second mesh's file, or `A simplified to 15 %`.
    b: String,
    triangles_a: usize,
    triangles_b: usize,
    /// `symmetric` or `one-sided`.
    mode: &'static str,
    /// `trees` (the default) or `meshsweeper`.
    engine: &'static str,
    /// The tolerance in mesh units.
    tolerance: f64,
    /// Certified: the true distance lies in `[lower, upper]`.
    lower: f64,
    upper: f64,
    /// Both bounds as fractions of the joint bounding-box diagonal.
    lower_relative: f64,
    upper_relative: f64,
    /// `a_to_b` or `b_to_a`: the direction where the maximum is reached.
    dominating: &'static str,
    /// `false` if `--max-samples` stopped the refinement first (bounds still certified).
    converged: bool,
    a_to_b: Side,
    b_to_a: Option<Side>,
    /// When B is A's simplification: the simplifier's certified error bound.
    simplifier_bound: Option<f64>,
    colors: Option<String>,
    seconds: Seconds,
}

/// One direction's figures.
#[derive(Debug, Serialize)]
struct Side {
    lower: f64,
    upper: f64,
    /// Where the lower bound is reached, and its closest point on the other mesh.
    farthest: [f64; 3],
    closest: [f64; 3],
    samples: usize,
    /// Samples whose distance was certified by a closest-point query (the others only
    /// needed a near point, from a local walk).
    certified_samples: usize,
    refined_triangles: usize,
}

#[derive(Debug, Serialize)]
struct Seconds {
    load: f64,
    /// Simplifying A when B was omitted.
    simplify: f64,
    /// Building both hierarchies of error spheres (`meshsweeper` engine only).
    hierarchies: Option<f64>,
    /// The Hausdorff computation itself (with the `trees` engine, the trees' build
    /// included).
    hausdorff: f64,
}

pub fn run(args: &HausdorffArgs, quiet: bool) -> Result<()> {
    if let Some(path) = &args.colors {
        check_ply(path)?;
    }
    let input_a = read_mesh(args.a.as_deref(), quiet)?;
    let mesh_a = &input_a.loaded.mesh;
    let mut load = input_a.seconds;
    let (mesh_b, b_name, simplifier_bound, simplify_seconds) = match &args.b {
        Some(path) => {
            let input_b = read_mesh(Some(path), quiet)?;
            load += input_b.seconds;
            (input_b.loaded.mesh, input_b.source, None, 0.0)
        }
        None => {
            let spinner = progress::spinner(quiet, "simplifying A to 15 % (B was omitted)");
            let started = Instant::now();
            let simplified = simplify(
                mesh_a,
                &SimplifyOptions::default().with_target_ratio(DEFAULT_RATIO),
            );
            spinner.finish_and_clear();
            let simplified = simplified?;
            (
                simplified.mesh,
                "A simplified to 15 % of its triangles".to_owned(),
                Some(simplified.error_bound),
                started.elapsed().as_secs_f64(),
            )
        }
    };

    let diagonal = joint_diagonal(mesh_a, &mesh_b);
    let tolerance = args.tolerance.resolve(diagonal);
    let spinner = progress::spinner(quiet, "querying the vertices");
    let report_progress = |p: &HausdorffProgress| {
        if p.vertices_done < p.vertices {
            spinner.set_message(format!(
                "querying the vertices: {} of {}",
                thousands(p.vertices_done),
                thousands(p.vertices)
            ));
        } else {
            spinner.set_message(format!(
                "refining: {} samples, gap {:.3e}",
                thousands(p.samples),
                p.upper - p.lower
            ));
        }
    };
    let options = HausdorffOptions::default()
        .with_tolerance(Length::Absolute(tolerance))
        .with_max_samples(args.max_samples)
        .with_symmetric(!args.one_sided);
    let (result, hierarchy_seconds, hausdorff_seconds) = match args.engine {
        HausdorffEngineArg::Trees => {
            let started = Instant::now();
            let result = hausdorff_with_progress(mesh_a, &mesh_b, &options, &report_progress);
            (result, None, started.elapsed().as_secs_f64())
        }
        HausdorffEngineArg::Meshsweeper => {
            spinner.set_message("building the hierarchies of error spheres");
            let (result, hierarchies, seconds) =
                by_meshsweeper(mesh_a, &mesh_b, &options, &report_progress)?;
            (result, Some(hierarchies), seconds)
        }
    };
    spinner.finish_and_clear();
    let result = result?;

    if let Some(path) = &args.colors {
        let colors = colormap::scalars_to_colors(&result.a_to_b.vertex_distances, None);
        io::write_ply(path, mesh_a, PlyEncoding::BinaryLittleEndian, Some(&colors))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }

    let relative = |d: f64| if diagonal > 0.0 { d / diagonal } else { 0.0 };
    let report = Report {
        a: input_a.source,
        b: b_name,
        triangles_a: mesh_a.triangle_count(),
        triangles_b: mesh_b.triangle_count(),
        mode: if args.one_sided {
            "one-sided"
        } else {
            "symmetric"
        },
        engine: match args.engine {
            HausdorffEngineArg::Trees => "trees",
            HausdorffEngineArg::Meshsweeper => "meshsweeper",
        },
        tolerance,
        lower: result.lower,
        upper: result.upper,
        lower_relative: relative(result.lower),
        upper_relative: relative(result.upper),
        dominating: match result.dominating {
            Direction::AToB => "a_to_b",
            Direction::BToA => "b_to_a",
        },
        converged: result.converged,
        a_to_b: side(&result.a_to_b),
        b_to_a: result.b_to_a.as_ref().map(side),
        simplifier_bound,
        colors: args.colors.as_ref().map(|p| p.display().to_string()),
        seconds: Seconds {
            load,
            simplify: simplify_seconds,
            hierarchies: hierarchy_seconds,
            hausdorff: hausdorff_seconds,
        },
    };
    print_report(&report, args.print.json)
}

/// The paper's engine: the result, the hierarchies' seconds and the computation's.
fn by_meshsweeper(
    a: &TriMesh,
    b: &TriMesh,
    options: &HausdorffOptions,
    progress: &(dyn Fn(&HausdorffProgress) + Sync),
) -> Result<(
    Result<HausdorffDistance, sphaera::sweep::SweepError>,
    f64,
    f64,
)> {
    let started = Instant::now();
    let (ha, hb) = (build_hierarchy(a)?, build_hierarchy(b)?);
    let hierarchies = started.elapsed().as_secs_f64();
    let (sa, sb) = (Sweeper::new(&ha)?, Sweeper::new(&hb)?);
    let started = Instant::now();
    let result = meshsweeper_hausdorff_with_progress(&sa, &sb, options, progress);
    Ok((result, hierarchies, started.elapsed().as_secs_f64()))
}

fn side(d: &DirectedHausdorff) -> Side {
    Side {
        lower: d.lower,
        upper: d.upper,
        farthest: d.farthest.to_array(),
        closest: d.closest.to_array(),
        samples: d.samples,
        certified_samples: d.certified_samples,
        refined_triangles: d.refined_triangles,
    }
}

/// The bounding-box diagonal of both meshes together.
fn joint_diagonal(a: &TriMesh, b: &TriMesh) -> f64 {
    let (ba, bb) = (a.bounding_box(), b.bounding_box());
    (ba.max.max(bb.max) - ba.min.min(bb.min)).length()
}

/// Refuses a `--colors` path that is not `.ply` before any work is done.
fn check_ply(path: &std::path::Path) -> Result<()> {
    let is_ply = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ply"));
    anyhow::ensure!(
        is_ply,
        "--colors {}: the coloured mesh is written as PLY; give a `.ply` path",
        path.display()
    );
    Ok(())
}

impl crate::output::Report for Report {
    fn to_text(&self) -> String {
        let direction = |name: &str, s: &Side| {
            format!(
                "{name:<16}[{:.9e}, {:.9e}] at ({:.6}, {:.6}, {:.6}); {} samples ({} certified), {} triangles refined",
                s.lower,
                s.upper,
                s.farthest[0],
                s.farthest[1],
                s.farthest[2],
                thousands(s.samples),
                thousands(s.certified_samples),
                thousands(s.refined_triangles)
            )
        };
        let mut lines = vec![
            format!(
                "A               {} ({} triangles)",
                self.a,
                thousands(self.triangles_a)
            ),
            format!(
                "B               {} ({} triangles)",
                self.b,
                thousands(self.triangles_b)
            ),
            format!(
                "{:<16}[{:.9e}, {:.9e}] ({:.4} % to {:.4} % of the diagonal), gap {:.3e} (tolerance {:.3e}){}",
                if self.mode == "symmetric" {
                    "H(A, B)"
                } else {
                    "h(A -> B)"
                },
                self.lower,
                self.upper,
                100.0 * self.lower_relative,
                100.0 * self.upper_relative,
                self.upper - self.lower,
                self.tolerance,
                if self.converged {
                    ""
                } else {
                    "; --max-samples reached"
                }
            ),
            direction("h(A -> B)", &self.a_to_b),
        ];
        if let Some(b) = &self.b_to_a {
            lines.push(direction("h(B -> A)", b));
            lines.push(format!("dominating      {}", self.dominating));
        }
        if let Some(bound) = self.simplifier_bound {
            lines.push(format!("simplifier      certified bound {bound:.9e}"));
        }
        if let Some(path) = &self.colors {
            lines.push(format!("colours         A by distance to B, in {path}"));
        }
        let hierarchies = self
            .seconds
            .hierarchies
            .map_or(String::new(), |s| format!("{s:.3} s for the hierarchies, "));
        lines.push(format!(
            "time            {:.3} s to read, {:.3} s to simplify, {hierarchies}{:.3} s for the distance ({} engine)",
            self.seconds.load, self.seconds.simplify, self.seconds.hausdorff, self.engine
        ));
        let mut text = lines.join("\n");
        text.push('\n');
        text
    }
}
