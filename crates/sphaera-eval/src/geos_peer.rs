//! GEOS prepared geometry, the same-run peer of 2D HAL point inclusion (with the `geos`
//! feature): the outlines and queries, the GEOS polygon of an outline and its answer in
//! HAL's terms. The `hal2_vs_geos` bench and the `hal2_geos` test both go through here, so
//! that they compare the same calls on the same points.
//!
//! GEOS's prepared predicates and HAL's [`Containment`] name the same partition of the
//! plane: HAL's `Inside` is GEOS's `contains` (the point is in the interior) and
//! `Inside | Boundary` is GEOS's `intersects` (interior or boundary); so `Boundary` is
//! `intersects && !contains` and `Outside` is `!intersects`. Both count ray crossings with
//! the same half-open rule; GEOS's orientation test is double-double arithmetic behind a
//! filter, HAL's is exact (`robust`).
//!
//! GEOS is the system's libgeos (Debian: `apt-get install libgeos-dev`), found with
//! pkg-config by the `geos-sys` crate's prebuilt bindings.

use std::path::Path;

use anyhow::{Context, Result, bail};
use geos::{CoordSeq, Geometry, PreparedGeometry};
use sphaera::hal::{Containment, Polyline2};
use sphaera::mesh::glam::DVec2;

/// The seed of the query points ([`crate::query_sets::box_points`],
/// [`crate::query_sets::near_outline_points`]) in the bench and the test.
pub const QUERY_SEED: u64 = 41;

/// Every outline of `data/polygons/*.txt`, sorted by file name, with its name (the file
/// stem).
///
/// # Errors
///
/// If the folder cannot be listed, holds no outline, or a file is not a polygon.
pub fn outlines(data: &Path) -> Result<Vec<(String, Polyline2)>> {
    let dir = data.join("polygons");
    let mut paths = Vec::new();
    for entry in
        std::fs::read_dir(&dir).with_context(|| format!("cannot list {}", dir.display()))?
    {
        let path = entry?.path();
        if path.extension().is_some_and(|e| e == "txt") {
            paths.push(path);
        }
    }
    paths.sort();
    if paths.is_empty() {
        bail!("no outline (*.txt) in {}", dir.display());
    }
    paths
        .iter()
        .map(|path| {
            let name = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            let outline = Polyline2::read_polygon(path)
                .with_context(|| format!("cannot read the outline {}", path.display()))?;
            Ok((name, outline))
        })
        .collect()
}

/// The GEOS polygon of a closed outline: one shell, its ring closed by repeating the
/// first vertex (the outline files close implicitly). Prepare it with
/// [`geos::Geom::to_prepared_geom`].
///
/// # Errors
///
/// If the outline is open, or GEOS refuses the ring.
pub fn geos_polygon(outline: &Polyline2) -> Result<Geometry> {
    if !outline.is_closed() {
        bail!("GEOS polygons are closed; the outline is open");
    }
    let points = outline.points();
    let mut coords: Vec<[f64; 2]> = points.iter().map(|p| [p.x, p.y]).collect();
    if let (Some(first), Some(last)) = (points.first(), points.last())
        && first != last
    {
        coords.push([first.x, first.y]);
    }
    let ring = CoordSeq::new_from_vec(&coords)
        .and_then(Geometry::create_linear_ring)
        .context("GEOS refuses the outline as a ring")?;
    Geometry::create_polygon(ring, Vec::new()).context("GEOS refuses the outline as a polygon")
}

/// GEOS point geometries of `points`, made once so that a timing measures the predicate
/// only (GEOS 3.11 has no predicate on bare coordinates: `GEOSPreparedContainsXY` came in
/// 3.12).
///
/// # Errors
///
/// If GEOS cannot make a point.
pub fn geos_points(points: &[DVec2]) -> Result<Vec<Geometry>> {
    points
        .iter()
        .map(|p| {
            CoordSeq::new_from_vec(&[[p.x, p.y]])
                .and_then(Geometry::create_point)
                .with_context(|| format!("GEOS cannot make the point ({}, {})", p.x, p.y))
        })
        .collect()
}

/// GEOS's answer for a point in HAL's terms (module docs): `contains` is
/// [`Containment::Inside`], `intersects` without `contains` is
/// [`Containment::Boundary`], neither is [`Containment::Outside`].
///
/// # Errors
///
/// If a GEOS predicate fails.
pub fn geos_containment(prepared: &PreparedGeometry<'_>, point: &Geometry) -> Result<Containment> {
    if prepared.contains(point).context("GEOS contains")? {
        return Ok(Containment::Inside);
    }
    Ok(if prepared.intersects(point).context("GEOS intersects")? {
        Containment::Boundary
    } else {
        Containment::Outside
    })
}
