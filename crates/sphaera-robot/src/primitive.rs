//! URDF primitives (box, cylinder, sphere, capsule) spherized analytically.
//!
//! Every primitive is convex, so how far a ball `B(c, R)` reaches beyond it is exactly
//! `max(0, R + d(c))`, with `d` the signed distance to the primitive (negative inside):
//! the distance from a point to a convex set is the largest of `u·p − h(u)` over unit
//! `u` (`h`: the support function), and over the ball that is `R + d(c)`. The sphere
//! sets below cover the primitive's surface by construction, and their protrusion is
//! computed with that formula, so it is exact, not estimated.

use glam::{DAffine3, DVec2, DVec3};
use sphaera_mesh::Sphere;

/// A primitive in its own frame (centred on the origin, cylinders and capsules along z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A box of these half side lengths.
    Box {
        /// Half the side lengths.
        half: DVec3,
    },
    /// A cylinder.
    Cylinder {
        /// Its radius.
        radius: f64,
        /// Half its length.
        half_length: f64,
    },
    /// A sphere.
    Sphere {
        /// Its radius.
        radius: f64,
    },
    /// A capsule: the points within `radius` of the segment `z ∈ [−h, h]`.
    Capsule {
        /// Its radius.
        radius: f64,
        /// Half the distance between its caps' centres.
        half_length: f64,
    },
}

/// A primitive placed in a link's frame by a rigid transform.
///
/// # Examples
///
/// ```
/// use glam::{DAffine3, DVec3};
/// use sphaera_robot::{Primitive, Shape};
///
/// let rod = Primitive::new(Shape::Capsule { radius: 0.05, half_length: 0.2 }, DAffine3::IDENTITY);
/// let (spheres, protrusion) = rod.spherize(5);
/// assert_eq!(spheres.len(), 5);
/// // Spheres 0.1 apart on the axis reach √(0.05² + 0.05²) − 0.05 beyond the capsule.
/// assert!((protrusion - (0.05f64.hypot(0.05) - 0.05)).abs() < 1e-12);
/// assert!(rod.signed_distance(DVec3::new(0.0, 0.0, 0.25)) < 0.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Primitive {
    /// The shape, in its own frame.
    pub shape: Shape,
    /// Its frame in the link's frame (rigid).
    pub pose: DAffine3,
}

impl Primitive {
    /// A shape placed by `pose`.
    #[must_use]
    pub fn new(shape: Shape, pose: DAffine3) -> Self {
        Self { shape, pose }
    }

