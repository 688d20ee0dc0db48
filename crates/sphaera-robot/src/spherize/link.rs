//! Spherizing one link: its parts' spheres to a count or a tolerance, merged when the
//! parts outnumber the spheres, and its report.

use std::time::Instant;

use sphaera_mesh::Sphere;
use sphaera_mesh::geometry::minimum_enclosing_ball_of_balls;
use sphaera_query::Surface;

use super::budget::{Target, divide};
use super::mesh_fit::{ball_bound, mesh_count, mesh_tolerance, prepare_surface};
use super::primitive_fit::{primitive_count, primitive_tolerance};
use super::protrusion::percentile_protrusion;
use super::{LinkFit, LinkReport, LinkSpheres, PartFit, SpherizeOptions};
use crate::RobotError;
use crate::geometry::LinkGeometry;
use crate::primitive::{Primitive, Shape};
pub(super) fn spherize_link(
    link: &LinkGeometry,
    target: Target,
    options: &SpherizeOptions,
) -> Result<LinkSpheres, RobotError> {
    let started = Instant::now();
    let fail = |message: String| RobotError::Spherize {
        link: link.link.clone(),
        message,
    };
    let surface = link
        .mesh
        .as_ref()
        .map(prepare_surface)
        .transpose()
        .map_err(|e| fail(e.to_string()))?;
    let fit = match target {
        Target::Count(n) => fit_count(link, surface.as_ref(), n, options).map_err(fail)?,
        Target::Tolerance(t) => fit_tolerance(link, surface.as_ref(), t, options)?,
    };
    let bounding_sphere =
        minimum_enclosing_ball_of_balls(&fit.spheres).map_err(|e| fail(e.to_string()))?;
    let worst = fit.protrusion;
    // A quantile never exceeds the maximum; rounding in the sampled distances could make
    // it (1e-17 above an exact 0 on a sphere link).
    let p95 =
        percentile_protrusion(&fit.spheres, surface.as_ref(), &link.primitives, 0.95).min(worst);
    let report = LinkReport {
        link: link.link.clone(),
        files: link.files.iter().map(|p| p.display().to_string()).collect(),
        triangles: link
            .mesh
            .as_ref()
            .map_or(0, sphaera_mesh::TriMesh::triangle_count),
        primitives: link.primitives.len(),
        closed: surface.as_ref().is_none_or(Surface::is_embedded_solid),
        shell: surface.as_ref().is_some_and(|s| !s.has_inside()),
        diagonal: link.diagonal(),
        budget: match target {
            Target::Count(n) => Some(n),
            Target::Tolerance(_) => None,
        },
        shortfall: fit.shortfall,
        tolerance: match target {
            Target::Count(_) => None,
            Target::Tolerance(t) => Some(t),
        },
        meets_tolerance: match target {
            Target::Count(_) => None,
            Target::Tolerance(t) => Some(worst <= t),
        },
        spheres: fit.spheres.len(),
        worst_protrusion: worst,
        p95_protrusion: p95,
        coverage: if fit.samples == 0 {
            1.0
        } else {
            fit.covered as f64 / fit.samples as f64
        },
        coverage_certified: fit.certified,
        seconds: started.elapsed().as_secs_f64(),
    };
    Ok(LinkSpheres {
        link: link.link.clone(),
        spheres: fit.spheres,
        bounding_sphere,
        report,
    })
}

/// Exactly `n` spheres for the link (fewer only where a part cannot use them): the
/// count divided among its parts by area, a primitive's unused share handed to the
/// meshes; more parts than spheres share them (one sphere each, the closest merged).
fn fit_count(
    link: &LinkGeometry,
    surface: Option<&Surface>,
    n: usize,
    options: &SpherizeOptions,
) -> Result<LinkFit, String> {
    let parts = usize::from(surface.is_some()) + link.primitives.len();
    if parts > n {
        return merged(link, surface, n, options);
    }
    let mut areas: Vec<f64> = Vec::with_capacity(parts);
    if let Some(surface) = surface {
        areas.push(surface.mesh().surface_area());
    }
    areas.extend(link.primitives.iter().map(Primitive::area));
    let shares = divide(n, &areas);
    let (mesh_share, primitive_shares) = match surface {
        Some(_) => (shares[0], &shares[1..]),
        None => (0, &shares[..]),
    };
    let mut primitives: Vec<PartFit> = Vec::with_capacity(link.primitives.len());
    let mut unused = 0;
    let mut reasons: Vec<String> = Vec::new();
    for (primitive, &share) in link.primitives.iter().zip(primitive_shares) {
        let part = primitive_count(primitive, share, options);
        if part.spheres.len() < share {
            unused += share - part.spheres.len();
            reasons.push(match primitive.shape {
                Shape::Sphere { .. } => "a sphere primitive is its own sphere".to_owned(),
                _ => format!(
                    "the {}'s tightest layout has {} (no set of {share} found is tighter)",
                    primitive.kind(),
                    spheres_text(part.spheres.len())
                ),
            });
        }
        primitives.push(part);
    }
    let mut fit = LinkFit::new();
    if let Some(surface) = surface {
        // The meshes take what the primitives could not use.
        let count = mesh_share + unused;
        let part = mesh_count(surface, count, options)?;
        reasons.clear();
        unused = count - part.spheres.len().min(count);
        if unused > 0 {
            reasons.push(format!(
                "the meshes' surface was divided into only {} regions",
                part.spheres.len()
            ));
        }
        fit.add(part);
    }
    for part in primitives {
        fit.add(part);
    }
    if unused > 0 {
        fit.shortfall = Some(reasons.join("; "));
    }
    Ok(fit)
}

