//! The classic `.sph` sphere-tree text format of the original sphere-tree construction
//! toolkit (Bradshaw and O'Sullivan), so sphere-trees built by other tools can be
//! evaluated beside ours, and ours read by them.
//!
//! # The format
//!
//! ```text
//! 3 2                  ← levels (including the root) and branching factor B
//! 0 0 0 2 1            ← node 0, the root: x y z radius importance
//! -1 0 0 1 1           ← nodes 1 … B: the root's children
//! 1 0 0 1 1
//! -1.5 0 0 0.5 1       ← nodes B+1 … B+B²: the grandchildren
//! -0.5 0 0 0.5 1
//! 0 0 0 -1 1           ← an unused slot (radius ≤ 0)
//! 0 0 0 -1 1
//! ```
//!
//! - Line 1: the number of **levels including the root** (a root alone is 1 level) and
//!   the branching factor `B`.
//! - Then the nodes of a **complete** `B`-ary tree stored as a flat array, level by level:
//!   `1 + B + B² + … + B^(levels−1)` lines. The children of node `N` are nodes
//!   `N·B + 1 … N·B + B`, its parent `(N − 1) / B`.
//! - A node line is `x y z r importance`. A radius `r ≤ 0` marks an unused slot (the
//!   toolkit writes `-1`; it also treats `r = 0` as unused). The importance is 1 for
//!   every sphere the toolkit writes. Older tools write the centres relative to the
//!   mesh's bounding-box centre: [`read_sph`] adds an offset to every centre, and
//!   [`write_sph`] subtracts one.
//!
//! The reader also accepts what the toolkit itself accepts: blank lines anywhere, node
//! lines of 4 fields (`x y z r`, importance 1), and the toolkit's 10-field lines, whose
//! last five fields (an auxiliary sphere and its error decrease, written by some of its
//! optimisers) are ignored. Trailing lines beyond the complete tree are accepted only when
//! they are unused slots (the toolkit allocates `1 + B` nodes even for a single level).
//! Anything else is a [`SphereTreeError::SphSyntax`] naming the line and the
//! [`SphDefect`].

use std::fmt::Write as _;
use std::ops::Range;

use glam::DVec3;

use crate::{Sphere, SphereTreeError};

/// The most slots a `.sph` file made from a tree may have (a complete tree of depth 4
/// and branching factor 16 has 69,905).
const MAX_SLOTS: usize = 1 << 24;

/// Importance written for an unused slot, as the original toolkit does.
const UNUSED_IMPORTANCE: f64 = 1.0;

