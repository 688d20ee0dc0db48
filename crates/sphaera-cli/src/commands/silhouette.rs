//! `sphaera silhouette`: silhouette labels from a set of cameras, and the level of detail
//! they guide for one view, with its certified error per region and its silhouette error
//! in pixels against the plain simplifier's (`sphaera simplify`) at as many triangles.

use std::{
    path::{Path, PathBuf},
    time::Instant,
};

use anyhow::{Context, Result, bail};
use image::{ImageEncoder, codecs::png::PngEncoder};
use serde::Serialize;
use sphaera::{
    mesh::{DVec3, TriMesh, io},
    silhouette::{
        ContourTolerance, Interpolation, LabelFileProblem, LabelOptions, Labels, Picture,
        Projection, SilhouetteError, ViewDependent, ViewSet, bounding_sphere, contour_displacement,
        coverage, overlay_picture, shaded_picture, silhouette_difference,
    },
    simplify::{SimplifyOptions, simplify},
};

use crate::{
    cli::SilhouetteArgs,
    input::{file_policy, read_mesh},
    output::{check_mesh_format, check_target, print_report, thousands},
    progress,
};

/// Everything `sphaera silhouette` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    /// The input file, or `<embedded bunny_lowres.obj>`.
    source: String,
    /// The view: the unit direction toward the camera.
    view: [f64; 3],
    /// The camera's position when `--eye` gave one (`null` otherwise).
    eye: Option<[f64; 3]>,
    /// Cameras of the view set and the degrees between them.
    cameras: usize,
    step_degrees: f64,
    /// `orthographic`, or `perspective` with the distance in bounding radii.
    projection: String,
    /// Cells a side of the label grids (and of the silhouette comparison).
    resolution: usize,
    /// `outline` or `all` (the outline and the internal silhouettes).
    contours: &'static str,
    /// `euclidean` or `chamfer`.
    transform: &'static str,
    /// Cameras whose labels the view's are the average of (1: the nearest).
    nearest: usize,
    /// The contour region: triangles within this many cells of the silhouette.
    threshold: f32,
    /// How the contour region is decided: `widened`, `corners` or `certified`.
    region: &'static str,
    /// The contour region's allowed error as a fraction of `error`.
    factor: f64,
    /// The contour region's allowed error is also at most this many cells (`null`: no
    /// cap).
    contour_cells: Option<f64>,
    /// The error allowed in the contour region (the smaller of the two), a length.
    contour_allowance: f64,
    /// The error allowed away from the contour, absolute and relative to the diagonal.
    error: f64,
    error_relative: f64,
    /// Bytes of the stored labels (one `u16` per vertex per camera).
    label_bytes: usize,
    /// The label file (`--labels`; `null` when not given): read instead of labelling
    /// (`reused`), or written after labelling.
    labels_file: Option<LabelsFile>,
    triangles_in: usize,
    triangles_out: usize,
    contour_triangles: usize,
    /// Certified bounds on the distance between the result and the input, per region.
    contour_error: f64,
    other_error: f64,
    /// Cells of the view where the result's silhouette differs from the original's.
    silhouette_pixels_wrong: usize,
    /// The farthest a differing cell lies from the other silhouette, in cells (`null`
    /// when the result shows nothing).
    contour_displacement: Option<f64>,
    /// The same for the plain simplifier (`sphaera simplify --triangles N`, its
    /// defaults) at as many triangles as the result, and its triangle count.
    plain_triangles: usize,
    plain_pixels_wrong: usize,
    plain_contour_displacement: Option<f64>,
    /// Whether the guided result has fewer wrong silhouette pixels than the plain
    /// simplifier's; when it has not, the mesh has no outline detail to keep at this
    /// error and view, and `sphaera simplify` does as well.
    gains: bool,
    /// Cells the original covers in the view.
    silhouette_pixels: usize,
    /// Written files (`null` when not asked for).
    output: Option<String>,
    labels_png: Option<String>,
    compare_png: Option<String>,
    seconds: Seconds,
}

#[derive(Debug, Serialize)]
struct LabelsFile {
    path: String,
    /// Whether the labels were read from the file (`true`) or computed and written to it.
    reused: bool,
}

#[derive(Debug, Serialize)]
struct Seconds {
    load: f64,
    labels: f64,
    hierarchy: f64,
    extract: f64,
    compare: f64,
    write: f64,
}