    /// The kind's name: `box`, `cylinder`, `sphere` or `capsule`.
    #[must_use]
    pub fn kind(&self) -> &'static str {
        match self.shape {
            Shape::Box { .. } => "box",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Sphere { .. } => "sphere",
            Shape::Capsule { .. } => "capsule",
        }
    }

    /// Its surface area.
    #[must_use]
    pub fn area(&self) -> f64 {
        use std::f64::consts::PI;
        match self.shape {
            Shape::Box { half: h } => 8.0 * (h.x * h.y + h.y * h.z + h.z * h.x),
            Shape::Cylinder {
                radius: r,
                half_length: h,
            } => 2.0 * PI * r * r + 4.0 * PI * r * h,
            Shape::Sphere { radius: r } => 4.0 * PI * r * r,
            Shape::Capsule {
                radius: r,
                half_length: h,
            } => 4.0 * PI * r * r + 4.0 * PI * r * h,
        }
    }

    /// The corners of its bounding box in its own frame, placed in the link's frame.
    #[must_use]
    pub fn box_corners(&self) -> Vec<DVec3> {
        let half = self.local_half();
        (0..8)
            .map(|i| {
                let sign = DVec3::new(
                    if i & 1 == 0 { -1.0 } else { 1.0 },
                    if i & 2 == 0 { -1.0 } else { 1.0 },
                    if i & 4 == 0 { -1.0 } else { 1.0 },
                );
                self.pose.transform_point3(sign * half)
            })
            .collect()
    }

    /// Half the sides of its bounding box in its own frame.
    fn local_half(&self) -> DVec3 {
        match self.shape {
            Shape::Box { half } => half,
            Shape::Cylinder {
                radius,
                half_length,
            } => DVec3::new(radius, radius, half_length),
            Shape::Sphere { radius } => DVec3::splat(radius),
            Shape::Capsule {
                radius,
                half_length,
            } => DVec3::new(radius, radius, half_length + radius),
        }
    }

    /// The signed distance from `p` (link frame) to the primitive: negative inside.
    #[must_use]
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        local_signed_distance(&self.shape, self.pose.inverse().transform_point3(p))
    }

    /// How far the ball `sphere` (link frame) reaches beyond the primitive: exactly
    /// `max(0, r + d(c))`.
    #[must_use]
    pub fn protrusion(&self, sphere: &Sphere) -> f64 {
        (sphere.radius + self.signed_distance(sphere.center)).max(0.0)
    }

    /// At most `count` spheres (at least one) covering the primitive, in the link's frame,
    /// and how far they reach beyond it (exact). A sphere takes one sphere whatever the
    /// count; a capsule spheres along its axis; a cylinder slabs along its axis, each
    /// split into a grid across when that is tighter; a box the boundary cells of the
    /// grid that is tightest.
    #[must_use]
    pub fn spherize(&self, count: usize) -> (Vec<Sphere>, f64) {
        let count = count.max(1);
        let layout = match self.shape {
            Shape::Sphere { radius } => vec![Sphere::new(DVec3::ZERO, radius)],
            Shape::Capsule {
                radius,
                half_length,
            } => capsule_spheres(radius, half_length, count),
            Shape::Box { half } => box_spheres(half, count),
            Shape::Cylinder {
                radius,
                half_length,
            } => cylinder_spheres(radius, half_length, count),
        };
        // The regular layout, or cells split where they reach farthest when that is
        // tighter (a cylinder's rim, a flat box).
        let worst = |set: &[Sphere]| {
            set.iter()
                .map(|s| (s.radius + local_signed_distance(&self.shape, s.center)).max(0.0))
                .fold(0.0, f64::max)
        };
        let local = match self.shape {
            Shape::Sphere { .. } => layout,
            _ => {
                let half = self.local_half();
                let split = split_cells(&self.shape, -half, half, count);
                if !split.is_empty() && worst(&split) < worst(&layout) {
                    split
                } else {
                    layout
                }
            }
        };
        let spheres: Vec<Sphere> = local
            .iter()
            .map(|s| Sphere::new(self.pose.transform_point3(s.center), s.radius))
            .collect();
        let protrusion = local
            .iter()
            .map(|s| (s.radius + local_signed_distance(&self.shape, s.center)).max(0.0))
            .fold(0.0, f64::max);
        (spheres, protrusion)
    }

    /// The fewest spheres (up to `max_count`) whose protrusion is at most `tolerance`,
    /// with their protrusion; the set for `max_count` when none meets it.
    #[must_use]
    pub fn spherize_within(&self, tolerance: f64, max_count: usize) -> (Vec<Sphere>, f64) {
        let max_count = max_count.max(1);
        // Protrusion does not always fall with the count (grids change shape), so the
        // counts are tried in order; each try is a closed form or a short enumeration.
        let mut count = 1;
        loop {
            let (spheres, protrusion) = self.spherize(count);
            if protrusion <= tolerance || count >= max_count {
                return (spheres, protrusion);
            }
            count = (count + 1).max(count + count / 8);
            count = count.min(max_count);
        }
    }

    /// A closed mesh inside the primitive whose surface is within `gap` of the
    /// primitive's surface (link frame), with that gap: a box exactly (gap 0), a cylinder
    /// with its vertices on the true surface (gap `r·(1 − cos(π/n))`, `n` = 96 segments
    /// around). Spheres covering the mesh's surface, grown by the gap, cover the
    /// primitive's. `None` for spheres and capsules, whose axis layouts are already tight.
    #[must_use]
    pub fn inscribed_mesh(&self) -> Option<(sphaera_mesh::TriMesh, f64)> {
        const AROUND: usize = 96;
        let (mesh, gap) = match self.shape {
            Shape::Box { half } => {
                let cube = sphaera_mesh::shapes::cube(2.0, 4).ok()?;
                let (lo, hi) = cube.positions().iter().fold(
                    (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                    |(lo, hi), &p| (lo.min(p), hi.max(p)),
                );
                let center = 0.5 * (lo + hi);
                let scale = 2.0 * half / (hi - lo);
                let positions = cube
                    .positions()
                    .iter()
                    .map(|&p| (p - center) * scale)
                    .collect();
                (
                    sphaera_mesh::TriMesh::new(positions, cube.triangles().to_vec()).ok()?,
                    0.0,
                )
            }
            Shape::Cylinder {
                radius,
                half_length,
            } => (
                sphaera_mesh::shapes::cylinder(radius, 2.0 * half_length, AROUND).ok()?,
                radius * (1.0 - (std::f64::consts::PI / AROUND as f64).cos()),
            ),
            Shape::Sphere { .. } | Shape::Capsule { .. } => return None,
        };
        let placed = mesh
            .positions()
            .iter()
            .map(|&p| self.pose.transform_point3(p))
            .collect();
        Some((
            sphaera_mesh::TriMesh::new(placed, mesh.triangles().to_vec()).ok()?,
            gap,
        ))
    }

    /// `count` points spread over the primitive's surface (link frame), deterministic:
    /// for dense coverage checks.
    #[must_use]
    pub fn surface_points(&self, count: usize) -> Vec<DVec3> {
        let n = count.max(1);
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        let local: Vec<DVec3> = (0..n)
            .map(|i| {
                let t = (i as f64 + 0.5) / n as f64;
                let angle = golden * i as f64;
                // A direction spread over the sphere (a Fibonacci lattice), pushed out to
                // the surface along the shape's own parametrization.
                let z = 1.0 - 2.0 * t;
                let ring = (1.0 - z * z).max(0.0).sqrt();
                let u = DVec3::new(ring * angle.cos(), ring * angle.sin(), z);
                project_to_surface(&self.shape, u, t)
            })
            .collect();
        local
            .into_iter()
            .map(|p| self.pose.transform_point3(p))
            .collect()
    }
}

