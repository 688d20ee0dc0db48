//! The 2D bounding area of a polyline (the paper's Definitions 1 to 4): two discs with
//! signed radii through the ends of its chord, combined by the ± operator.
//!
//! Every disc through the chord's ends `a` and `b` has its centre on the chord's
//! perpendicular bisector, at `m + t·n` (`m` the chord's midpoint, `n` the unit normal to
//! the left of `a → b`, `h` half the chord's length) and radius `√(h² + t²)`. A lens
//! stores each disc by its **bulge** `k = t / h` (scale free): `k → +∞` is the half-plane
//! left of the chord, `k → −∞` the half-plane right of it, both exactly (the paper's
//! "disc of radius −∞"), never large discs.
//!
//! A point `x` lies in the disc of bulge `k` exactly when `(x − a)·(x − b) ≤ k·o`, where
//! `o = (b − a) × (x − a)` is twice the signed area of `a, b, x` (positive on the left):
//! the power of `x` with respect to the chord's diametral circle against the bisector
//! offset. A vertex `x` to the left is in every disc of bulge at least
//! `(x − a)·(x − b) / o`, one to the right in every disc of bulge at most that value.

use glam::DVec2;

/// Relative slack of [`Lens::may_contain`]: a point within this fraction of the terms'
/// size of a disc's boundary counts as inside, so that rounding can only make a query
/// descend, never prune a part it should have looked at.
pub const CONTAINMENT_SLACK: f64 = 1e-12;

/// Which of the paper's forms a bounding area takes (Definition 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LensKind {
    /// `D₁ ∩ D₂`, a disc and a half-plane included (`D ∩ H`): every bounding area of a
    /// HAL tree over a polygon whose vertices avoid the lines of their chords (Theorem 1).
    Intersection,
    /// `D₁ ∪ D₂`: no single disc through the chord's ends holds the polyline. Theorem 1
    /// says this never happens in 2D; it does when a vertex lies on the chord's line
    /// outside the chord (a collinear back-track), and then one of the discs is a
    /// half-plane.
    Union,
}

/// A disc with a signed radius (Definition 1), or a half-plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SignedDisc {
    /// A disc: its centre, and its radius, negative when the centre lies on the other
    /// side of the chord from the vertex that defines it.
    Disc {
        /// The centre.
        center: DVec2,
        /// The signed radius.
        radius: f64,
    },
    /// A closed half-plane bounded by the chord's line: the points `x` with
    /// `(x − point)·inward ≥ 0`.
    HalfPlane {
        /// A point of the boundary line (the chord's first end).
        point: DVec2,
        /// The unit normal pointing into the half-plane.
        inward: DVec2,
    },
}

/// The bounding area of a polyline from `a` to `b`: the discs through `a` and `b` of
/// bulges `left` (containing the vertices left of `a → b`) and `right` (containing those
/// right of it), combined by the ± operator.
///
/// With no vertex on a side, that side's bulge is the opposite half-plane's
/// (`left = −∞`, `right = +∞`), so that the area is `D ∩ H` as Definition 3 says; with no
/// vertex off the chord's line at all, it is the line itself.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lens {
    /// Bulge of the left disc: `−∞` (no vertex on the left) up to `+∞` (a vertex on the
    /// chord's line, outside the chord).
    pub left: f64,
    /// Bulge of the right disc: `+∞` (no vertex on the right) down to `−∞`.
    pub right: f64,
}

impl Lens {
    /// The lens of no vertex at all (the chord's line).
    pub const EMPTY: Self = Self {
        left: f64::NEG_INFINITY,
        right: f64::INFINITY,
    };

    /// Intersection or union (the ± operator of Definition 2, in bulges: the left disc
    /// lies inside the right one on the left side exactly when `left ≤ right`).
    #[must_use]
    pub fn kind(&self) -> LensKind {
        if self.left <= self.right {
            LensKind::Intersection
        } else {
            LensKind::Union
        }
    }

    /// The widths `w₁` (left) and `w₂` (right) of Definition 4 for the chord `a → b`: the
    /// largest distance from the chord's line to the left disc's boundary on the left, and
    /// to the right disc's on the right. A side without vertices has width 0 (the paper's
    /// half-plane); a half-plane on the vertices' side, infinite width.
    #[must_use]
    pub fn widths(&self, a: DVec2, b: DVec2) -> (f64, f64) {
        let h = 0.5 * a.distance(b);
        (bulge_width(self.left, h), bulge_width(-self.right, h))
    }

    /// `max(w₁, w₂)`: the covering error of this bounding area (the paper's eq. 1 term).
    #[must_use]
    pub fn width(&self, a: DVec2, b: DVec2) -> f64 {
        let (w1, w2) = self.widths(a, b);
        w1.max(w2)
    }

