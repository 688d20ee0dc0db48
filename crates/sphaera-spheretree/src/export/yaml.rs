//! The "collision spheres" YAML list robot motion planners take (cuRobo's robot
//! configurations, `MoveIt`-style sphere lists): per link name, a list of spheres.

use std::fmt::Write as _;
use std::io::Write;

use sphaera_mesh::Sphere;

use crate::select::Cut;
use crate::{SphereTree, SphereTreeError};

/// One link (one rigid part of a robot, or one object) and its collision spheres.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::CollisionLink;
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let link = CollisionLink::new("gripper", vec![Sphere::new(DVec3::ZERO, 0.05)]);
/// assert_eq!(link.name, "gripper");
/// assert_eq!(link.spheres.len(), 1);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CollisionLink {
    /// The link's name (any string: it is written quoted).
    pub name: String,
    /// Its spheres, in the link's frame.
    pub spheres: Vec<Sphere>,
}

impl CollisionLink {
    /// A link of the given spheres.
    #[must_use]
    pub fn new(name: impl Into<String>, spheres: Vec<Sphere>) -> Self {
        Self {
            name: name.into(),
            spheres,
        }
    }

    /// A link of the spheres of `tree`'s level `level` (none beyond the deepest).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_spheretree::export::CollisionLink;
    /// use sphaera_spheretree::{SphereTreeOptions, build, Surface};
    ///
    /// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 8)?;
    /// let options = SphereTreeOptions::default()
    ///     .with_depth(1)
    ///     .with_branch(4)
    ///     .with_samples(400)
    ///     .with_initial_spheres(60)
    ///     .with_min_spheres_per_node(20);
    /// let tree = build(&Surface::new(&mesh)?, &options)?;
    /// let link = CollisionLink::from_level("arm", &tree, 1);
    /// assert_eq!(link.spheres, tree.level_spheres(1));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn from_level(name: impl Into<String>, tree: &SphereTree, level: usize) -> Self {
        Self::new(name, tree.level_spheres(level))
    }

    /// A link of the spheres of a cut of `tree` (see
    /// [`cut_for_tolerance`](crate::select::cut_for_tolerance)).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_spheretree::export::CollisionLink;
    /// use sphaera_spheretree::select::cut_for_tolerance;
    /// use sphaera_spheretree::{SphereTreeOptions, build, Surface};
    ///
    /// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 8)?;
    /// let options = SphereTreeOptions::default()
    ///     .with_depth(1)
    ///     .with_branch(4)
    ///     .with_samples(400)
    ///     .with_initial_spheres(60)
    ///     .with_min_spheres_per_node(20);
    /// let tree = build(&Surface::new(&mesh)?, &options)?;
    /// let cut = cut_for_tolerance(&tree, 0.1);
    /// let link = CollisionLink::from_cut("arm", &tree, &cut);
    /// assert_eq!(link.spheres.len(), cut.nodes.len());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn from_cut(name: impl Into<String>, tree: &SphereTree, cut: &Cut) -> Self {
        Self::new(name, cut.spheres(tree))
    }
}

/// `v` as a YAML float that YAML 1.1 readers (`PyYAML`) and YAML 1.2 readers both read as
/// a float: always a decimal point, and an explicit exponent sign. Exact: Rust's
/// shortest round-trip digits.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::yaml_float;
///
/// assert_eq!(yaml_float(1.0), "1.0");
/// assert_eq!(yaml_float(1e-7), "1.0e-7");
/// assert_eq!(yaml_float(2.5e20), "2.5e+20");
/// ```
#[must_use]
pub fn yaml_float(v: f64) -> String {
    let text = format!("{v:?}");
    let Some((mantissa, exponent)) = text.split_once('e') else {
        return text;
    };
    let dot = if mantissa.contains('.') { "" } else { ".0" };
    let sign = if exponent.starts_with('-') { "" } else { "+" };
    format!("{mantissa}{dot}e{sign}{exponent}")
}

