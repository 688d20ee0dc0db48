//! `hal_vs_simplify`: is a 3D HAL approximation a good simplification? For each genus-0
//! mesh of [`super::MESHES_3D`] and tolerances `diagonal · 2⁻ᵏ`, `k ∈` [`EXPONENTS`]: the
//! adaptive approximation's triangles (closed: its gaps filled), its largest covering
//! width, and its certified symmetric Hausdorff distance to the original
//! (`sphaera-sweep`, to [`HAUSDORFF_TOLERANCE`] of the diagonal); beside it,
//! `sphaera-simplify` at the same triangle count, with its measured distance and its own
//! certified bound. Distances in % of the original's bounding-box diagonal.

use std::path::Path;

use anyhow::{Context, Result, bail};
use sphaera::hal::HalTree3;
use sphaera::mesh::{Length, TriMesh};
use sphaera::simplify::{SimplifyOptions, simplify};
use sphaera::sweep::{HausdorffOptions, hausdorff};

use super::{panels, style};
use crate::chart::{
    LegendEntry, Marker, Series, Style, StyledSeries, XAxis, titled_panels, write_csv,
};

/// The tolerance exponents `k` (tolerance `diagonal · 2⁻ᵏ`).
pub const EXPONENTS: &[i32] = &[3, 4, 5, 6, 7, 8];

/// The Hausdorff bracket's tolerance, relative to the diagonal.
pub const HAUSDORFF_TOLERANCE: f64 = 1e-4;

/// An unjoined hollow triangle in colour `i`: a bound or width beside a measured curve.
fn hollow(i: usize) -> Style {
    Style {
        filled: false,
        ..style(i, Marker::Triangle, false)
    }
}

/// The certified symmetric Hausdorff distance between `a` and `b` (its upper end).
fn certified_hausdorff(a: &TriMesh, b: &TriMesh) -> Result<f64> {
    let options =
        HausdorffOptions::default().with_tolerance(Length::RelativeToDiagonal(HAUSDORFF_TOLERANCE));
    Ok(hausdorff(a, b, &options)?.upper)
}

/// Writes `hal_vs_simplify.csv` and `.svg`.
pub fn versus_simplify(data: &Path, out: &Path) -> Result<()> {
    let mut rows = Vec::new();
    let mut panels_data = Vec::new();
    for file in super::MESHES_3D {
        let Some(mesh) = crate::experiments::load_or_skip(data, file)? else {
            continue;
        };
        let tree = HalTree3::build(&mesh).with_context(|| format!("no HAL tree for {file}"))?;
        let diagonal = mesh.bounding_box_diagonal();
        let percent = |d: f64| 100.0 * d / diagonal;
        let mut hal = Series::new("HAL");
        let mut width = Series::new("HAL width");
        let mut simplified = Series::new("simplify");
        let mut bound = Series::new("simplify bound");
        for &k in EXPONENTS {
            let tolerance = diagonal * f64::from(-k).exp2();
            let approximation = tree.approximate(tolerance)?;
            let triangles = approximation.triangle_count();
            let kept = tree.kept_width(|n| n.width > tolerance);
            let distance = certified_hausdorff(&mesh, &approximation)
                .with_context(|| format!("{file}: Hausdorff of the HAL approximation"))?;
            let other = simplify(
                &mesh,
                &SimplifyOptions::default().with_target_triangles(triangles),
            )
            .with_context(|| format!("{file}: simplify to {triangles} triangles"))?;
            let other_distance = certified_hausdorff(&mesh, &other.mesh)
                .with_context(|| format!("{file}: Hausdorff of the simplification"))?;
            let x = triangles as f64;
            hal.points.push((x, percent(distance)));
            width.points.push((x, percent(kept)));
            simplified.points.push((x, percent(other_distance)));
            bound.points.push((x, percent(other.error_bound)));
            eprintln!(
                "{file} 2^-{k}: {triangles} triangles, HAL {:.3} % (width {:.3} %), simplify {} triangles {:.4} % (bound {:.4} %)",
                percent(distance),
                percent(kept),
                other.mesh.triangle_count(),
                percent(other_distance),
                percent(other.error_bound)
            );
            rows.push(vec![
                (*file).to_owned(),
                format!("2^-{k}"),
                triangles.to_string(),
                format!("{:.6}", percent(kept)),
                format!("{:.6}", percent(distance)),
                other.mesh.triangle_count().to_string(),
                format!("{:.6}", percent(other_distance)),
                format!("{:.6}", percent(other.error_bound)),
            ]);
        }
        panels_data.push((
            format!("{file} ({} triangles)", mesh.triangle_count()),
            vec![
                StyledSeries::new(hal, style(0, Marker::Circle, true)),
                StyledSeries::new(width, hollow(0)),
                StyledSeries::new(simplified, style(1, Marker::Square, true)),
                StyledSeries::new(bound, hollow(1)),
            ],
        ));
    }
    if panels_data.is_empty() {
        bail!("no mesh found for hal_vs_simplify");
    }
    write_csv(
        &out.join("hal_vs_simplify.csv"),
        &[
            "mesh",
            "hal_tolerance",
            "triangles",
            "hal_width_pct_diagonal",
            "hal_hausdorff_pct_diagonal",
            "simplify_triangles",
            "simplify_hausdorff_pct_diagonal",
            "simplify_bound_pct_diagonal",
        ],
        &rows,
    )?;
    let panels = panels(&panels_data, "triangles", "% of diagonal", &XAxis::Log);
    let legend = [
        ("HAL: certified Hausdorff", style(0, Marker::Circle, true)),
        ("HAL: largest kept width", hollow(0)),
        (
            "simplify: certified Hausdorff",
            style(1, Marker::Square, true),
        ),
        ("simplify: its own bound", hollow(1)),
    ]
    .map(|(label, style)| LegendEntry {
        label: label.into(),
        style,
    });
    titled_panels(
        &out.join("hal_vs_simplify.svg"),
        "3D HAL approximations against sphaera-simplify at equal triangle counts",
        &panels,
        &legend,
    )
}
