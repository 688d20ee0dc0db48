//! The certified error of one sphere: branch and bound over its surface.

use std::cmp::Reverse;

use glam::DVec3;
use sphaera_mesh::heap::{MaxHeap, Priority, TotalF64};
use sphaera_query::Surface;
use sphaera_query::winding::WindingBoundary;

use super::EvaluationOptions;
use super::patch::{Patch, Probe, icosahedron, upper_bound};
use crate::{Sphere, SphereTreeError};

/// Fraction of the tolerance below which a point's inside/outside classification is not
/// trusted (the guard band, see the [module documentation](super)).
const GUARD_FRACTION: f64 = 0.25;

/// The certified error of one sphere: the largest distance from a point of its surface
/// lying outside the object to the object's surface lies in `[lower, upper]`.
///
/// # Examples
///
/// ```
/// use sphaera_query::Surface;
/// use sphaera_mesh::shapes;
/// use sphaera_spheretree::evaluate::{EvaluationOptions, sphere_error};
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let mesh = shapes::cube(2.0, 1)?; // [-1, 1]³
/// let surface = Surface::new(&mesh)?;
/// // A ball poking 0.5 out of the top face: its error is 0.5.
/// let fit = sphere_error(&surface, &Sphere::new(DVec3::new(0.0, 0.0, 0.5), 1.0),
///     &EvaluationOptions::default())?;
/// assert!(fit.converged && fit.lower <= 0.5 + 1e-9 && 0.5 <= fit.upper + 1e-9);
/// assert!(fit.upper - fit.lower <= EvaluationOptions::default().tolerance_for(surface.diagonal()));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereFit {
    /// A true value of the error: `f` at an evaluated point of the sphere's surface (0 when
    /// no evaluated point lies outside the object beyond the guard band).
    pub lower: f64,
    /// A certified bound of the error: no point of the sphere's surface lies outside the
    /// object farther than this from the object's surface.
    pub upper: f64,
    /// Whether `upper − lower` reached the tolerance within the patch budget. When
    /// `false` the interval is still valid, only wider.
    pub converged: bool,
    /// The number of patches evaluated (the cost: one closest-point query and at most one
    /// inside test each).
    pub patches: usize,
    /// The evaluated point where `lower` was found (`None` when `lower` is 0).
    pub witness: Option<DVec3>,
}

/// A patch in the queue, ordered by its upper bound (then by creation order, for
/// determinism).
struct Queued {
    upper: f64,
    order: usize,
    patch: Patch,
    /// What its evaluation found, for its children.
    found: Side,
}

/// A probe whose side of the surface is known: its point, its distance to the surface
/// and whether it is inside, with what its children need to inherit that side on a mesh
/// with holes (see [`Search::evaluate`]).
#[derive(Clone, Copy)]
struct Side {
    point: DVec3,
    distance: f64,
    inside: Option<bool>,
    /// A certified lower bound of `|w − ½|` at the point (infinite on a closed mesh, where
    /// it is not needed).
    margin: f64,
    /// The chord of the probe's patch: every point of the patch, among them its
    /// children's probes, lies within it.
    reach: f64,
    /// A bound of the winding number's gradient off the mesh within `reach` of the point
    /// (0 on a closed mesh).
    gradient: f64,
    /// On a mesh with holes, the integer winding number at the point of the mesh closed
    /// by its caps, when known (see [`Search::evaluate`]).
    closed: Option<f64>,
}

/// A patch evaluated: its bound and what its probe found, or its inside test put off.
enum Evaluated {
    Known(f64, Side),
    Deferred(Deferred),
}

/// A dropped patch whose probe's side was not asked (see [`Search::evaluate`]): its bound
/// taken as outside holds whatever the side; the side can only lower it.
struct Deferred {
    /// The bound taken as outside, capped by the parent's.
    upper: f64,
    /// The parent's bound.
    cap: f64,
    patch: Patch,
    point: DVec3,
    probe: Probe,
    /// The margin its inside bound needs (0 on a closed mesh, see [`Search::evaluate`]).
    needed: f64,
}