/// The links as a YAML "collision spheres" document:
///
/// ```yaml
/// collision_spheres:
///   "link_name":
///     - center: [0.0, 0.1, -0.25]
///       radius: 0.05
///   "empty_link": []
/// ```
///
/// Link names are written as double-quoted strings (JSON escapes, which YAML reads), in
/// the order given; numbers with enough digits to read back exactly, always with a
/// decimal point (`PyYAML`'s YAML 1.1 would read `1e-7` as a string).
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::{CollisionLink, collision_spheres_yaml};
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let link = CollisionLink::new("tool", vec![Sphere::new(DVec3::new(0.0, 0.5, 1.0), 0.25)]);
/// let yaml = collision_spheres_yaml(&[link])?;
/// assert_eq!(
///     yaml,
///     "collision_spheres:\n  \"tool\":\n    - center: [0.0, 0.5, 1.0]\n      radius: 0.25\n"
/// );
/// # Ok::<(), sphaera_spheretree::SphereTreeError>(())
/// ```
///
/// # Errors
///
/// - [`SphereTreeError::DuplicateLink`] when two links have the same name.
/// - [`SphereTreeError::InvalidSphere`] for a NaN or infinite centre or radius, or a
///   negative radius; `index` counts the spheres of all links in order.
///
/// # Panics
///
/// Never.
pub fn collision_spheres_yaml(links: &[CollisionLink]) -> Result<String, SphereTreeError> {
    let mut names: Vec<&str> = links.iter().map(|l| l.name.as_str()).collect();
    names.sort_unstable();
    if let Some(pair) = names.windows(2).find(|w| w[0] == w[1]) {
        return Err(SphereTreeError::DuplicateLink {
            name: pair[0].to_owned(),
        });
    }
    let mut index = 0;
    for link in links {
        for sphere in &link.spheres {
            if !sphere.is_valid() {
                return Err(SphereTreeError::InvalidSphere { index });
            }
            index += 1;
        }
    }
    if links.is_empty() {
        return Ok("collision_spheres: {}\n".to_owned());
    }
    let mut out = String::from("collision_spheres:\n");
    for link in links {
        // A JSON string is a valid YAML double-quoted scalar; encoding a `&str` cannot
        // fail.
        let name = serde_json::to_string(&link.name).unwrap_or_default();
        if link.spheres.is_empty() {
            let _ = writeln!(out, "  {name}: []");
            continue;
        }
        let _ = writeln!(out, "  {name}:");
        for s in &link.spheres {
            let _ = writeln!(
                out,
                "    - center: [{}, {}, {}]\n      radius: {}",
                yaml_float(s.center.x),
                yaml_float(s.center.y),
                yaml_float(s.center.z),
                yaml_float(s.radius)
            );
        }
    }
    Ok(out)
}

/// Writes [`collision_spheres_yaml`] to any writer (a file: write it atomically with
/// `sphaera_io::write_atomic`).
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::{CollisionLink, write_collision_spheres_yaml};
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let link = CollisionLink::new("base", vec![Sphere::new(DVec3::ZERO, 0.1)]);
/// let mut text = Vec::new();
/// write_collision_spheres_yaml(&mut text, &[link])?;
/// assert!(text.starts_with(b"collision_spheres:"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// As [`collision_spheres_yaml`]; [`SphereTreeError::Write`] when the writer fails.
///
/// # Panics
///
/// Never.
pub fn write_collision_spheres_yaml(
    mut out: impl Write,
    links: &[CollisionLink],
) -> Result<(), SphereTreeError> {
    let text = collision_spheres_yaml(links)?;
    out.write_all(text.as_bytes())
        .map_err(SphereTreeError::Write)
}

#[cfg(test)]
mod tests {
    use super::yaml_float;

    #[test]
    fn floats_always_read_as_floats() {
        assert_eq!(yaml_float(1.0), "1.0");
        assert_eq!(yaml_float(-0.25), "-0.25");
        assert_eq!(yaml_float(1e-7), "1.0e-7");
        assert_eq!(yaml_float(1.5e20), "1.5e+20");
        assert_eq!(yaml_float(0.1), "0.1");
        for v in [1e-7, 1.5e20, 0.1, -3.75e-12, 123_456.789] {
            assert_eq!(yaml_float(v).parse::<f64>().ok(), Some(v));
        }
    }
}