fn local_signed_distance(shape: &Shape, p: DVec3) -> f64 {
    match *shape {
        Shape::Box { half } => {
            let q = p.abs() - half;
            q.max(DVec3::ZERO).length() + q.max_element().min(0.0)
        }
        Shape::Cylinder {
            radius,
            half_length,
        } => {
            let d = DVec2::new(p.truncate().length() - radius, p.z.abs() - half_length);
            d.max(DVec2::ZERO).length() + d.max_element().min(0.0)
        }
        Shape::Sphere { radius } => p.length() - radius,
        Shape::Capsule {
            radius,
            half_length,
        } => {
            let z = p.z.clamp(-half_length, half_length);
            (p - DVec3::new(0.0, 0.0, z)).length() - radius
        }
    }
}

/// A point of the surface in direction `u` (for a box, a cylinder and a capsule: the
/// ray from the centre; `t` spreads the points along the length of long shapes).
fn project_to_surface(shape: &Shape, u: DVec3, t: f64) -> DVec3 {
    match *shape {
        Shape::Sphere { radius } => u * radius,
        Shape::Box { half } => {
            // The ray from the centre meets the face where the largest scaled component
            // reaches 1.
            let scaled = u / half;
            u / scaled.abs().max_element()
        }
        Shape::Cylinder {
            radius,
            half_length,
        } => {
            let around = u.truncate().try_normalize().unwrap_or(DVec2::X);
            // Half the points on the side, half on the caps.
            if t < 0.5 {
                let z = -half_length + 4.0 * t * half_length;
                (around * radius).extend(z)
            } else {
                let s = ((t - 0.5) * 2.0).sqrt();
                let z = if u.z >= 0.0 {
                    half_length
                } else {
                    -half_length
                };
                (around * radius * s).extend(z)
            }
        }
        Shape::Capsule {
            radius,
            half_length,
        } => {
            let z = -half_length + 2.0 * t * half_length;
            let around = u.truncate().try_normalize().unwrap_or(DVec2::X);
            if t < 0.5 {
                (around * radius).extend(z)
            } else {
                let cap = if u.z >= 0.0 {
                    half_length
                } else {
                    -half_length
                };
                DVec3::new(0.0, 0.0, cap) + u * radius
            }
        }
    }
}