impl Deferred {
    /// The patch's bound with its probe's side known: what the search would have dropped
    /// it with.
    fn settle(&self, search: &Search<'_>) -> f64 {
        let inside = if search.holes.is_none() {
            search.surface.is_inside_certified(self.point)
        } else {
            search
                .surface
                .side_with_margin(self.point, self.needed)
                .is_some_and(|side| side.inside && side.margin > self.needed)
        };
        if !inside {
            return self.upper;
        }
        let probe = Probe {
            trusted_inside: true,
            ..self.probe
        };
        upper_bound(&self.patch, search.center, search.radius, &probe).min(self.cap)
    }
}

impl Priority for Queued {
    type Key = (TotalF64, Reverse<usize>);

    /// Largest bound first; among equal bounds the oldest patch first.
    fn priority(&self) -> Self::Key {
        (TotalF64(self.upper), Reverse(self.order))
    }
}

/// The state of one sphere's branch and bound.
struct Search<'a> {
    surface: &'a Surface,
    /// The boundary chain of a mesh with holes taken as a solid (`None` for a closed mesh
    /// or a certified embedded solid, where the winding number changes only across it).
    holes: Option<&'a WindingBoundary>,
    center: DVec3,
    radius: f64,
    guard: f64,
    lower: f64,
    witness: Option<DVec3>,
    patches: usize,
}

