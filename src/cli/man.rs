//! `microslip man [COMMAND]`: the manual page (roff) of the program or of one command,
//! on standard output, to be installed as `microslip.1` (or `microslip-COMMAND.1`).

use clap::Args;

use super::report::Failure;

#[derive(Args)]
pub struct ManArgs {
    /// A command whose own page to print (`dissipation`, `batch`, …); without it, the
    /// program's page, which lists every command.
    pub command: Option<String>,
}

/// The page of `program` (the whole command tree) or of the named subcommand.
pub fn run(args: &ManArgs, mut program: clap::Command) -> Result<String, Failure> {
    program.build();
    let page = match &args.command {
        None => program,
        Some(name) => match program.find_subcommand(name) {
            Some(command) => command.clone().version(env!("CARGO_PKG_VERSION")),
            None => {
                let known: Vec<&str> = program
                    .get_subcommands()
                    .map(clap::Command::get_name)
                    .filter(|known| *known != "help")
                    .collect();
                return Err(Failure::refused(format!(
                    "no command '{name}' to print a manual page for; the commands are {}",
                    known.join(", ")
                )));
            }
        },
    };
    let mut roff = Vec::new();
    clap_mangen::Man::new(page)
        .render(&mut roff)
        .map_err(|error| Failure::failed(format!("manual page: {error}")))?;
    let roff = String::from_utf8(roff).map_err(|error| Failure::failed(format!("manual page: {error}")))?;
    Ok(roff.trim_end().to_string())
}