/// A box cell of the primitive's bounding box and its circumscribed sphere.
#[derive(Clone, Copy)]
struct Cell {
    lo: DVec3,
    hi: DVec3,
}

impl Cell {
    fn sphere(&self) -> Sphere {
        Sphere::new(
            0.5 * (self.lo + self.hi),
            0.5 * (self.hi - self.lo).length(),
        )
    }

    /// Whether the cell may hold part of the surface: some corner is outside or on it
    /// (the signed distance is convex, so its largest value is at a corner) and the
    /// solid comes within the cell's ball.
    fn may_hold_surface(&self, shape: &Shape) -> bool {
        let s = self.sphere();
        let outside = (0..8).any(|i| {
            let corner = DVec3::new(
                if i & 1 == 0 { self.lo.x } else { self.hi.x },
                if i & 2 == 0 { self.lo.y } else { self.hi.y },
                if i & 4 == 0 { self.lo.z } else { self.hi.z },
            );
            local_signed_distance(shape, corner) >= 0.0
        });
        outside && local_signed_distance(shape, s.center) <= s.radius
    }

    /// The two halves across `axis`.
    fn halves(&self, axis: DVec3) -> [Self; 2] {
        let middle = 0.5 * (self.lo + self.hi);
        let cut_hi = self.hi * (DVec3::ONE - axis) + middle * axis;
        let cut_lo = self.lo * (DVec3::ONE - axis) + middle * axis;
        [
            Self {
                lo: self.lo,
                hi: cut_hi,
            },
            Self {
                lo: cut_lo,
                hi: self.hi,
            },
        ]
    }
}

/// Cells of the bounding box that may hold surface, each in its circumscribed sphere:
/// the cell reaching farthest beyond the primitive is halved across its longest side
/// while the count allows; the tightest set met on the way is kept. Every surface point
/// lies in a kept cell, hence in its sphere.
fn split_cells(shape: &Shape, lo: DVec3, hi: DVec3, count: usize) -> Vec<Sphere> {
    let reach = |c: &Cell| {
        let s = c.sphere();
        (s.radius + local_signed_distance(shape, s.center)).max(0.0)
    };
    let mut cells = vec![Cell { lo, hi }];
    let worst = |cells: &[Cell]| cells.iter().map(reach).fold(0.0, f64::max);
    let mut best = (worst(&cells), cells.clone());
    while let Some((index, _)) = cells
        .iter()
        .enumerate()
        .map(|(i, c)| (i, reach(c)))
        .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))
    {
        let parent = cells.swap_remove(index);
        let size = parent.hi - parent.lo;
        let axis = if size.x >= size.y && size.x >= size.z {
            DVec3::X
        } else if size.y >= size.z {
            DVec3::Y
        } else {
            DVec3::Z
        };
        let children: Vec<Cell> = parent
            .halves(axis)
            .into_iter()
            .filter(|c| c.may_hold_surface(shape))
            .collect();
        if cells.len() + children.len() > count {
            break;
        }
        cells.extend(children);
        let w = worst(&cells);
        if w < best.0 {
            best = (w, cells.clone());
        }
    }
    best.1.iter().map(Cell::sphere).collect()
}