impl Search<'_> {
    /// Evaluates the representative point of `patch`, raises the lower bound and returns
    /// the patch's upper bound and what the probe found.
    ///
    /// The inside test is skipped when the parent's probe (`parent`) is known to lie on
    /// one side and the new probe lies in the ball about it that holds no surface (closer
    /// to it than its distance to the surface, by more than the guard band): the segment
    /// between them crosses no surface, so both lie on the same side.
    ///
    /// It is put off ([`Evaluated::Deferred`]) when it cannot change the search: the
    /// probe is no farther from the surface than the lower bound (so it cannot raise it),
    /// and the patch's bound taken as outside, capped by `cap` (the parent's bound), is
    /// already within `tolerance` of the lower bound (so the patch is dropped whatever its
    /// side). Only the final upper bound may need its side ([`Deferred::settle`]).
    ///
    /// # Meshes with holes
    ///
    /// Across a hole the winding number `w` passes ½ without crossing a triangle, so
    /// neither that inheritance nor the inside bound of [`upper_bound`] follows from a
    /// clear segment alone. What does hold (the boundary bound, see
    /// [`WindingBoundary`]): on a segment `[p, x]` that meets no triangle, `|w(x) − w(p)|`
    /// is at most `|x − p|` times a bound `G` of `|∇w|` near it, which the rims of the holes
    /// give. Each probe therefore carries a certified margin `m ≤ |w(p) − ½|`
    /// ([`Surface::side_with_margin`]) and the bound `G` over the ball of its patch's chord
    /// `ρ` (every point of the patch, and every child's probe, lies in that ball):
    ///
    /// - a child's probe `c` in the clear ball (`[p, c]` meets no triangle) with
    ///   `m − |c − p| G > 0` has `|w(c) − w(p)| < m`, so it lies on `p`'s side, with the
    ///   margin `m − |c − p| G`;
    /// - `p` inside with `m > ρ G`: a point `x` of the patch outside (`w(x) ≤ ½`) differs
    ///   from `w(p)` by at least `m > |x − p| G`, so `[p, x]` meets a triangle, at least
    ///   `d(p)` from `p`, and `f(x) ≤ |x − p| − d(p)`: the inside bound holds. Otherwise
    ///   the patch gets only the bounds valid on both sides, and is split until it is
    ///   small enough (`ρ G` shrinks with `ρ` while the margin stays).
    ///
    /// On a closed mesh `G = 0` and this is the argument above, at no cost.
    fn evaluate(
        &mut self,
        patch: &Patch,
        parent: Option<(&Side, f64)>,
        tolerance: f64,
    ) -> Result<Evaluated, SphereTreeError> {
        self.patches += 1;
        let point = self.center + self.radius * patch.direction;
        let reach = patch.chord(self.radius);
        // The parent's probe bounds the distance (the distance is 1-Lipschitz), which
        // prunes the descent from the start; the answer is the same.
        // On a certified embedded solid the side comes with the closest point at the cost
        // of the closest point alone (the pseudo-normal test); elsewhere the side is asked
        // of the certified winding number only where it is needed and not inherited.
        if self.surface.is_embedded_solid() {
            let signed = self.surface.signed_closest(point)?;
            let distance = signed.closest.distance;
            let inside = (distance > self.guard).then_some(signed.inside);
            let side = Side {
                point,
                distance,
                inside,
                margin: f64::INFINITY,
                reach,
                gradient: 0.0,
                closed: None,
            };
            let (upper, found) = self.record(patch, signed.closest.point, side);
            return Ok(Evaluated::Known(upper, found));
        }
        let bound = parent.map(|(p, _)| (p.distance + point.distance(p.point)) * (1.0 + 1e-9));
        let closest = match bound {
            Some(bound) => match self.surface.tree().closest_within(point, bound)? {
                Some(found) => found,
                None => self.surface.closest(point)?,
            },
            None => self.surface.closest(point)?,
        };
        let distance = closest.distance;
        let mut side = Side {
            point,
            distance,
            inside: None,
            margin: 0.0,
            reach,
            gradient: 0.0,
            closed: None,
        };
        if distance <= self.guard {
            let (upper, found) = self.record(patch, closest.point, side);
            return Ok(Evaluated::Known(upper, found));
        }
        // On a mesh with holes: the gradient bound over the patch's ball and the margin
        // the inside bound needs there (`m > ρ G`, see above).
        let needed = match self.holes {
            Some(holes) => {
                side.gradient = holes.gradient_bound(point, reach);
                reach * side.gradient * (1.0 + 1e-9)
            }
            None => 0.0,
        };
        // A probe in the clear ball of its parent's probe, or with its parent's probe in
        // its own clear ball, is on the parent's side: the segment between them crosses
        // no surface (on a mesh with holes, only while the parent's margin less the step
        // times its gradient bound stays positive, and with that margin).
        let inherited = parent.and_then(|(p, _)| {
            let step = point.distance(p.point);
            let clear = p.distance.max(distance) - self.guard;
            if self.holes.is_none() {
                return p
                    .inside
                    .filter(|_| step < clear)
                    .map(|inside| (inside, f64::INFINITY));
            }
            let margin = p.margin - step * p.gradient * (1.0 + 1e-9);
            let inherits = step < clear && step <= p.reach && margin > 0.0;
            p.inside.filter(|_| inherits).map(|inside| (inside, margin))
        });
        // An inherited side that already gives what the bound can use (outside, or
        // inside with the margin the inside bound needs) is final; otherwise the
        // certified test is asked, or put off.
        let settled = inherited.filter(|&(inside, margin)| !inside || margin > needed);
        // A probe known to be inside (its margin too small for the inside bound) cannot
        // raise `lower` either, wherever it lies.
        let known_inside = inherited.is_some_and(|(inside, _)| inside);
        if settled.is_none()
            && let Some((_, cap)) = parent
            && (distance <= self.lower || known_inside)
        {
            let probe = Probe {
                distance,
                closest: closest.point,
                trusted_inside: false,
            };
            let outside = upper_bound(patch, self.center, self.radius, &probe).min(cap);
            if outside - self.lower <= tolerance {
                return Ok(Evaluated::Deferred(Deferred {
                    upper: outside,
                    cap,
                    patch: *patch,
                    point,
                    probe,
                    needed,
                }));
            }
        }
        // On a mesh with holes, the closed winding number is handed on along a segment
        // that meets neither the mesh (the clear balls) nor the caps, and gives the side
        // and margin at the cost of the caps' solid angles.
        let handed = match (self.holes, parent) {
            (Some(holes), Some((p, _))) => p.closed.filter(|_| {
                point.distance(p.point) < p.distance.max(distance) - self.guard
                    && holes.caps_avoid_segment(p.point, point)
            }),
            _ => None,
        };
        side.closed = handed;
        // A probe no certified evaluation decides (on the ½ level set within rounding, or
        // within rounding of a cap's edge and near `w = ½`) stays unclassified, as in
        // the guard band: its patch keeps the bounds valid on both sides and it never
        // raises `lower`.
        let decided = match settled {
            Some(decided) => Some(decided),
            None if self.holes.is_none() => {
                Some((self.surface.is_inside_certified(point), f64::INFINITY))
            }
            None => {
                let by_hand = handed.zip(self.holes).and_then(|(closed, holes)| {
                    holes
                        .side_given_closed(point, closed)
                        .map(|c| (c.inside, c.margin))
                });
                by_hand
                    .or_else(|| {
                        let (closed, certified) = self.surface.capped_side(point)?;
                        side.closed = Some(closed);
                        Some((certified.inside, certified.margin))
                    })
                    .or_else(|| {
                        self.surface
                            .side_with_margin(point, needed)
                            .map(|certified| (certified.inside, certified.margin))
                    })
                    .or(inherited)
            }
        };
        if let Some((inside, margin)) = decided {
            side.inside = Some(inside);
            side.margin = margin;
        }
        let (upper, found) = self.record(patch, closest.point, side);
        Ok(Evaluated::Known(upper, found))
    }

    /// Raises the lower bound with a probe whose side is known (`None` within the guard
    /// band) and returns the patch's upper bound and what the probe found. The inside
    /// bound is used only where the probe's margin covers the patch (`m > ρ G`, see
    /// [`Search::evaluate`]; always on a closed mesh).
    fn record(&mut self, patch: &Patch, closest: DVec3, side: Side) -> (f64, Side) {
        let (trusted_outside, inside) = match side.inside {
            Some(inside) => (!inside, inside),
            None => (false, false),
        };
        let trusted_inside = inside && side.margin > side.reach * side.gradient * (1.0 + 1e-9);
        if trusted_outside && side.distance > self.lower {
            self.lower = side.distance;
            self.witness = Some(side.point);
        }
        let probe = Probe {
            distance: side.distance,
            closest,
            trusted_inside,
        };
        (upper_bound(patch, self.center, self.radius, &probe), side)
    }
}