pub fn run(args: &SilhouetteArgs, quiet: bool) -> Result<()> {
    if let Some(path) = &args.output {
        check_mesh_format(path)?;
        check_target(path)?;
    }
    for path in [&args.labels_png, &args.compare_png].into_iter().flatten() {
        check_png(path)?;
        check_target(path)?;
    }
    // An existing label file is read (and checked) later; a new one must be writable.
    let reuse = args.labels.as_ref().is_some_and(|path| path.exists());
    if let Some(path) = args.labels.as_ref().filter(|_| !reuse) {
        check_target(path)?;
    }
    let view = DVec3::from_array(args.view).normalize();
    let eye = args.eye.map(DVec3::from_array);
    let interpolation = match args.nearest {
        0 => bail!("--nearest must be at least 1"),
        1 => Interpolation::Nearest,
        n => Interpolation::Average(n),
    };
    let mut views = ViewSet::regular(args.step)?;
    if let Some(distance) = args.perspective {
        views = views.with_perspective(distance)?;
    }
    let projection = views.projection();
    if args.nearest > views.len() {
        bail!(
            "--nearest {} asks for more cameras than the {} of a {}° step",
            args.nearest,
            views.len(),
            args.step
        );
    }
    let input = read_mesh(args.mesh.as_deref(), quiet)?;
    let mesh = &input.loaded.mesh;
    if mesh.triangle_count() == 0 {
        bail!("{} has no triangles: nothing to label", input.source);
    }
    let diagonal = mesh.bounding_box_diagonal();
    let error = args.error.resolve(diagonal);
    let tolerance = ContourTolerance {
        error,
        factor: args.factor,
        threshold: args.threshold,
        cells: args.contour_cells,
    };

    let started = Instant::now();
    let options = LabelOptions::default()
        .with_resolution(args.resolution)
        .with_transform(args.transform)
        .with_contours(args.contours);
    let labels = match &args.labels {
        Some(path) if reuse => read_labels(path, mesh, &views, &options, quiet)?,
        _ => {
            let bar = progress::bar(
                quiet,
                &format!("labelling {} views at {}²", views.len(), args.resolution),
                views.len() as u64,
            );
            let labels = Labels::compute_with_progress(mesh, &views, &options, &|done| {
                bar.set_position(done as u64);
            });
            bar.finish_and_clear();
            let labels = labels?;
            if let Some(path) = &args.labels {
                labels.save(mesh, path)?;
            }
            labels
        }
    };
    let labels_seconds = started.elapsed().as_secs_f64();

    let started = Instant::now();
    let hierarchy = progress::hierarchy(quiet, mesh);
    let hierarchy = hierarchy?;
    let hierarchy_seconds = started.elapsed().as_secs_f64();

    let started = Instant::now();
    let mut lod = ViewDependent::new(&hierarchy, &labels)?.with_region(args.region);
    let extraction = match eye {
        Some(eye) => lod.extract_at(eye, interpolation, tolerance)?,
        None => lod.extract(view, interpolation, tolerance)?,
    };
    let extract_seconds = started.elapsed().as_secs_f64();
    let result = &extraction.simplified.mesh;

    let started = Instant::now();
    let frame = bounding_sphere(mesh)?;
    // The images the camera sees: from the eye, perspective at its distance.
    let (view, seen_as) = match eye {
        Some(eye) => {
            let offset = eye - frame.center;
            let distance = offset.length() / frame.radius;
            (offset.normalize(), Projection::Perspective { distance })
        }
        None => (view, projection),
    };
    let picture = |m: &TriMesh| coverage(m, frame, view, seen_as, args.resolution);
    let original = picture(mesh)?;
    let ours = picture(result)?;
    let plain = simplify(
        mesh,
        &SimplifyOptions::default().with_target_triangles(result.triangle_count()),
    )?
    .mesh;
    let plain_picture = picture(&plain)?;
    let compare_seconds = started.elapsed().as_secs_f64();

    let started = Instant::now();
    if let Some(path) = &args.output {
        io::save(path, result)?;
    }
    if let Some(path) = &args.labels_png {
        let values = labels.for_view(view, interpolation)?;
        let scale = values.iter().copied().fold(0.0_f32, f32::max).max(1.0);
        let shaded = shaded_picture(mesh, frame, view, seen_as, args.resolution, &values, scale)?;
        write_png(path, &shaded)?;
    }
    if let Some(path) = &args.compare_png {
        write_png(path, &overlay_picture(&original, &ours, args.resolution))?;
    }
    let write_seconds = started.elapsed().as_secs_f64();

    let shown = |p: &Option<PathBuf>| p.as_ref().map(|p| p.display().to_string());
    let report = Report {
        source: input.source,
        view: view.to_array(),
        eye: args.eye,
        cameras: views.len(),
        step_degrees: args.step,
        projection: match projection {
            Projection::Perspective { distance } => format!("perspective at {distance} radii"),
            _ => "orthographic".to_owned(),
        },
        resolution: args.resolution,
        contours: args.contours.name(),
        transform: args.transform.name(),
        nearest: args.nearest,
        threshold: args.threshold,
        region: args.region.name(),
        factor: args.factor,
        contour_cells: args.contour_cells.is_finite().then_some(args.contour_cells),
        contour_allowance: extraction.contour_allowance,
        error,
        error_relative: if diagonal > 0.0 {
            error / diagonal
        } else {
            0.0
        },
        label_bytes: labels.storage_bytes(),
        labels_file: shown(&args.labels).map(|path| LabelsFile {
            path,
            reused: reuse,
        }),
        triangles_in: mesh.triangle_count(),
        triangles_out: result.triangle_count(),
        contour_triangles: extraction.contour_triangles,
        contour_error: extraction.contour_error,
        other_error: extraction.other_error,
        silhouette_pixels_wrong: silhouette_difference(&original, &ours),
        contour_displacement: contour_displacement(&original, &ours, args.resolution),
        plain_triangles: plain.triangle_count(),
        plain_pixels_wrong: silhouette_difference(&original, &plain_picture),
        plain_contour_displacement: contour_displacement(
            &original,
            &plain_picture,
            args.resolution,
        ),
        gains: silhouette_difference(&original, &ours)
            < silhouette_difference(&original, &plain_picture),
        silhouette_pixels: original.iter().filter(|&&c| c).count(),
        output: shown(&args.output),
        labels_png: shown(&args.labels_png),
        compare_png: shown(&args.compare_png),
        seconds: Seconds {
            load: input.seconds,
            labels: labels_seconds,
            hierarchy: hierarchy_seconds,
            extract: extract_seconds,
            compare: compare_seconds,
            write: write_seconds,
        },
    };
    print_report(&report, args.print.json)
}