/// `count` spheres on the axis, evenly from cap centre to cap centre: a sphere of radius
/// `√(r² + (d/2)²)` (`d`: the spacing) covers the capsule between its neighbours' midpoints
/// and the cap around its centre.
fn capsule_spheres(radius: f64, half_length: f64, count: usize) -> Vec<Sphere> {
    if count == 1 || half_length == 0.0 {
        return vec![Sphere::new(DVec3::ZERO, radius + half_length)];
    }
    let spacing = 2.0 * half_length / (count - 1) as f64;
    let r = radius.hypot(0.5 * spacing);
    (0..count)
        .map(|i| Sphere::new(DVec3::new(0.0, 0.0, -half_length + i as f64 * spacing), r))
        .collect()
}

/// The grid of boundary cells that is tightest within `count`: each cell in its
/// circumscribed sphere. The worst cell is a corner cell, whose centre is `s/2` from the
/// nearest face (`s`: the cell's smallest side), so a grid's protrusion is its cells'
/// half-diagonal minus half their smallest side.
fn box_spheres(half: DVec3, count: usize) -> Vec<Sphere> {
    let boundary = |n: [usize; 3]| {
        let inner: usize = n.iter().map(|&k| k.saturating_sub(2)).product();
        n[0] * n[1] * n[2] - inner
    };
    let mut best: Option<(f64, usize, [usize; 3])> = None;
    let limit = count.min(64);
    for nx in 1..=limit {
        for ny in 1..=limit {
            for nz in 1..=limit {
                let n = [nx, ny, nz];
                let cells = boundary(n);
                if cells > count {
                    break;
                }
                let cell = DVec3::new(
                    2.0 * half.x / nx as f64,
                    2.0 * half.y / ny as f64,
                    2.0 * half.z / nz as f64,
                );
                let protrusion = 0.5 * cell.length() - 0.5 * cell.min_element();
                let better = best.is_none_or(|(p, c, _)| {
                    protrusion < p * (1.0 - 1e-12) || (protrusion <= p && cells < c)
                });
                if better {
                    best = Some((protrusion, cells, n));
                }
            }
        }
    }
    let n = best.map_or([1, 1, 1], |(_, _, n)| n);
    let cell = DVec3::new(
        2.0 * half.x / n[0] as f64,
        2.0 * half.y / n[1] as f64,
        2.0 * half.z / n[2] as f64,
    );
    let radius = 0.5 * cell.length();
    let mut spheres = Vec::new();
    for i in 0..n[0] {
        for j in 0..n[1] {
            for k in 0..n[2] {
                let on_boundary = [(i, n[0]), (j, n[1]), (k, n[2])]
                    .iter()
                    .any(|&(a, m)| a == 0 || a + 1 == m);
                if on_boundary {
                    let center =
                        -half + cell * DVec3::new(i as f64 + 0.5, j as f64 + 0.5, k as f64 + 0.5);
                    spheres.push(Sphere::new(center, radius));
                }
            }
        }
    }
    spheres
}