/// The certified error of `sphere` against the object of `surface`: an interval
/// `[lower, upper]` containing `E = max f` over the sphere's surface, where `f(x)` is the
/// distance from `x` to the mesh surface when `x` is outside the object and 0 inside.
///
/// Branch and bound over spherical-triangle patches of the sphere's surface (see the
/// [module documentation](super)), best first by upper bound, until `upper − lower` is at
/// most the tolerance of `options` or the patch budget is spent (`converged: false`).
///
/// # Examples
///
/// ```
/// use sphaera_query::Surface;
/// use sphaera_mesh::shapes;
/// use sphaera_spheretree::evaluate::{EvaluationOptions, sphere_error};
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let surface = Surface::new(&shapes::sphere(1.0, 24)?)?;
/// let options = EvaluationOptions::default();
/// // Inside: no error.
/// let inside = sphere_error(&surface, &Sphere::new(DVec3::ZERO, 0.5), &options)?;
/// assert_eq!((inside.lower, inside.upper), (0.0, 0.0));
/// // Outside, 1 from the unit ball: the farthest point is 1 + 2·0.5 = 2 away.
/// let outside = sphere_error(&surface, &Sphere::new(DVec3::new(2.5, 0.0, 0.0), 0.5), &options)?;
/// assert!(outside.converged && (outside.lower - 2.0).abs() < 2e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`SphereTreeError::InvalidSphere`] (index 0) for a NaN or infinite centre or radius or a
/// negative radius; [`SphereTreeError::InvalidParameter`] for bad options.
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// Each patch costs one closest-point query and (away from the surface) one
/// winding-number inside test. A sphere whose error is attained at a single point
/// converges in a few hundred patches; flat maxima (a sphere concentric with a round
/// object) need more, up to the budget.
pub fn sphere_error(
    surface: &Surface,
    sphere: &Sphere,
    options: &EvaluationOptions,
) -> Result<SphereFit, SphereTreeError> {
    let tolerance = options.checked_tolerance(surface.diagonal())?;
    if !sphere.is_valid() {
        return Err(SphereTreeError::InvalidSphere { index: 0 });
    }
    fit(
        surface,
        sphere,
        tolerance,
        options.max_patches,
        f64::NEG_INFINITY,
    )
}

