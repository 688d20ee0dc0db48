//! [`Shape`]: every test shape as a value, with its name, genus and analytic volume.

use std::f64::consts::PI;

use glam::DVec3;

use crate::{MeshError, TriMesh};

/// A procedural test shape with its parameters; [`Shape::build`] makes the mesh.
///
/// Non-exhaustive: more shapes may be added, so a `match` needs a wildcard arm.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes::{DEFAULT_SHAPES, Shape};
///
/// let shape = Shape::Torus { major_radius: 1.0, minor_radius: 0.25 };
/// assert_eq!(shape.name(), "torus");
/// assert_eq!(shape.genus(), 1);
/// let mesh = shape.build(128)?;
/// let relative_error = (signed_volume(&mesh) - shape.volume()) / shape.volume();
/// assert!(relative_error.abs() < 0.01);
///
/// assert_eq!(DEFAULT_SHAPES.iter().filter(|s| s.genus() == 1).count(), 2);
///
/// fn signed_volume(mesh: &sphaera_mesh::TriMesh) -> f64 {
///     mesh.triangle_iter().map(|t| t.a.dot(t.b.cross(t.c)) / 6.0).sum()
/// }
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Shape {
    /// [`super::cube`].
    Cube {
        /// Edge length.
        size: f64,
    },
    /// [`super::sphere`].
    Sphere {
        /// Radius.
        radius: f64,
    },
    /// [`super::ellipsoid`].
    Ellipsoid {
        /// Semi-axes along x, y and z.
        semi_axes: DVec3,
    },
    /// [`super::capsule`].
    Capsule {
        /// Radius of the cylinder and the hemispheres.
        radius: f64,
        /// Length of the cylindrical part.
        length: f64,
    },
    /// [`super::cylinder`].
    Cylinder {
        /// Radius.
        radius: f64,
        /// Height.
        height: f64,
    },
    /// [`super::cone`].
    Cone {
        /// Base radius.
        radius: f64,
        /// Height from base to apex.
        height: f64,
    },
    /// [`super::torus`].
    Torus {
        /// Distance from the axis to the centre of the tube.
        major_radius: f64,
        /// Radius of the tube.
        minor_radius: f64,
    },
    /// [`super::thick_tube`].
    ThickTube {
        /// Radius of the inner wall.
        inner_radius: f64,
        /// Radius of the outer wall.
        outer_radius: f64,
        /// Height.
        height: f64,
    },
    /// [`super::s_tube`].
    STube {
        /// Radius of the tube.
        tube_radius: f64,
        /// Radius of the two half circles of the centre curve.
        bend_radius: f64,
    },
    /// [`super::l_block`].
    LBlock {
        /// Length of each leg of the L.
        leg_length: f64,
        /// Width of the arms.
        arm_width: f64,
        /// Extrusion depth.
        depth: f64,
    },
}

/// One of each shape, with proportions in the spirit of the sphere-tree paper's test set;
/// each fits in a box of diagonal about 2 to 5.
pub const DEFAULT_SHAPES: [Shape; 10] = [
    Shape::Cube { size: 2.0 },
    Shape::Sphere { radius: 1.0 },
    Shape::Ellipsoid {
        semi_axes: DVec3::new(1.5, 1.0, 0.5),
    },
    Shape::Capsule {
        radius: 0.5,
        length: 2.0,
    },
    Shape::Cylinder {
        radius: 1.0,
        height: 2.0,
    },
    Shape::Cone {
        radius: 1.0,
        height: 2.0,
    },
    Shape::Torus {
        major_radius: 1.0,
        minor_radius: 0.3,
    },
    Shape::ThickTube {
        inner_radius: 0.8,
        outer_radius: 1.0,
        height: 2.0,
    },
    Shape::STube {
        tube_radius: 0.3,
        bend_radius: 1.0,
    },
    Shape::LBlock {
        leg_length: 2.0,
        arm_width: 0.8,
        depth: 1.0,
    },
];