/// Slabs along the axis, each covered by one sphere on the axis (radius `√(r² + (d/2)²)`)
/// or, when tighter, by a grid of `g × g` square cells across (the cells that meet the
/// disc and touch the surface: the side, or a cap slab); the tightest layout within
/// `count`.
fn cylinder_spheres(radius: f64, half_length: f64, count: usize) -> Vec<Sphere> {
    let shape = Shape::Cylinder {
        radius,
        half_length,
    };
    let mut best: Option<(f64, Vec<Sphere>)> = None;
    let mut consider = |spheres: Vec<Sphere>| {
        let protrusion = spheres
            .iter()
            .map(|s| (s.radius + local_signed_distance(&shape, s.center)).max(0.0))
            .fold(0.0, f64::max);
        let better = best.as_ref().is_none_or(|(p, set)| {
            protrusion < p * (1.0 - 1e-12) || (protrusion <= *p && spheres.len() < set.len())
        });
        if better {
            best = Some((protrusion, spheres));
        }
    };
    // Slabs on the axis in the middle, split cells at both ends: the rims need small
    // spheres, the body does not.
    for end in [0.25, 0.5, 1.0].map(|f| f * radius) {
        if 2.0 * end >= 2.0 * half_length {
            continue;
        }
        let middle = half_length - end;
        for per_end in 1..count.saturating_sub(1) / 2 + 1 {
            let slabs = count - 2 * per_end;
            if slabs == 0 {
                break;
            }
            let depth = 2.0 * middle / slabs as f64;
            let mut spheres: Vec<Sphere> = (0..slabs)
                .map(|k| {
                    let z = -middle + (k as f64 + 0.5) * depth;
                    Sphere::new(DVec3::new(0.0, 0.0, z), radius.hypot(0.5 * depth))
                })
                .collect();
            for sign in [-1.0, 1.0] {
                let (a, b) = (sign * middle, sign * half_length);
                spheres.extend(split_cells(
                    &shape,
                    DVec3::new(-radius, -radius, a.min(b)),
                    DVec3::new(radius, radius, a.max(b)),
                    per_end,
                ));
            }
            consider(spheres);
        }
    }
    let grids = (1..=16).take_while(|g| g * g <= count.max(1) * 4);
    for g in grids {
        for slabs in 1..=count {
            let spheres = cylinder_layout(radius, half_length, slabs, g);
            if spheres.len() > count {
                break;
            }
            consider(spheres);
        }
    }
    best.map_or_else(
        || vec![Sphere::new(DVec3::ZERO, radius.hypot(half_length))],
        |(_, s)| s,
    )
}

