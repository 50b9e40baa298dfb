//! The `needlesim-server identify …` subcommands (argument parsing and file I/O only; the work is
//! in the sibling modules).

use clap::Subcommand;

/// `needlesim-server identify <command>`.
#[derive(Subcommand, Debug)]
pub enum IdentifyCommand {}

/// Runs one identify command.
pub fn run(cmd: IdentifyCommand) -> anyhow::Result<()> {
    match cmd {}
}
