//! One module per subcommand.

mod distance;
mod hal;
mod hal_shapes;
mod hausdorff;
mod info;
mod medial;
mod scene;
mod silhouette;
mod simplify;
mod spheretree;
mod urdf;
mod view;

use anyhow::Result;

use crate::cli::{Cli, Command};

/// Runs the subcommand the user asked for.
pub fn run(cli: &Cli) -> Result<()> {
    if let Some(bytes) = cli.max_file_bytes {
        crate::input::set_max_file_bytes(bytes);
    }
    match &cli.command {
        Command::Info(args) => info::run(args, cli.quiet),
        Command::Simplify(args) => simplify::run(args, cli.quiet),
        Command::Distance(args) => distance::run(args, cli.quiet),
        Command::Hausdorff(args) => hausdorff::run(args, cli.quiet),
        Command::Medial(args) => medial::run(args, cli.quiet),
        Command::Spheretree(args) => spheretree::run(args, cli.quiet),
        Command::Hal(args) => hal::run(args),
        Command::Silhouette(args) => silhouette::run(args, cli.quiet),
        Command::Scene(args) => scene::run(args, cli.quiet),
        Command::Urdf(args) => urdf::run(args, cli.quiet),
        Command::View(args) => view::run(args, cli.quiet),
    }
}