fn cylinder_layout(radius: f64, half_length: f64, slabs: usize, g: usize) -> Vec<Sphere> {
    let depth = 2.0 * half_length / slabs as f64;
    let mut spheres = Vec::new();
    for k in 0..slabs {
        let z = -half_length + (k as f64 + 0.5) * depth;
        let cap = k == 0 || k + 1 == slabs;
        if g == 1 {
            spheres.push(Sphere::new(
                DVec3::new(0.0, 0.0, z),
                radius.hypot(0.5 * depth),
            ));
            continue;
        }
        let side = 2.0 * radius / g as f64;
        let cell_radius = 0.5 * DVec3::new(side, side, depth).length();
        for i in 0..g {
            for j in 0..g {
                let lo = DVec2::new(-radius + i as f64 * side, -radius + j as f64 * side);
                let hi = lo + DVec2::splat(side);
                // The nearest and farthest points of the square from the axis.
                let nearest = DVec2::ZERO.clamp(lo, hi).length();
                let farthest = lo.abs().max(hi.abs()).length();
                let meets_disc = nearest < radius;
                let touches_side = farthest >= radius;
                if meets_disc && (cap || touches_side) {
                    // The box around the part of the square inside the disc: `x` reaches
                    // as far as the smallest `|y|` of the square allows, and back.
                    let nearest_y = 0.0f64.clamp(lo.y, hi.y);
                    let nearest_x = 0.0f64.clamp(lo.x, hi.x);
                    let reach_x = (radius * radius - nearest_y * nearest_y).max(0.0).sqrt();
                    let reach_y = (radius * radius - nearest_x * nearest_x).max(0.0).sqrt();
                    let clipped_lo = DVec2::new(lo.x.max(-reach_x), lo.y.max(-reach_y));
                    let clipped_hi = DVec2::new(hi.x.min(reach_x), hi.y.min(reach_y));
                    let c = 0.5 * (clipped_lo + clipped_hi);
                    let r = 0.5 * (clipped_hi - clipped_lo).extend(depth).length();
                    spheres.push(Sphere::new(c.extend(z), r.min(cell_radius)));
                }
            }
        }
    }
    spheres
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every surface point lies in some sphere, and the protrusion is what dense points
    /// on the spheres measure (never less).
    #[test]
    fn every_shape_is_covered_and_its_protrusion_is_exact() {
        let shapes = [
            Shape::Box {
                half: DVec3::new(0.3, 0.1, 0.05),
            },
            Shape::Cylinder {
                radius: 0.05,
                half_length: 0.3,
            },
            Shape::Cylinder {
                radius: 0.4,
                half_length: 0.02,
            },
            Shape::Sphere { radius: 0.2 },
            Shape::Capsule {
                radius: 0.04,
                half_length: 0.15,
            },
        ];
        let pose = DAffine3::from_rotation_translation(
            glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1),
            DVec3::new(0.1, -0.2, 0.5),
        );
        for shape in shapes {
            let primitive = Primitive::new(shape, pose);
            for count in [1, 2, 5, 12, 40] {
                let (spheres, protrusion) = primitive.spherize(count);
                assert!(
                    !spheres.is_empty() && spheres.len() <= count.max(1),
                    "{shape:?} {count}"
                );
                for p in primitive.surface_points(3000) {
                    assert!(
                        spheres
                            .iter()
                            .any(|s| s.center.distance(p) <= s.radius * (1.0 + 1e-12)),
                        "{shape:?} {count}: {p} uncovered"
                    );
                }
                // Points on the spheres' surfaces never measure beyond the protrusion.
                let mut measured: f64 = 0.0;
                for s in &spheres {
                    for u in Primitive::new(Shape::Sphere { radius: 1.0 }, DAffine3::IDENTITY)
                        .surface_points(400)
                    {
                        let q = s.center + u * s.radius;
                        measured = measured.max(primitive.signed_distance(q));
                    }
                }
                assert!(
                    measured <= protrusion + 1e-12,
                    "{shape:?} {count}: {measured} > {protrusion}"
                );
                assert!(
                    measured >= 0.9 * protrusion - 1e-9,
                    "{shape:?} {count}: {measured} ≪ {protrusion}"
                );
            }
        }
    }

    /// More spheres never make a primitive's cover looser than fewer, and a tolerance is
    /// met with the fewest. Slabs alone bottom out at `(√2 − 1)·r` on a cylinder (a slab's
    /// sphere must reach the cap's rim); split cells at the ends go below, with enough
    /// spheres for the rims (80 for this rod, 12 times longer than thick).
    #[test]
    fn more_spheres_are_never_looser_and_a_tolerance_is_met() {
        let rod = Primitive::new(
            Shape::Cylinder {
                radius: 0.05,
                half_length: 0.3,
            },
            DAffine3::IDENTITY,
        );
        let mut last = f64::INFINITY;
        for count in (1..=40).chain([80]) {
            let (_, p) = rod.spherize(count);
            assert!(p <= last * (1.0 + 1e-12), "{count}: {p} after {last}");
            last = p;
        }
        assert!(last < 0.8 * (2f64.sqrt() - 1.0) * 0.05, "{last}");
        let (spheres, p) = rod.spherize_within(0.025, 200);
        assert!(
            p <= 0.025 && spheres.len() < 10,
            "{} spheres, {p}",
            spheres.len()
        );
        let block = Primitive::new(
            Shape::Box {
                half: DVec3::new(0.3, 0.1, 0.05),
            },
            DAffine3::IDENTITY,
        );
        let (_, four) = block.spherize(4);
        let (_, forty) = block.spherize(40);
        assert!(forty < 0.5 * four, "{forty} against {four}");
    }
}
