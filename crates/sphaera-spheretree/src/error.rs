//! Errors of sphere-tree construction, evaluation, traversal and file formats.

use crate::export::SphDefect;
use crate::tree::TreeDefect;

/// Why a sphere-tree could not be built, evaluated, traversed, read or written.
///
/// Messages are lowercase without a final period, so they compose into larger messages.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::SphereTreeError;
///
/// let error = SphereTreeError::InvalidParameter {
///     name: "error_fraction",
///     value: 2.0,
///     requirement: "in (0, 1]",
/// };
/// assert_eq!(error.to_string(), "invalid `error_fraction` (2): must be in (0, 1]");
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SphereTreeError {
    /// The mesh is empty or invalid, or a transform is not a similarity.
    #[error(transparent)]
    Mesh(#[from] sphaera_mesh::MeshError),
    /// A spatial query failed: the mesh has no meaningful inside, a parameter of the
    /// sampling or the winding number is out of range.
    #[error(transparent)]
    Query(#[from] sphaera_query::QueryError),
    /// A writer given to an exporter failed.
    #[error("cannot write the sphere-tree: {0}")]
    Write(#[source] std::io::Error),
    /// The medial approximation failed (too few distinct samples, …).
    #[error(transparent)]
    Medial(#[from] sphaera_medial::MedialError),
    /// A numeric parameter is out of its domain (NaN, negative, zero, out of range).
    #[error("invalid `{name}` ({value}): must be {requirement}")]
    InvalidParameter {
        /// The parameter's name as it appears in the API, e.g. `"error_fraction"`.
        name: &'static str,
        /// The value supplied.
        value: f64,
        /// What the value must be, e.g. `"in (0, 1]"`.
        requirement: &'static str,
    },
    /// A sphere has a NaN or infinite centre or radius, or a negative radius.
    #[error("sphere {index} is not a valid sphere (NaN, infinite or negative radius)")]
    InvalidSphere {
        /// Index of the sphere in the input.
        index: usize,
    },
    /// A reducer's candidate lists a point that does not exist.
    #[error("candidate {candidate} covers point {point}, but there are only {points} points")]
    CoverOutOfRange {
        /// Index of the candidate.
        candidate: usize,
        /// The point index it lists.
        point: u32,
        /// The number of points.
        points: usize,
    },
    /// A point given to a reducer is covered by no candidate.
    #[error("point {point} is covered by no candidate")]
    UncoveredPoint {
        /// Index of the point.
        point: usize,
    },
    /// Two links of a collision-sphere list have the same name.
    #[error("two links are named {name:?}")]
    DuplicateLink {
        /// The name.
        name: String,
    },
    /// A `.sph` text could not be read: what is wrong, and on which line.
    #[error("line {line}: {defect}")]
    SphSyntax {
        /// 1-based line number.
        line: usize,
        /// What is wrong there.
        defect: SphDefect,
    },
    /// A `.sph` tree cannot be written (or laid out from a [`SphereTree`](crate::SphereTree)).
    #[error("cannot write the .sph tree: {0}")]
    SphLayout(SphDefect),
    /// A JSON sphere-tree could not be parsed.
    #[error("line {line}: {source}")]
    Json {
        /// 1-based line number of the problem.
        line: usize,
        /// The JSON parser's error.
        #[source]
        source: serde_json::Error,
    },
    /// An evaluation was asked for a set without spheres (its error and coverage would be
    /// meaningless).
    #[error("the sphere set is empty")]
    EmptySphereSet,
    /// A sphere-tree read from a file is inconsistent (levels, parents and children that
    /// do not match, a wrong format tag or version).
    #[error("invalid sphere-tree: {0}")]
    InvalidTree(TreeDefect),
    /// One of the paper's medial methods (or a baseline) was asked to build on a shell, a
    /// surface without inside ([`Surface::shell`](sphaera_query::Surface::shell)): their
    /// spheres sit on the medial axis of a solid. The minimax method (the default) covers
    /// shells.
    #[error(
        "the {method} method needs a solid, and the surface has no inside (a sheet or an \
         open patch): use the minimax method (auto)"
    )]
    NeedsInside {
        /// The method asked for.
        method: &'static str,
    },
    /// A tolerance tree would need more nodes than a tree may have
    /// ([`MAX_TREE_NODES`](crate::MAX_TREE_NODES)) or deeper levels than
    /// [`MAX_MEDIAL_DEPTH`](crate::MAX_MEDIAL_DEPTH) to meet the tolerance: it is far below
    /// the mesh's size (or the surface has parts that no sphere of that error can cover
    /// at that count, such as a sheet asked for a tiny tolerance).
    #[error(
        "cannot meet the tolerance {tolerance}: after {spheres} spheres and {levels} levels \
         the worst leaf still reaches {worst} beyond the surface, and finer levels would \
         exceed the limits (at most {limit} nodes, {depth} levels, 2^24 surface pieces per \
         level); ask for a larger tolerance{}",
        if *limit < crate::MAX_TREE_NODES { " or a larger node budget" } else { "" }
    )]
    ToleranceUnreachable {
        /// The tolerance asked for (in the mesh's units).
        tolerance: f64,
        /// The worst certified leaf error reached.
        worst: f64,
        /// Spheres (nodes) built when the construction stopped.
        spheres: usize,
        /// Levels built.
        levels: usize,
        /// The node limit ([`SphereTreeOptions::max_nodes`](crate::SphereTreeOptions::max_nodes)).
        limit: usize,
        /// The depth limit.
        depth: usize,
    },
}
