//! `microslip completions <SHELL>`: a completion script for the shell, on standard output.

use clap::Args;
use clap_complete::Shell;

use super::report::Failure;

#[derive(Args)]
pub struct CompletionsArgs {
    /// The shell to complete for.
    #[arg(value_enum)]
    pub shell: Shell,
}

/// The completion script of `command` (the whole command tree) for the chosen shell.
pub fn run(args: &CompletionsArgs, mut command: clap::Command) -> Result<String, Failure> {
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut command, "microslip", &mut script);
    let script = String::from_utf8(script).map_err(|error| Failure::failed(format!("completion script: {error}")))?;
    Ok(script.trim_end().to_string())
}
