//! Inside/outside of triangle meshes by the generalized winding number (draft docs).

mod evaluator;
mod ray_parity;
mod solid_angle;
mod solidity;
#[cfg(test)]
mod test_meshes;
#[cfg(test)]
mod tests;
mod tree;

pub use evaluator::{Expansion, WindingEstimate, WindingNumber, WindingOptions};
pub use ray_parity::inside_by_ray_parity;
pub use solid_angle::{triangle_solid_angle, winding_number_brute};
pub use solidity::{INWARD_THRESHOLD, SOLID_THRESHOLD, SolidityReport};