/// `1 sphere`, `6 spheres`.
pub(super) fn spheres_text(n: usize) -> String {
    if n == 1 {
        "1 sphere".to_owned()
    } else {
        format!("{n} spheres")
    }
}

/// Fewer spheres than parts: one sphere per part (the meshes' one-sphere tree, each
/// primitive's own), then the two whose enclosing ball is smallest replaced by it until
/// `n` remain. A merged ball holds the balls it replaces, so the surface stays covered;
/// its protrusion beyond the link is at most its protrusion beyond any one part (eq. 2
/// on the meshes, exact on a primitive).
fn merged(
    link: &LinkGeometry,
    surface: Option<&Surface>,
    n: usize,
    options: &SpherizeOptions,
) -> Result<LinkFit, String> {
    let mut fit = LinkFit::new();
    let mut balls: Vec<Sphere> = Vec::new();
    if let Some(surface) = surface {
        let part = mesh_count(surface, 1, options)?;
        fit.covered += part.covered;
        fit.samples += part.samples;
        fit.certified &= part.certified;
        balls.extend(part.spheres);
    }
    for primitive in &link.primitives {
        let (set, _) = primitive.spherize(1);
        balls.extend(set);
    }
    while balls.len() > n.max(1) {
        let mut best: Option<(f64, usize, usize, Sphere)> = None;
        for i in 0..balls.len() {
            for j in i + 1..balls.len() {
                let ball = minimum_enclosing_ball_of_balls(&[balls[i], balls[j]])
                    .map_err(|e| e.to_string())?;
                if best.is_none_or(|(r, ..)| ball.radius < r) {
                    best = Some((ball.radius, i, j, ball));
                }
            }
        }
        let Some((_, i, j, ball)) = best else {
            break;
        };
        balls.swap_remove(j);
        balls[i] = ball;
    }
    for ball in &balls {
        let mut bound = f64::INFINITY;
        if let Some(surface) = surface {
            bound = ball_bound(surface, *ball)?;
        }
        for primitive in &link.primitives {
            bound = bound.min(primitive.protrusion(ball));
        }
        fit.protrusion = fit.protrusion.max(bound);
    }
    for primitive in &link.primitives {
        let part = PartFit::of_primitive(primitive, balls.clone(), 0.0);
        fit.covered += part.covered;
        fit.samples += part.samples;
    }
    fit.spheres = balls;
    Ok(fit)
}

/// Every link's spheres within `tolerance`: its meshes' tolerance tree, its
/// primitives' fewest analytic spheres.
fn fit_tolerance(
    link: &LinkGeometry,
    surface: Option<&Surface>,
    tolerance: f64,
    options: &SpherizeOptions,
) -> Result<LinkFit, RobotError> {
    let max = options.max_spheres_per_link;
    let unreachable = |message: String| RobotError::ToleranceUnreachable {
        link: link.link.clone(),
        tolerance,
        max,
        message,
    };
    let mut fit = LinkFit::new();
    if let Some(surface) = surface {
        let part = mesh_tolerance(surface, tolerance, options).map_err(|message| {
            RobotError::Spherize {
                link: link.link.clone(),
                message,
            }
        })?;
        if part.spheres.len() > max {
            return Err(unreachable(format!(
                "its meshes need {} spheres",
                part.spheres.len()
            )));
        }
        fit.add(part);
    }
    for primitive in &link.primitives {
        let part = primitive_tolerance(primitive, tolerance, options);
        if part.protrusion > tolerance {
            return Err(unreachable(format!(
                "{} spheres of its {} reach {} beyond it",
                part.spheres.len(),
                primitive.kind(),
                part.protrusion
            )));
        }
        fit.add(part);
    }
    if fit.spheres.len() > max {
        return Err(unreachable(format!(
            "its parts need {} spheres together",
            fit.spheres.len()
        )));
    }
    if fit.protrusion > tolerance {
        // The tolerance trees' leaves meet it by construction; this is a last guard.
        return Err(unreachable(format!(
            "its spheres reach {} beyond it",
            fit.protrusion
        )));
    }
    Ok(fit)
}