/// The branch and bound, for a valid sphere and a checked tolerance.
///
/// The search also stops, converged, once the sphere's upper bound is at most `settle`:
/// a caller looking for the worst of several spheres needs no more of a sphere that
/// cannot exceed what another already reached (`f64::NEG_INFINITY`: never).
pub(crate) fn fit(
    surface: &Surface,
    sphere: &Sphere,
    tolerance: f64,
    max_patches: usize,
    settle: f64,
) -> Result<SphereFit, SphereTreeError> {
    let holes = (surface.has_inside() && !surface.is_embedded_solid())
        .then(|| surface.winding_boundary())
        .filter(|b| !b.is_empty());
    let mut search = Search {
        surface,
        holes,
        center: sphere.center,
        radius: sphere.radius,
        guard: GUARD_FRACTION * tolerance,
        lower: 0.0,
        witness: None,
        patches: 0,
    };
    let mut queue = MaxHeap::new();
    // The largest upper bound of the patches dropped because they can no longer matter.
    let mut dropped = 0.0_f64;
    let mut order = 0_usize;
    // The dropped patches whose side was put off.
    let mut deferred: Vec<Deferred> = Vec::new();
    for patch in icosahedron() {
        // A patch without parent is never deferred; were it, its side unknown is safe.
        let (upper, found) = match search.evaluate(&patch, None, tolerance)? {
            Evaluated::Known(upper, found) => (upper, found),
            Evaluated::Deferred(d) => (
                d.upper,
                Side {
                    point: d.point,
                    distance: d.probe.distance,
                    inside: None,
                    margin: 0.0,
                    reach: d.patch.chord(sphere.radius),
                    gradient: 0.0,
                    closed: None,
                },
            ),
        };
        queue.push(Queued {
            upper,
            order,
            patch,
            found,
        });
        order += 1;
    }
    let converged = loop {
        let Some(top) = queue.pop() else {
            break true;
        };
        if top.upper - search.lower <= tolerance || top.upper <= settle {
            queue.push(top);
            break true;
        }
        if search.patches + 4 > max_patches {
            queue.push(top);
            break false;
        }
        for child in top.patch.split() {
            // A child's bound may exceed its parent's (each is computed independently);
            // the parent's also holds on the child, so keep the smaller.
            match search.evaluate(&child, Some((&top.found, top.upper)), tolerance)? {
                Evaluated::Deferred(d) => deferred.push(d),
                Evaluated::Known(upper, found) => {
                    let upper = upper.min(top.upper);
                    if upper - search.lower <= tolerance {
                        dropped = dropped.max(upper);
                    } else {
                        queue.push(Queued {
                            upper,
                            order,
                            patch: child,
                            found,
                        });
                    }
                }
            }
            order += 1;
        }
    };
    let open = queue.peek().map_or(0.0, |q| q.upper);
    let mut upper = open.max(dropped).max(search.lower);
    // The put-off sides that could raise the upper bound, largest bound first: with its
    // side known each patch has the bound it would have been dropped with.
    deferred.sort_by(|a, b| b.upper.total_cmp(&a.upper));
    for d in &deferred {
        if d.upper <= upper {
            break;
        }
        upper = upper.max(d.settle(&search));
    }
    Ok(SphereFit {
        lower: search.lower,
        upper,
        converged,
        patches: search.patches,
        witness: search.witness,
    })
}

