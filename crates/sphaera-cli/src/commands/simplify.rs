//! `sphaera simplify`: edge-collapse simplification with a two-sided error bound.

use std::time::Instant;

use anyhow::Result;
use serde::Serialize;
use sphaera::{
    mesh::io,
    simplify::{SimplifyOptions, SimplifyProgress, simplify_with_progress},
};

use crate::{
    cli::SimplifyArgs,
    input::read_mesh,
    measure,
    output::{check_mesh_format, check_target, print_report, thousands},
    progress,
};

/// Everything `sphaera simplify` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    /// The input file, or `<embedded bunny_lowres.obj>`.
    source: String,
    /// Where the result was written (`null` without `--output`).
    output: Option<String>,
    /// `--placement`: where kept vertices go.
    placement: &'static str,
    /// `--order`: the collapse order asked for (`auto`, `strict` or `batched`).
    order: &'static str,
    triangles_in: usize,
    triangles_out: usize,
    vertices_out: usize,
    collapses: usize,
    /// Bound on the symmetric Hausdorff distance between input and output.
    error_bound: f64,
    /// The bound as a fraction of the input's bounding-box diagonal.
    error_bound_relative: f64,
    /// With `--measure`: the sampled symmetric Hausdorff distance between input and output
    /// (a lower bound of the true one); `null` without.
    measured_hausdorff: Option<f64>,
    /// The measured distance as a fraction of the input's bounding-box diagonal.
    measured_hausdorff_relative: Option<f64>,
    locked_boundary_vertices: usize,
    locked_non_manifold_vertices: usize,
    seconds: Seconds,
}

#[derive(Debug, Serialize)]
struct Seconds {
    load: f64,
    simplify: f64,
    /// With `--measure`: the measurement; `null` without.
    measure: Option<f64>,
    write: f64,
}

pub fn run(args: &SimplifyArgs, quiet: bool) -> Result<()> {
    if let Some(path) = &args.output {
        check_mesh_format(path)?;
        check_target(path)?;
    }
    let input = read_mesh(args.mesh.as_deref(), quiet)?;
    let mesh = &input.loaded.mesh;
    let mut options = SimplifyOptions::default()
        .with_lock_boundary(!args.free_boundary)
        .with_placement(args.placement)
        .with_order(args.order);
    options.target_triangles = args.triangles;
    options.target_ratio = args.ratio;
    options.max_error = args.max_error;
    let bar = progress::bar(
        quiet,
        &format!("simplifying {} triangles", thousands(mesh.triangle_count())),
        mesh.triangle_count() as u64,
    );
    let report_progress = |p: &SimplifyProgress| {
        bar.set_length(p.to_remove as u64);
        bar.set_position(p.removed as u64);
    };
    let started = Instant::now();
    let simplified = simplify_with_progress(mesh, &options, &report_progress);
    let simplify_seconds = started.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let simplified = simplified?;

    let (measured, measure_seconds) = if args.measure {
        let spinner = progress::spinner(quiet, "measuring the Hausdorff distance");
        let started = Instant::now();
        let h = measure::sampled_hausdorff(mesh, &simplified.mesh);
        spinner.finish_and_clear();
        (Some(h?), Some(started.elapsed().as_secs_f64()))
    } else {
        (None, None)
    };

    let started = Instant::now();
    if let Some(path) = &args.output {
        io::save(path, &simplified.mesh)?;
    }
    let write_seconds = started.elapsed().as_secs_f64();

    let diagonal = mesh.bounding_box_diagonal();
    let relative = |d: f64| if diagonal > 0.0 { d / diagonal } else { 0.0 };
    let report = Report {
        source: input.source,
        output: args.output.as_ref().map(|p| p.display().to_string()),
        placement: args.placement.name(),
        order: args.order.name(),
        triangles_in: mesh.triangle_count(),
        triangles_out: simplified.mesh.triangle_count(),
        vertices_out: simplified.mesh.vertex_count(),
        collapses: simplified.collapses,
        error_bound: simplified.error_bound,
        error_bound_relative: relative(simplified.error_bound),
        measured_hausdorff: measured,
        measured_hausdorff_relative: measured.map(relative),
        locked_boundary_vertices: simplified.locked.boundary,
        locked_non_manifold_vertices: simplified.locked.non_manifold,
        seconds: Seconds {
            load: input.seconds,
            simplify: simplify_seconds,
            measure: measure_seconds,
            write: write_seconds,
        },
    };
    print_report(&report, args.print.json)
}

impl crate::output::Report for Report {
    fn to_text(&self) -> String {
        let mut lines = vec![
            format!("mesh            {}", self.source),
            format!("placement       {} (order {})", self.placement, self.order),
            format!(
                "triangles       {} -> {} ({} collapses)",
                thousands(self.triangles_in),
                thousands(self.triangles_out),
                thousands(self.collapses)
            ),
            format!(
                "error bound     {:.6e} ({:.4} % of the diagonal), both directions",
                self.error_bound,
                100.0 * self.error_bound_relative
            ),
        ];
        if let (Some(h), Some(r)) = (self.measured_hausdorff, self.measured_hausdorff_relative) {
            lines.push(format!(
                "measured        {h:.6e} ({:.4} % of the diagonal), sampled lower bound",
                100.0 * r
            ));
        }
        lines.extend([
            format!(
                "locked          {} boundary, {} non-manifold vertices",
                thousands(self.locked_boundary_vertices),
                thousands(self.locked_non_manifold_vertices)
            ),
            match self.seconds.measure {
                Some(m) => format!(
                    "time            {:.3} s to read, {:.3} s to simplify, {m:.3} s to measure, \
                     {:.3} s to write",
                    self.seconds.load, self.seconds.simplify, self.seconds.write
                ),
                None => format!(
                    "time            {:.3} s to read, {:.3} s to simplify, {:.3} s to write",
                    self.seconds.load, self.seconds.simplify, self.seconds.write
                ),
            },
        ]);
        lines.push(match &self.output {
            Some(path) => format!("written to      {path}"),
            None => "written to      nothing (give --output FILE.obj or .ply)".to_owned(),
        });
        lines.join("\n") + "\n"
    }
}