/// What is wrong with a `.sph` text ([`SphereTreeError::SphSyntax`], with its line) or
/// with a tree to be written in the format ([`SphereTreeError::SphLayout`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SphDefect {
    /// The text holds no header.
    #[error("empty file: expected a header \"levels branch\"")]
    EmptyFile,
    /// The header is not two fields.
    #[error("expected a header of two integers \"levels branch\", found {fields} fields")]
    HeaderFields {
        /// The number of fields found.
        fields: usize,
    },
    /// A header field is not a non-negative integer.
    #[error("the {name} is not a non-negative integer: {text:?}")]
    HeaderNotInteger {
        /// `"number of levels"` or `"branching factor"`.
        name: &'static str,
        /// The field as written.
        text: String,
    },
    /// The tree has no level.
    #[error("a tree has at least one level (the root)")]
    NoLevel,
    /// The branching factor is 0.
    #[error("the branching factor must be at least 1")]
    NoBranch,
    /// The complete tree of the header is larger than the text could hold (reading) or
    /// than memory can address (writing).
    #[error(
        "a complete tree of {levels} levels and branching factor {branch} has more nodes than {limit}"
    )]
    TooLarge {
        /// Levels, the root included.
        levels: usize,
        /// Branching factor.
        branch: usize,
        /// What the node count exceeds: `"the file has characters"`, `"the format's 2^24
        /// slots (write JSON instead)"`.
        limit: &'static str,
    },
    /// A node field is not a number.
    #[error("field {field} is not a number: {text:?}")]
    NotANumber {
        /// 1-based field number.
        field: usize,
        /// The field as written.
        text: String,
    },
    /// A node field is NaN or infinite.
    #[error("field {field} is not finite: {text:?}")]
    NotFinite {
        /// 1-based field number.
        field: usize,
        /// The field as written.
        text: String,
    },
    /// A node line has the wrong number of fields.
    #[error("expected 4, 5 or 10 fields (x y z r [importance [auxiliary sphere]]), found {fields}")]
    NodeFields {
        /// The number of fields found.
        fields: usize,
    },
    /// A centre overflows once the offset is added.
    #[error("the center is not finite once the offset is added")]
    CentreNotFinite,
    /// A used sphere follows the complete tree.
    #[error("a used sphere beyond the {nodes} nodes of the complete tree")]
    BeyondTree {
        /// The complete tree's node count.
        nodes: usize,
    },
    /// The text ends before the complete tree does.
    #[error(
        "the file ends after {found} of the {nodes} nodes of a complete tree of {levels} levels and branching factor {branch}"
    )]
    Truncated {
        /// Node lines found.
        found: usize,
        /// The complete tree's node count.
        nodes: usize,
        /// Levels, the root included.
        levels: usize,
        /// Branching factor.
        branch: usize,
    },
    /// A tree to be written does not have the complete tree's node count.
    #[error(
        "a complete tree of {levels} levels and branching factor {branch} has {} nodes, got {found}",
        nodes.map_or_else(|| "too many".to_owned(), |n| n.to_string())
    )]
    NodeCount {
        /// Levels, the root included.
        levels: usize,
        /// Branching factor.
        branch: usize,
        /// The complete tree's node count (`None` when it overflows).
        nodes: Option<usize>,
        /// The node count given.
        found: usize,
    },
    /// A sphere to be written has a NaN or infinite centre or radius.
    #[error("node {node} (level {level}) has a non-finite center or radius")]
    NonFiniteSphere {
        /// The node's slot.
        node: usize,
        /// Its level (the root is level 0).
        level: usize,
    },
    /// A sphere to be written has a radius that is not positive, which the format reads
    /// as an unused slot.
    #[error(
        "node {node} (level {level}) has radius {radius}, which the .sph format reads as an unused slot"
    )]
    NonPositiveRadius {
        /// The node's slot.
        node: usize,
        /// Its level (the root is level 0).
        level: usize,
        /// The radius given.
        radius: f64,
    },
    /// A node to be written has a NaN or infinite importance.
    #[error("node {node} has a non-finite importance {importance}")]
    NonFiniteImportance {
        /// The node's slot.
        node: usize,
        /// The importance given.
        importance: f64,
    },
}

/// A sphere-tree in `.sph` layout: a complete `branch`-ary tree of `levels` levels as a
/// flat array of optional nodes (a sphere and its importance).
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::SphFile;
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let root = Sphere::new(DVec3::ZERO, 2.0);
/// let left = Sphere::new(DVec3::new(-1.0, 0.0, 0.0), 1.0);
/// let tree = SphFile {
///     levels: 2,
///     branch: 3,
///     nodes: vec![Some((root, 1.0)), Some((left, 1.0)), None, None],
/// };
/// assert_eq!(SphFile::node_count(2, 3), Some(4));
/// assert_eq!(tree.children(0), 1..4);
/// assert_eq!(tree.level(0), vec![root]);
/// assert_eq!(tree.level(1), vec![left]);
/// assert!(tree.level(2).is_empty());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SphFile {
    /// The number of levels, including the root (at least 1).
    pub levels: usize,
    /// The branching factor (at least 1).
    pub branch: usize,
    /// The nodes, level by level: `None` for an unused slot, else the sphere and its
    /// importance. A complete tree has [`SphFile::node_count`] nodes.
    pub nodes: Vec<Option<(Sphere, f64)>>,
}