/// The labels of `mesh` in the label file at `path`, read by the run's file policy, if
/// they belong to `mesh` and were computed for `views` and `options`; else an error
/// naming the file, what differs and how to go on.
fn read_labels(
    path: &Path,
    mesh: &TriMesh,
    views: &ViewSet,
    options: &LabelOptions,
    quiet: bool,
) -> Result<Labels> {
    let shown = path.display();
    let spinner = progress::spinner(quiet, &format!("reading labels {shown}"));
    let labels = Labels::load_with(path, mesh, &file_policy());
    spinner.finish_and_clear();
    let labels = match labels {
        Ok(labels) => labels,
        // The file could not be opened: the error says why.
        Err(
            error @ SilhouetteError::LabelFile {
                problem: LabelFileProblem::Refused { .. } | LabelFileProblem::Io { .. },
                ..
            },
        ) => return Err(error.into()),
        // It was read, and is not this mesh's labels: say how to go on.
        Err(error) => {
            bail!("{error} (delete the file to label again, or give another --labels file)")
        }
    };
    if let Err(SilhouetteError::LabelSettingsMismatch {
        setting,
        labels: theirs,
        asked,
    }) = labels.check_settings(views, options)
    {
        let file_option = match setting {
            "step" => format!("--step {}", labels.views().step_degrees()),
            "projection" => match labels.views().projection() {
                Projection::Perspective { distance } => format!("--perspective {distance}"),
                _ => "without --perspective".to_owned(),
            },
            "resolution" => format!("--resolution {}", labels.resolution()),
            "transform" => format!("--transform {}", labels.transform()),
            _ => format!("--contours {}", labels.contours()),
        };
        bail!(
            "label file {shown}: its labels were computed with {setting} {theirs}, not {asked}: \
             delete the file to label again with these options, or run with the file's \
             settings ({file_option})"
        );
    }
    Ok(labels)
}

/// Fails before any work unless `path` ends in `.png`.
fn check_png(path: &Path) -> Result<()> {
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !png {
        bail!(
            "cannot write {}: pictures are PNG files (.png)",
            path.display()
        );
    }
    Ok(())
}

