//! An animal nobody here has modelled: a procedural quadruped with thin legs, horns and a
//! tail, the "unseen mesh with thin legs and horns" of issue 36's acceptance check.
//!
//! Its parts are closed, outward-oriented primitives from [`sphaera_mesh::shapes`],
//! overlapping where they meet and joined without welding ([`awkward::join`]): the
//! inside test of every method is the winding number, which is 1 inside any part and 2
//! where two overlap, so the union is the solid. The pieces of each part's surface that
//! lie inside another part (a leg's top inside the body) are still triangles of the
//! mesh, a few percent of its area; every coverage measure counts them like the rest.
//!
//! [`awkward::join`]: crate::awkward::join

use sphaera_mesh::glam::{DQuat, DVec3};
use sphaera_mesh::{TriMesh, shapes};

use crate::awkward::{join, mapped};

/// A horned quadruped standing on the plane `z = 0`, facing `+x`, in arbitrary units
/// (2.61 long, 0.8 wide and 1.78 tall; bounding-box diagonal 3.26):
///
/// | part | shape | size | where |
/// |---|---|---|---|
/// | body | ellipsoid | semi-axes 0.9 × 0.4 × 0.35 | centre (0, 0, 1.1) |
/// | head | ellipsoid | semi-axes 0.28 × 0.2 × 0.2 | centre (0.95, 0, 1.3), overlapping the body's front |
/// | legs (4) | cylinders | radius 0.05, length 0.95 | vertical, feet on `z = 0` at x = ±0.55, y = ±0.2; tops 0.07–0.2 inside the body |
/// | horns (2) | cones | base radius 0.04, height 0.5 | bases just inside the head's top at (1.0, ±0.1, 1.38), leaning 0.5 rad out and 0.4 rad back |
/// | tail | cylinder | radius 0.03, length 0.7 | from inside the rump at (−0.8, 0, 1.15), pointing back and down (37° below horizontal) |
///
/// The legs' radius is 1.5 % of the diagonal and the horns taper to a point: the thin
/// parts on which sphere sets either spend many spheres or reach far beyond the surface.
/// 9,888 triangles; closed (every edge in two triangles of its part), outward-oriented,
/// self-intersecting where the parts overlap.
///
/// # Examples
///
/// ```
/// let animal = sphaera_tests::animal::quadruped();
/// let b = animal.bounding_box();
/// assert!(b.min.z.abs() < 1e-12 && (b.max.z - 1.78).abs() < 0.01);
/// assert_eq!(animal.triangle_count(), 9_888);
/// ```
///
/// # Panics
///
/// Never: the parts' parameters are valid.
#[must_use]
pub fn quadruped() -> TriMesh {
    let body = mapped(
        &shapes::ellipsoid(DVec3::new(0.9, 0.4, 0.35), 48).expect("valid ellipsoid"),
        |p| p + DVec3::new(0.0, 0.0, 1.1),
        false,
    );
    let head = mapped(
        &shapes::ellipsoid(DVec3::new(0.28, 0.2, 0.2), 32).expect("valid ellipsoid"),
        |p| p + DVec3::new(0.95, 0.0, 1.3),
        false,
    );
    let mut parts = vec![body, head];
    // Legs: centred at half their length, so the feet stand on z = 0.
    let leg = shapes::cylinder(0.05, 0.95, 12).expect("valid cylinder");
    for (x, y) in [(0.55, 0.2), (0.55, -0.2), (-0.55, 0.2), (-0.55, -0.2)] {
        parts.push(mapped(&leg, |p| p + DVec3::new(x, y, 0.475), false));
    }
    // Horns: base at z = 0 after the shift by half the height, then leaned and placed.
    let horn = shapes::cone(0.04, 0.5, 16).expect("valid cone");
    for side in [-1.0_f64, 1.0] {
        let lean = DQuat::from_rotation_y(-0.4) * DQuat::from_rotation_x(-side * 0.5);
        parts.push(mapped(
            &horn,
            |p| lean * (p + DVec3::new(0.0, 0.0, 0.25)) + DVec3::new(1.0, side * 0.1, 1.38),
            false,
        ));
    }
    // Tail: a cylinder along z, its near end moved to the origin, turned to point back and
    // down, set into the rump.
    let tail = shapes::cylinder(0.03, 0.7, 10).expect("valid cylinder");
    let direction = DVec3::new(-0.8, 0.0, -0.6);
    let turn = DQuat::from_rotation_arc(DVec3::Z, direction);
    parts.push(mapped(
        &tail,
        |p| turn * (p + DVec3::new(0.0, 0.0, 0.35)) + DVec3::new(-0.8, 0.0, 1.15),
        false,
    ));
    join(&parts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_query::Surface;

    /// Closed and outward: the winding number is 1 just outside-in of the body's top and
    /// 0 beyond it; a point inside a leg is inside, a point between the legs is not.
    #[test]
    fn the_quadruped_is_a_closed_outward_solid() {
        let animal = quadruped();
        let surface = Surface::new(&animal).expect("closed parts");
        assert!(surface.has_inside());
        let inside = [
            DVec3::new(0.0, 0.0, 1.1),     // body
            DVec3::new(1.1, 0.0, 1.3),     // head
            DVec3::new(0.55, 0.2, 0.3),    // a front leg
            DVec3::new(-0.55, -0.2, 0.05), // a hind foot
        ];
        let outside = [
            DVec3::new(0.0, 0.0, 0.4),  // under the belly, between the legs
            DVec3::new(0.0, 0.0, 1.5),  // above the back
            DVec3::new(0.55, 0.0, 0.3), // between the front legs
        ];
        for p in inside {
            assert!(surface.is_inside(p), "{p} should be inside");
        }
        for p in outside {
            assert!(!surface.is_inside(p), "{p} should be outside");
        }
        let b = animal.bounding_box();
        let diagonal = (b.max - b.min).length();
        assert!((3.2..3.6).contains(&diagonal), "diagonal {diagonal}");
    }
}
