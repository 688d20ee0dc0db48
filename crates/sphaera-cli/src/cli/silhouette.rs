//! Arguments of `sphaera silhouette`: the view, the contours and the distance transform.

use std::path::PathBuf;

use clap::Args;
use sphaera::mesh::Length;
use sphaera::silhouette::{ContourRegion, Contours, DistanceTransform};

use super::choice::Choice;
use super::{OutputArgs, parse_length};
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

    /// The contour region: triangles within this many cells of the silhouette (how it is
    /// decided: `--region`).
    #[arg(long, default_value_t = 2.0)]
    pub threshold: f32,

    /// Which triangles are in the contour region.
    #[arg(long, default_value = "widened", value_parser = Choice::of(REGIONS))]
    pub region: ContourRegion,

    /// The contour region's allowed error as a fraction of `--error` (0: exact there).
    #[arg(long, default_value_t = 0.25)]
    pub factor: f64,

    /// The contour region's allowed error is also at most this many cells of the view
    /// (`inf`: `--factor` alone, the paper's rule).
    #[arg(long, default_value_t = 0.25)]
    pub contour_cells: f64,

    /// The error allowed away from the contour: a distance (`0.002`) or a percentage of
    /// the bounding-box diagonal (`1%`).
    #[arg(long, value_parser = parse_length, default_value = "1%")]
    pub error: Length,

    /// The view: the direction toward the camera, `x,y,z`.
    #[arg(long, value_parser = parse_direction, default_value = "0,0,1", allow_hyphen_values = true)]
    pub view: [f64; 3],

    /// A pinhole camera at this point `x,y,z` (the mesh's coordinates, outside its
    /// bounding sphere) instead of `--view`: the view is from the sphere's centre toward
    /// it, the contour's cap in cells is taken at the camera's scale when it is nearer
    /// than the labels' cameras, and the silhouettes are compared as it sees them.
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true, conflicts_with = "view")]
    pub eye: Option<[f64; 3]>,

    /// Labels for the view: those of the nearest camera (1) or the average of this many
    /// nearest cameras.
    #[arg(long, default_value_t = 1)]
    pub nearest: usize,

    /// Which silhouettes the labels measure from.
    #[arg(long, default_value = "outline", value_parser = Choice::of(CONTOURS))]
    pub contours: Contours,

    /// The distance transform of the label images.
    #[arg(long, default_value = "euclidean", value_parser = Choice::of(TRANSFORMS))]
    pub transform: DistanceTransform,

    /// Perspective cameras this many bounding radii from the centre (more than 1);
    /// orthographic when omitted.
    #[arg(long)]
    pub perspective: Option<f64>,

    /// Keep the labels in this file (any name, e.g. `bunny.labels`). When it exists it is
    /// read instead of labelling again: it must belong to the mesh and have been computed
    /// with the same --step, --resolution, --transform, --contours and --perspective
    /// (otherwise an error says what differs). When it does not, the labels are computed
    /// and written to it, atomically, for the next run.
    #[arg(long, value_name = "FILE")]
    pub labels: Option<PathBuf>,

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

/// `--contours`: which silhouettes labels measure from (every [`Contours`]).
pub const CONTOURS: &[(Contours, &str)] = &[
    (
        Contours::External,
        "The outline only (the better silhouette per triangle on scanned meshes)",
    ),
    (
        Contours::All,
        "The outline and the internal silhouettes (the paper's Fig. 2)",
    ),
];

/// `--region`: which triangles are in the contour region (every [`ContourRegion`]).
pub const REGIONS: &[(ContourRegion, &str)] = &[
    (
        ContourRegion::Widened,
        "A corner within the threshold once the triangle's error bound is counted (the best outline per triangle, measured)",
    ),
    (
        ContourRegion::Corners,
        "A corner within the threshold (the paper's rule)",
    ),
    (
        ContourRegion::Certified,
        "Any point of the triangle's error region within the threshold (more triangles)",
    ),
];

/// `--transform`: the distance transform of the label images (every
/// [`DistanceTransform`]).
pub const TRANSFORMS: &[(DistanceTransform, &str)] = &[
    (DistanceTransform::Euclidean, "Exact Euclidean distances"),
    (
        DistanceTransform::Chamfer,
        "The paper's two-pass 3–4 chamfer (within 8 % of Euclidean)",
    ),
];

/// Three numbers `x,y,z` on the command line; `kind` names them in the message.
fn parse_triple(text: &str, kind: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = text.split(',').collect();
    let [x, y, z] = parts.as_slice() else {
        return Err(format!("`{text}` is not a {kind} `x,y,z`"));
    };
    let mut out = [0.0_f64; 3];
    for (o, part) in out.iter_mut().zip([x, y, z]) {
        *o = part
            .trim()
            .parse()
            .map_err(|e| format!("`{part}` in `{text}` is not a number: {e}"))?;
    }
    Ok(out)
}

/// A point on the command line: `x,y,z`, finite.
fn parse_point(text: &str) -> Result<[f64; 3], String> {
    let out = parse_triple(text, "point")?;
    if let Some(c) = out.iter().find(|c| !c.is_finite()) {
        return Err(format!("`{c}` in `{text}` is not finite"));
    }
    Ok(out)
}

/// A direction on the command line: `x,y,z`, finite and not zero.
fn parse_direction(text: &str) -> Result<[f64; 3], String> {
    let out = parse_triple(text, "direction")?;
    if out.iter().any(|c| !c.is_finite()) || out.iter().all(|&c| c == 0.0) {
        return Err(format!("`{text}` must be finite and not zero"));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_parse_as_three_numbers() {
        assert_eq!(parse_direction("0,0,1"), Ok([0.0, 0.0, 1.0]));
        assert_eq!(parse_direction(" -1, 0.5 ,2"), Ok([-1.0, 0.5, 2.0]));
        for bad in ["1,2", "1,2,3,4", "a,b,c", "0,0,0", "inf,0,1", "NaN,0,1"] {
            assert!(parse_direction(bad).is_err(), "{bad}");
        }
    }
}