/// Encodes `picture` as PNG and writes it atomically.
fn write_png(path: &Path, picture: &Picture) -> Result<()> {
    let mut bytes = Vec::new();
    let side = u32::try_from(picture.size).context("the picture is too large for PNG")?;
    PngEncoder::new(&mut bytes)
        .write_image(&picture.rgb, side, side, image::ExtendedColorType::Rgb8)
        .with_context(|| format!("cannot encode {} as PNG", path.display()))?;
    io::write_atomic(path, |w| std::io::Write::write_all(w, &bytes))?;
    Ok(())
}

impl crate::output::Report for Report {
    fn to_text(&self) -> String {
        let cells = |d: Option<f64>| d.map_or("-".to_owned(), |d| format!("{d:.1}"));
        let percent = |d: f64| {
            if self.error_relative > 0.0 {
                100.0 * d * self.error_relative / self.error
            } else {
                0.0
            }
        };
        let [x, y, z] = self.view;
        let mut lines = vec![
            format!("mesh            {}", self.source),
            format!(
                "cameras         {} every {}°, {}, {}² cells, {} labels, {} transform ({} KiB)",
                self.cameras,
                self.step_degrees,
                self.projection,
                self.resolution,
                self.contours,
                self.transform,
                self.label_bytes / 1024
            ),
            format!(
                "labels file     {}",
                self.labels_file.as_ref().map_or_else(
                    || "none (give --labels FILE to keep the labels for the next run)".to_owned(),
                    |f| format!(
                        "{} ({})",
                        f.path,
                        if f.reused {
                            "read instead of labelling"
                        } else {
                            "written"
                        }
                    )
                )
            ),
            format!(
                "view            {x:.3},{y:.3},{z:.3}{} (labels of {} nearest camera{})",
                self.eye.map_or(String::new(), |[a, b, c]| format!(
                    ", from a camera at {a},{b},{c}"
                )),
                self.nearest,
                if self.nearest == 1 { "" } else { "s" }
            ),
            format!(
                "triangles       {} -> {} ({} in the contour region: {}, {} cells)",
                thousands(self.triangles_in),
                thousands(self.triangles_out),
                thousands(self.contour_triangles),
                self.region,
                self.threshold
            ),
            format!(
                "error bound     {:.4e} ({:.4} %) in the contour region, allowed {:.4e} \
                 ({:.4} % × {}{}); {:.4e} ({:.4} %) elsewhere, allowed {:.4} %",
                self.contour_error,
                percent(self.contour_error),
                self.contour_allowance,
                100.0 * self.error_relative,
                self.factor,
                self.contour_cells
                    .map_or(String::new(), |c| format!(", at most {c} cell")),
                self.other_error,
                percent(self.other_error),
                100.0 * self.error_relative,
            ),
            format!(
                "silhouette      {} of {} pixels wrong, contour moved up to {} cells \
                 (sphaera simplify, {} triangles: {} wrong, {} cells)",
                thousands(self.silhouette_pixels_wrong),
                thousands(self.silhouette_pixels),
                cells(self.contour_displacement),
                thousands(self.plain_triangles),
                thousands(self.plain_pixels_wrong),
                cells(self.plain_contour_displacement)
            ),
            format!(
                "time            {:.3} s to read, {:.3} s to label, {:.3} s for the hierarchy, \
                 {:.4} s to extract, {:.3} s to compare, {:.3} s to write",
                self.seconds.load,
                self.seconds.labels,
                self.seconds.hierarchy,
                self.seconds.extract,
                self.seconds.compare,
                self.seconds.write
            ),
        ];
        if !self.gains {
            lines.push(
                "note            no gain on this mesh from this view: the plain simplifier \
                 keeps the outline as well with as many triangles (no outline detail to keep \
                 at this error); `sphaera simplify --triangles N` does the same job"
                    .to_owned(),
            );
        }
        let labels_written = self
            .labels_file
            .as_ref()
            .filter(|f| !f.reused)
            .map(|f| f.path.clone());
        let written: Vec<&str> = [
            &labels_written,
            &self.output,
            &self.labels_png,
            &self.compare_png,
        ]
        .into_iter()
        .flatten()
        .map(String::as_str)
        .collect();
        lines.push(if written.is_empty() {
            "written to      nothing (give --output FILE.obj, --labels-png, --compare-png)"
                .to_owned()
        } else {
            format!("written to      {}", written.join(", "))
        });
        lines.join("\n") + "\n"
    }
}
