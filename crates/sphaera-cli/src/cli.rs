//! The command line, declared with clap.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

/// Hierarchical sphere-based approximation of triangle meshes.
///
/// Every MESH argument may be omitted: the embedded low-resolution Stanford bunny
/// (public domain, 3,674 triangles) is used instead. Supported formats: OBJ, PLY (ASCII
/// and binary), STL (ASCII and binary), OFF.
#[derive(Debug, Parser)]
#[command(name = "sphaera", version)]
pub struct Cli {
    /// Hide progress bars.
    #[arg(long, short, global = true)]
    pub quiet: bool,

    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands: one per capability.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Describe a mesh: counts, bounding box, topology (closed, manifold, genus,
    /// components, boundary loops), degenerate and duplicate triangles.
    Info(InfoArgs),
}

/// Arguments of `sphaera info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// The mesh file (OBJ, PLY, STL, OFF); the embedded bunny when omitted.
    pub mesh: Option<PathBuf>,

    #[command(flatten)]
    pub output: OutputArgs,
}

/// How a result is printed; shared by every subcommand.
#[derive(Debug, Args)]
pub struct OutputArgs {
    /// Print the result as one JSON document on stdout instead of text.
    #[arg(long)]
    pub json: bool,
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    use super::*;

    #[test]
    fn command_line_is_well_formed() {
        Cli::command().debug_assert();
    }
}