impl Shape {
    /// The builder's name in snake case (`"thick_tube"`, `"s_tube"`, ...).
    pub fn name(&self) -> &'static str {
        match self {
            Self::Cube { .. } => "cube",
            Self::Sphere { .. } => "sphere",
            Self::Ellipsoid { .. } => "ellipsoid",
            Self::Capsule { .. } => "capsule",
            Self::Cylinder { .. } => "cylinder",
            Self::Cone { .. } => "cone",
            Self::Torus { .. } => "torus",
            Self::ThickTube { .. } => "thick_tube",
            Self::STube { .. } => "s_tube",
            Self::LBlock { .. } => "l_block",
        }
    }

    /// The smallest `resolution` [`Shape::build`] accepts: 1 for the cube and the L block,
    /// 3 for the round shapes.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes::DEFAULT_SHAPES;
    /// for shape in &DEFAULT_SHAPES {
    ///     assert!(shape.build(shape.min_resolution()).is_ok());
    ///     assert!(shape.build(shape.min_resolution() - 1).is_err());
    /// }
    /// ```
    pub fn min_resolution(&self) -> usize {
        match self {
            Self::Cube { .. } | Self::LBlock { .. } => 1,
            _ => 3,
        }
    }

    /// The genus of the surface: 1 for the torus and the thick tube, 0 otherwise.
    pub fn genus(&self) -> u32 {
        match self {
            Self::Torus { .. } | Self::ThickTube { .. } => 1,
            _ => 0,
        }
    }

    /// The volume of the exact (smooth) solid.
    ///
    /// Meshes of the cube and the L block have exactly this volume. Round shapes are
    /// inscribed polygonal approximations with a smaller volume; the relative error
    /// shrinks as `O(1/m²)` for `m` segments around the coarsest circle (`m = resolution`,
    /// except `resolution · minor_radius / major_radius` for the torus's minor circle). The
    /// tests check it is below `20/m²` for the [`DEFAULT_SHAPES`] at resolutions 8 to 128.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes::Shape;
    /// let cube = Shape::Cube { size: 2.0 };
    /// assert_eq!(cube.volume(), 8.0);
    /// ```
    pub fn volume(&self) -> f64 {
        match *self {
            Self::Cube { size } => size.powi(3),
            Self::Sphere { radius } => 4.0 / 3.0 * PI * radius.powi(3),
            Self::Ellipsoid { semi_axes } => {
                4.0 / 3.0 * PI * semi_axes.x * semi_axes.y * semi_axes.z
            }
            Self::Capsule { radius, length } => {
                PI * radius * radius * length + 4.0 / 3.0 * PI * radius.powi(3)
            }
            Self::Cylinder { radius, height } => PI * radius * radius * height,
            Self::Cone { radius, height } => PI * radius * radius * height / 3.0,
            Self::Torus {
                major_radius,
                minor_radius,
            } => 2.0 * PI * PI * major_radius * minor_radius * minor_radius,
            Self::ThickTube {
                inner_radius,
                outer_radius,
                height,
            } => PI * (outer_radius * outer_radius - inner_radius * inner_radius) * height,
            Self::STube {
                tube_radius,
                bend_radius,
            } => PI * tube_radius * tube_radius * 2.0 * PI * bend_radius,
            Self::LBlock {
                leg_length,
                arm_width,
                depth,
            } => (2.0 * leg_length - arm_width) * arm_width * depth,
        }
    }

    /// The mesh of this shape at `resolution` (see each builder for its meaning).
    ///
    /// # Errors
    ///
    /// As the builder: [`MeshError::InvalidParameter`] for bad sizes or a too small
    /// resolution, [`MeshError::ShapeTooLarge`] beyond [`super::MAX_VERTICES`].
    ///
    /// # Panics
    ///
    /// Never.
    pub fn build(&self, resolution: usize) -> Result<TriMesh, MeshError> {
        match *self {
            Self::Cube { size } => super::cube(size, resolution),
            Self::Sphere { radius } => super::sphere(radius, resolution),
            Self::Ellipsoid { semi_axes } => super::ellipsoid(semi_axes, resolution),
            Self::Capsule { radius, length } => super::capsule(radius, length, resolution),
            Self::Cylinder { radius, height } => super::cylinder(radius, height, resolution),
            Self::Cone { radius, height } => super::cone(radius, height, resolution),
            Self::Torus {
                major_radius,
                minor_radius,
            } => super::torus(major_radius, minor_radius, resolution),
            Self::ThickTube {
                inner_radius,
                outer_radius,
                height,
            } => super::thick_tube(inner_radius, outer_radius, height, resolution),
            Self::STube {
                tube_radius,
                bend_radius,
            } => super::s_tube(tube_radius, bend_radius, resolution),
            Self::LBlock {
                leg_length,
                arm_width,
                depth,
            } => super::l_block(leg_length, arm_width, depth, resolution),
        }
    }
}