impl SphFile {
    /// The `.sph` layout of `tree`: node `N`'s `k`-th child goes to slot `N·B + 1 + k`,
    /// unused slots stay `None`, every importance is 1.
    ///
    /// # Errors
    ///
    /// [`SphereTreeError::SphLayout`] ([`SphDefect::TooLarge`]) when the complete tree of
    /// the tree's depth and branching factor has more slots than memory can address.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_spheretree::{SphereTreeOptions, Surface, build, export::SphFile};
    ///
    /// let mesh = shapes::capsule(0.5, 2.0, 8)?;
    /// let options = SphereTreeOptions::default()
    ///     .with_depth(1)
    ///     .with_branch(4)
    ///     .with_samples(800)
    ///     .with_initial_spheres(60)
    ///     .with_min_spheres_per_node(20);
    /// let tree = build(&Surface::new(&mesh)?, &options)?;
    /// let file = SphFile::from_tree(&tree)?;
    /// assert_eq!((file.levels, file.branch, file.nodes.len()), (2, 4, 5));
    /// assert_eq!(file.level(1).len(), tree.level(1).len());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_tree(tree: &crate::SphereTree) -> Result<Self, SphereTreeError> {
        let levels = tree.level_count().max(1);
        let branch = tree.branch().max(1);
        let count = Self::node_count(levels, branch)
            .filter(|&n| n <= MAX_SLOTS)
            .ok_or(SphereTreeError::SphLayout(SphDefect::TooLarge {
                levels,
                branch,
                limit: "the format's 2^24 slots (write JSON instead)",
            }))?;
        let mut nodes = vec![None; count];
        // Flat slot of every tree node, the root first (parents precede children).
        let mut slot = vec![0_usize; tree.nodes().len()];
        for (i, node) in tree.nodes().iter().enumerate() {
            let s = slot[i];
            if let Some(entry) = nodes.get_mut(s) {
                *entry = Some((node.sphere, 1.0));
            }
            for (k, child) in (node.children.start..node.children.end).enumerate() {
                if let Some(c) = slot.get_mut(child as usize) {
                    *c = s * branch + 1 + k;
                }
            }
        }
        Ok(Self {
            levels,
            branch,
            nodes,
        })
    }

    /// The number of nodes of a complete `branch`-ary tree of `levels` levels,
    /// `1 + B + … + B^(levels−1)`; `None` when it overflows `usize`.
    #[must_use]
    pub fn node_count(levels: usize, branch: usize) -> Option<usize> {
        let mut total = 0_usize;
        let mut width = 1_usize;
        for level in 0..levels {
            total = total.checked_add(width)?;
            if level + 1 < levels {
                width = width.checked_mul(branch)?;
            }
        }
        Some(total)
    }

    /// The indices of the nodes of `level` (0 is the root), clamped to the stored nodes:
    /// empty beyond the last level.
    #[must_use]
    pub fn level_range(&self, level: usize) -> Range<usize> {
        if level >= self.levels {
            return 0..0;
        }
        let start = Self::node_count(level, self.branch).unwrap_or(usize::MAX);
        let end = Self::node_count(level + 1, self.branch).unwrap_or(usize::MAX);
        start.min(self.nodes.len())..end.min(self.nodes.len())
    }

    /// The level of slot `node` (0 is the root; `levels` beyond the last level).
    fn level_of(&self, node: usize) -> usize {
        (0..self.levels)
            .find(|&level| self.level_range(level).end > node)
            .unwrap_or(self.levels)
    }

    /// The used spheres of `level` (0 is the root), in slot order.
    #[must_use]
    pub fn level(&self, level: usize) -> Vec<Sphere> {
        self.nodes[self.level_range(level)]
            .iter()
            .filter_map(|n| n.map(|(s, _)| s))
            .collect()
    }

    /// The slots of the children of `node`: `node·B + 1 … node·B + B`, clamped to the
    /// stored nodes.
    #[must_use]
    pub fn children(&self, node: usize) -> Range<usize> {
        let first = node
            .saturating_mul(self.branch)
            .saturating_add(1)
            .min(self.nodes.len());
        first..first.saturating_add(self.branch).min(self.nodes.len())
    }
}