    /// The area of the bounding area for the chord `a → b`: the left disc's cap on the
    /// left of the chord plus the right disc's cap on the right (a side without vertices
    /// adds nothing). Infinite for a half-plane on a vertex's side, `None` for a union.
    #[must_use]
    pub fn area(&self, a: DVec2, b: DVec2) -> Option<f64> {
        if self.kind() == LensKind::Union {
            return None;
        }
        let h = 0.5 * a.distance(b);
        let cap = |k: f64| {
            if k == f64::NEG_INFINITY || h == 0.0 {
                return 0.0;
            }
            if k == f64::INFINITY {
                return f64::INFINITY;
            }
            let r = h * (1.0 + k * k).sqrt();
            let w = bulge_width(k, h);
            // The cap of height w of a circle of radius r.
            let below = r - w;
            r * r * (below / r).clamp(-1.0, 1.0).acos()
                - below * (2.0 * r * w - w * w).max(0.0).sqrt()
        };
        Some(cap(self.left) + cap(-self.right))
    }

    /// The left and right discs in absolute terms, for the chord `a → b`.
    #[must_use]
    pub fn discs(&self, a: DVec2, b: DVec2) -> [SignedDisc; 2] {
        [
            signed_disc(a, b, self.left, 1.0),
            signed_disc(a, b, self.right, -1.0),
        ]
    }

    /// Whether `x` may lie in the bounding area of the chord `a → b`: exact up to
    /// [`CONTAINMENT_SLACK`], on the side of "yes". A union is always answered "yes" (its
    /// parts are not known to contain the polyline's edges, only its vertices), so it
    /// never prunes.
    #[must_use]
    pub fn may_contain(&self, a: DVec2, b: DVec2, x: DVec2) -> bool {
        if self.kind() == LensKind::Union {
            return true;
        }
        let (ab, ax, bx) = (b - a, x - a, x - b);
        let power = ax.dot(bx);
        let area = ab.perp_dot(ax);
        let slack =
            CONTAINMENT_SLACK * (ab.length_squared() + ax.length_squared() + bx.length_squared());
        in_disc(self.left, power, area, slack) && in_disc(self.right, power, area, slack)
    }
}

/// Whether the point with power `power` and doubled signed area `area` lies in the disc of
/// bulge `k`, within `slack` (scaled like a squared length).
fn in_disc(k: f64, power: f64, area: f64, slack: f64) -> bool {
    if k == f64::INFINITY {
        area >= -slack
    } else if k == f64::NEG_INFINITY {
        area <= slack
    } else {
        power - k * area <= slack * (1.0 + k.abs())
    }
}

/// Width of the disc (or ball) of bulge `k` on the side it bulges toward, `h` half the
/// chord (or the circumradius): `t + √(h² + t²)` with `t = k·h`, in a form without
/// cancellation for negative `t`.
pub(crate) fn bulge_width(k: f64, h: f64) -> f64 {
    if k == f64::INFINITY {
        return f64::INFINITY;
    }
    if k == f64::NEG_INFINITY || h == 0.0 {
        return 0.0;
    }
    let root = (1.0 + k * k).sqrt();
    if k >= 0.0 {
        h * (k + root)
    } else {
        h / (root - k)
    }
}

/// The disc of bulge `k` through `a` and `b`, with the sign of Definition 1 for a vertex on
/// side `side` (+1 left, −1 right).
fn signed_disc(a: DVec2, b: DVec2, k: f64, side: f64) -> SignedDisc {
    let ab = b - a;
    let normal = ab.perp().normalize_or_zero();
    if k.is_infinite() {
        return SignedDisc::HalfPlane {
            point: a,
            inward: normal * k.signum(),
        };
    }
    let h = 0.5 * ab.length();
    let t = k * h;
    let radius = h.hypot(t);
    SignedDisc::Disc {
        center: 0.5 * (a + b) + normal * t,
        radius: if t * side < 0.0 { -radius } else { radius },
    }
}

/// The bulge a vertex `x` off the chord `a → b` asks of its side's disc, with the side:
/// `Some((bulge, true))` left, `Some((bulge, false))` right; `None` for a vertex on the
/// chord itself (every disc holds it). A vertex on the chord's line outside the chord asks
/// for the left half-plane (`+∞`). The side is decided by the exact orientation.
#[must_use]
pub fn vertex_bulge(a: DVec2, b: DVec2, x: DVec2) -> Option<(f64, bool)> {
    let orientation = robust::orient2d(coord(a), coord(b), coord(x));
    let power = (x - a).dot(x - b);
    if orientation == 0.0 {
        return (power > 0.0).then_some((f64::INFINITY, true));
    }
    // `orient2d` is twice the signed area, positive on the left of `a → b` (its sign is
    // exact, its value accurate to rounding).
    Some((power / orientation, orientation > 0.0))
}

/// A `robust` coordinate.
pub(crate) fn coord(p: DVec2) -> robust::Coord<f64> {
    robust::Coord { x: p.x, y: p.y }
}