/// [`sphere_error`] for every sphere, in parallel with the `parallel` feature (the results
/// are identical either way). An empty slice gives an empty vector.
///
/// # Examples
///
/// ```
/// use sphaera_query::Surface;
/// use sphaera_mesh::shapes;
/// use sphaera_spheretree::evaluate::{EvaluationOptions, sphere_errors};
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let surface = Surface::new(&shapes::cube(2.0, 1)?)?;
/// let spheres = [Sphere::new(DVec3::ZERO, 0.5), Sphere::new(DVec3::new(1.0, 0.0, 0.0), 0.25)];
/// let fits = sphere_errors(&surface, &spheres, &EvaluationOptions::default())?;
/// assert_eq!(fits[0].upper, 0.0);
/// assert!((fits[1].lower - 0.25).abs() < 1e-3 && fits[1].upper >= 0.25 - 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`SphereTreeError::InvalidSphere`] with the index of the first invalid sphere;
/// [`SphereTreeError::InvalidParameter`] for bad options.
///
/// # Panics
///
/// Never.
pub fn sphere_errors(
    surface: &Surface,
    spheres: &[Sphere],
    options: &EvaluationOptions,
) -> Result<Vec<SphereFit>, SphereTreeError> {
    let tolerance = options.checked_tolerance(surface.diagonal())?;
    check_spheres(spheres)?;
    let max_patches = options.max_patches;
    let one = |s: &Sphere| fit(surface, s, tolerance, max_patches, f64::NEG_INFINITY);
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        spheres.par_iter().map(one).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        spheres.iter().map(one).collect()
    }
}

/// `Ok` when every sphere is valid, else the index of the first invalid one.
pub(crate) fn check_spheres(spheres: &[Sphere]) -> Result<(), SphereTreeError> {
    match spheres.iter().position(|s| !s.is_valid()) {
        Some(index) => Err(SphereTreeError::InvalidSphere { index }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use sphaera_mesh::{TriMesh, shapes};
    use sphaera_tests::point_sets::fibonacci_sphere;

    use super::*;

    /// On a mesh that is not an embedded solid (a capsule with a hole at its top pole) the
    /// sides are asked of the winding number, some put off; the bounds still bracket the
    /// error sampled densely, away from the hole.
    #[test]
    fn put_off_sides_keep_the_bounds_of_an_open_mesh() {
        let mesh = shapes::capsule(0.5, 2.0, 16).expect("capsule");
        let kept: Vec<[u32; 3]> = mesh
            .triangles()
            .iter()
            .copied()
            .filter(|t| t.iter().all(|&v| mesh.positions()[v as usize].z < 1.4))
            .collect();
        let holed = TriMesh::new(mesh.positions().to_vec(), kept).expect("mesh");
        let surface = Surface::new(&holed).expect("surface");
        assert!(surface.has_inside() && !surface.is_embedded_solid());
        let tolerance = 1e-3;
        for sphere in [
            Sphere::new(DVec3::new(0.0, 0.0, -0.5), 0.6),
            Sphere::new(DVec3::new(0.3, 0.0, -0.2), 0.3),
            Sphere::new(DVec3::new(0.0, 0.2, 0.0), 0.55),
        ] {
            let fit = fit(&surface, &sphere, tolerance, 100_000, f64::NEG_INFINITY).expect("fit");
            assert!(fit.converged && fit.upper - fit.lower <= tolerance + 1e-12);
            let sampled = fibonacci_sphere(20_000)
                .into_iter()
                .map(|u| sphere.center + sphere.radius * u)
                .filter(|&x| !surface.is_inside_certified(x))
                .map(|x| surface.closest(x).expect("closest").distance)
                .fold(0.0, f64::max);
            assert!(sampled <= fit.upper + 1e-12, "{sampled} > {}", fit.upper);
            assert!(
                fit.lower <= sampled + tolerance,
                "{} vs {sampled}",
                fit.lower
            );
        }
    }
}