/// Reads a `.sph` file, adding `offset` to every centre (pass the mesh's bounding-box
/// centre for files written relative to it, else [`DVec3::ZERO`]).
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::read_sph;
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let text = "2 2\n0 0 0 2 1\n-1 0 0 1 1\n0 0 0 -1 1\n";
/// let tree = read_sph(text, DVec3::new(10.0, 0.0, 0.0))?;
/// assert_eq!((tree.levels, tree.branch), (2, 2));
/// assert_eq!(tree.level(1), vec![Sphere::new(DVec3::new(9.0, 0.0, 0.0), 1.0)]);
/// assert_eq!(tree.nodes[2], None);
///
/// let error = read_sph("2 2\n0 0 0 2 1\n-1 0 zero 1 1\n0 0 0 -1 1\n", DVec3::ZERO).unwrap_err();
/// assert_eq!(error.to_string(), "line 3: field 3 is not a number: \"zero\"");
/// # Ok::<(), sphaera_spheretree::SphereTreeError>(())
/// ```
///
/// # Errors
///
/// [`SphereTreeError::SphSyntax`] with the 1-based line number and the [`SphDefect`]: a header that is not two
/// integers, zero levels or branching factor, a tree too large for memory, a node line
/// without 4, 5 or 10 numeric fields, a NaN or infinite field, fewer node lines than the
/// complete tree has, or used spheres beyond it.
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// Linear in the text's length.
pub fn read_sph(text: &str, offset: DVec3) -> Result<SphFile, SphereTreeError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty());
    let Some((header_line, header)) = lines.next() else {
        return Err(syntax(1, SphDefect::EmptyFile));
    };
    let (levels, branch) = parse_header(header_line, header)?;
    let expected = SphFile::node_count(levels, branch)
        .filter(|&n| n <= text.len())
        .ok_or(syntax(
            header_line,
            SphDefect::TooLarge {
                levels,
                branch,
                limit: "the file has characters",
            },
        ))?;
    let mut nodes = Vec::with_capacity(expected);
    let mut last_line = header_line;
    for (number, line) in lines {
        last_line = number;
        let node = parse_node(number, line, offset)?;
        if nodes.len() < expected {
            nodes.push(node);
        } else if node.is_some() {
            return Err(syntax(number, SphDefect::BeyondTree { nodes: expected }));
        }
    }
    if nodes.len() < expected {
        return Err(syntax(
            last_line + 1,
            SphDefect::Truncated {
                found: nodes.len(),
                nodes: expected,
                levels,
                branch,
            },
        ));
    }
    Ok(SphFile {
        levels,
        branch,
        nodes,
    })
}

