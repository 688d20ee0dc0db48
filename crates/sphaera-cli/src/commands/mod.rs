//! One module per subcommand.

mod info;

use anyhow::Result;

use crate::cli::{Cli, Command};

/// Runs the subcommand the user asked for.
pub fn run(cli: &Cli) -> Result<()> {
    match &cli.command {
        Command::Info(args) => info::run(args, cli.quiet),
    }
}