/// Writes `file` in `.sph` format, subtracting `offset` from every centre. Numbers are
/// written with Rust's shortest exact representation (no exponent), so
/// `read_sph(&write_sph(f, DVec3::ZERO)?, DVec3::ZERO)` gives `f` back bit for bit.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::{SphFile, read_sph, write_sph};
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let tree = SphFile {
///     levels: 2,
///     branch: 2,
///     nodes: vec![
///         Some((Sphere::new(DVec3::ZERO, 2.0), 1.0)),
///         Some((Sphere::new(DVec3::new(-1.0, 0.0, 0.5), 1.0), 1.0)),
///         None,
///     ],
/// };
/// let text = write_sph(&tree, DVec3::ZERO)?;
/// assert_eq!(text, "2 2\n0 0 0 2 1\n-1 0 0.5 1 1\n0 0 0 -1 1\n");
/// assert_eq!(read_sph(&text, DVec3::ZERO)?, tree);
/// # Ok::<(), sphaera_spheretree::SphereTreeError>(())
/// ```
///
/// # Errors
///
/// [`SphereTreeError::SphLayout`] for zero levels or branching factor, a node count other
/// than [`SphFile::node_count`], a NaN or infinite importance, a sphere with a
/// non-finite centre or radius, or a radius that is not positive (the format reads it as
/// an unused slot), naming the node's slot and level.
///
/// # Panics
///
/// Never.
pub fn write_sph(file: &SphFile, offset: DVec3) -> Result<String, SphereTreeError> {
    if file.levels == 0 {
        return Err(SphereTreeError::SphLayout(SphDefect::NoLevel));
    }
    if file.branch == 0 {
        return Err(SphereTreeError::SphLayout(SphDefect::NoBranch));
    }
    let expected = SphFile::node_count(file.levels, file.branch);
    if expected != Some(file.nodes.len()) {
        return Err(SphereTreeError::SphLayout(SphDefect::NodeCount {
            levels: file.levels,
            branch: file.branch,
            nodes: expected,
            found: file.nodes.len(),
        }));
    }
    let mut text = String::with_capacity(32 * file.nodes.len() + 16);
    // Writing to a `String` cannot fail.
    let _ = writeln!(text, "{} {}", file.levels, file.branch);
    for (index, node) in file.nodes.iter().enumerate() {
        match node {
            Some((sphere, importance)) => {
                let center = sphere.center - offset;
                let level = file.level_of(index);
                if !(center.is_finite() && sphere.radius.is_finite()) {
                    return Err(SphereTreeError::SphLayout(SphDefect::NonFiniteSphere {
                        node: index,
                        level,
                    }));
                }
                if sphere.radius <= 0.0 {
                    return Err(SphereTreeError::SphLayout(SphDefect::NonPositiveRadius {
                        node: index,
                        level,
                        radius: sphere.radius,
                    }));
                }
                if !importance.is_finite() {
                    return Err(SphereTreeError::SphLayout(SphDefect::NonFiniteImportance {
                        node: index,
                        importance: *importance,
                    }));
                }
                let _ = writeln!(
                    text,
                    "{} {} {} {} {}",
                    center.x, center.y, center.z, sphere.radius, importance
                );
            }
            None => {
                let _ = writeln!(text, "0 0 0 -1 {UNUSED_IMPORTANCE}");
            }
        }
    }
    Ok(text)
}

/// The header's levels and branching factor.
fn parse_header(number: usize, line: &str) -> Result<(usize, usize), SphereTreeError> {
    let fields: Vec<&str> = line.split_whitespace().collect();
    let [levels, branch] = fields.as_slice() else {
        return Err(syntax(
            number,
            SphDefect::HeaderFields {
                fields: fields.len(),
            },
        ));
    };
    let integer = |name: &'static str, field: &str| {
        field.parse::<usize>().map_err(|_| {
            syntax(
                number,
                SphDefect::HeaderNotInteger {
                    name,
                    text: field.to_owned(),
                },
            )
        })
    };
    let levels = integer("number of levels", levels)?;
    let branch = integer("branching factor", branch)?;
    if levels == 0 {
        return Err(syntax(number, SphDefect::NoLevel));
    }
    if branch == 0 {
        return Err(syntax(number, SphDefect::NoBranch));
    }
    Ok((levels, branch))
}

/// One node line: `None` for an unused slot (radius ≤ 0).
fn parse_node(
    number: usize,
    line: &str,
    offset: DVec3,
) -> Result<Option<(Sphere, f64)>, SphereTreeError> {
    let mut values = [0.0_f64; 10];
    let mut count = 0;
    for (i, field) in line.split_whitespace().enumerate() {
        let value: f64 = field.parse().map_err(|_| {
            syntax(
                number,
                SphDefect::NotANumber {
                    field: i + 1,
                    text: field.to_owned(),
                },
            )
        })?;
        if !value.is_finite() {
            return Err(syntax(
                number,
                SphDefect::NotFinite {
                    field: i + 1,
                    text: field.to_owned(),
                },
            ));
        }
        if let Some(slot) = values.get_mut(i) {
            *slot = value;
        }
        count = i + 1;
    }
    if !matches!(count, 4 | 5 | 10) {
        return Err(syntax(number, SphDefect::NodeFields { fields: count }));
    }
    let [x, y, z, radius, importance, ..] = values;
    if radius <= 0.0 {
        return Ok(None);
    }
    let importance = if count == 4 { 1.0 } else { importance };
    let center = DVec3::new(x, y, z) + offset;
    if !center.is_finite() {
        return Err(syntax(number, SphDefect::CentreNotFinite));
    }
    Ok(Some((Sphere::new(center, radius), importance)))
}

/// A [`SphereTreeError::SphSyntax`] at `line`.
fn syntax(line: usize, defect: SphDefect) -> SphereTreeError {
    SphereTreeError::SphSyntax { line, defect }
}
