//! How results and failures reach the terminal. Nothing here panics: a closed pipe
//! on standard output ends the program quietly (exit 0), any other write error is one
//! line on standard error and exit 1, and a failure is one line on standard error
//! with nothing on standard output.

use std::io::Write;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

use clap::error::{ContextKind, ContextValue, ErrorKind};

use microslip::answer::ExitStatus;
pub use microslip::answer::{FAILED, REFUSED};
use microslip::messages::printable;

/// A failure to report: a message (one line, or several for a list of findings) and
/// the exit code.
#[derive(Debug)]
pub struct Failure {
    pub message: String,
    pub code: u8,
}

impl Failure {
    /// Input refused (exit 2).
    pub fn refused(message: impl Into<String>) -> Self {
        Failure {
            message: message.into(),
            code: REFUSED,
        }
    }

    /// A run that failed (exit 1).
    pub fn failed(message: impl Into<String>) -> Self {
        Failure {
            message: message.into(),
            code: FAILED,
        }
    }
}

impl Failure {
    /// A library error as the library maps it: its line (message and hint) and exit code;
    /// `digits_asked`: whether `--digits` was given.
    pub fn of(error: &impl ExitStatus, digits_asked: bool) -> Self {
        Failure {
            message: error.line(digits_asked),
            code: error.exit_code(),
        }
    }
}

impl<E: std::fmt::Display> From<E> for Failure {
    fn from(error: E) -> Self {
        Failure::refused(error.to_string())
    }
}

/// Whether warnings and progress are kept off standard error (`--quiet`).
static QUIET: AtomicBool = AtomicBool::new(false);

/// Keeps warnings and progress off standard error from now on (errors still print).
pub fn set_quiet() {
    QUIET.store(true, Ordering::Relaxed);
}

/// Whether `--quiet` was given.
pub fn quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// Writes each line of `message` to standard error, prefixed with the program's name and
/// with control characters escaped; a failure to write there is ignored (there is
/// nowhere left to report it).
fn error_lines(message: &str) {
    let mut stderr = std::io::stderr().lock();
    for line in message.lines() {
        let _ = writeln!(stderr, "microslip: {}", printable(line));
    }
}

/// A warning on standard error (see [`error_lines`]), unless `--quiet` was given.
pub fn warn(message: &str) {
    if !quiet() {
        error_lines(message);
    }
}

/// A result printed on standard error where standard output carries other data (the
/// loop of `simulate --loop -`); kept by `--quiet`, which silences only warnings.
pub fn emit_on_stderr(text: &str) -> ExitCode {
    let mut stderr = std::io::stderr().lock();
    let _ = writeln!(stderr, "{text}");
    ExitCode::SUCCESS
}

/// Prints `text` (and a newline) to standard output and gives the exit code: success,
/// also when the reader has gone (a closed pipe is not an error of ours), or 1 with
/// one line on standard error when the write fails otherwise (a full disk, say).
pub fn emit(text: &str, success: ExitCode) -> ExitCode {
    let mut stdout = std::io::stdout().lock();
    let written = stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.write_all(b"\n"))
        .and_then(|()| stdout.flush());
    match written {
        Ok(()) => success,
        Err(error) if error.kind() == std::io::ErrorKind::BrokenPipe => success,
        Err(error) => {
            error_lines(&format!("writing to standard output: {error}"));
            ExitCode::from(FAILED)
        }
    }
}

/// Reports a failure on standard error and gives its exit code.
pub fn fail(failure: &Failure) -> ExitCode {
    error_lines(&failure.message);
    ExitCode::from(failure.code)
}

/// A command-line parsing error as what to print and where: help and version go to
/// standard output with exit 0; a bare `microslip` prints usage and the subcommands
/// to standard error with exit 2. Every other error is one line on standard error with
/// exit 2: a missing argument, a conflict or a value outside its range names what is
/// wrong; a misspelt command or flag, or a value not among the choices, keeps clap's
/// suggestion ("a similar subcommand exists"), the possible values and the usage, joined
/// into that line, since those are what a user needs to correct it.
pub fn parse_error(error: &clap::Error) -> ExitCode {
    match error.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => emit(error.to_string().trim_end(), ExitCode::SUCCESS),
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = write!(std::io::stderr().lock(), "{}", error.render());
            ExitCode::from(REFUSED)
        }
        _ => {
            let line = parse_error_line(error).unwrap_or_else(|| joined_lines(&error.render().to_string()));
            fail(&Failure::refused(line))
        }
    }
}

/// clap's rendering of an error as one line: its parts joined by "; ", without the
/// "error: " prefix.
fn joined_lines(rendered: &str) -> String {
    let parts: Vec<&str> = rendered
        .lines()
        .map(str::trim)
        .filter(|line| !line.is_empty())
        .map(|line| line.strip_prefix("error: ").unwrap_or(line))
        .collect();
    if parts.is_empty() {
        "invalid arguments".to_string()
    } else {
        parts.join("; ")
    }
}

fn context_string(error: &clap::Error, kind: ContextKind) -> Option<String> {
    match error.get(kind)? {
        ContextValue::String(text) => Some(text.clone()),
        ContextValue::Strings(list) => Some(list.join(", ")),
        _ => None,
    }
}

/// The flag of an argument as clap names it (`--digits <DIGITS>` → `--digits`), and a
/// group of alternatives as such (`<--lambda <LAMBDA>|--nu <NU>>` → `--lambda or --nu`).
fn flag_of(argument: &str) -> String {
    let inner = match argument.strip_prefix('<').and_then(|rest| rest.strip_suffix('>')) {
        Some(group) if group.starts_with('-') => group,
        _ => argument,
    };
    inner
        .split('|')
        .map(|alternative| alternative.split_whitespace().next().unwrap_or(alternative))
        .collect::<Vec<_>>()
        .join(" or ")
}

/// One line for a parsing error whose message is complete on its own; None where
/// clap's suggestion, possible values or usage line should be shown as well.
fn parse_error_line(error: &clap::Error) -> Option<String> {
    match error.kind() {
        ErrorKind::MissingRequiredArgument => {
            let missing: Vec<String> = match error.get(ContextKind::InvalidArg) {
                Some(ContextValue::Strings(list)) => list
                    .iter()
                    .map(|argument| match flag_of(argument).as_str() {
                        "--lambda" => "--lambda (or --nu)".to_string(),
                        "<SHELL>" => format!("<SHELL> (one of {})", shells()),
                        flag => flag.to_string(),
                    })
                    .collect(),
                _ => Vec::new(),
            };
            (!missing.is_empty()).then(|| format!("missing required arguments: {}", missing.join(", ")))
        }
        ErrorKind::ValueValidation | ErrorKind::InvalidValue => {
            let argument = context_string(error, ContextKind::InvalidArg).unwrap_or_default();
            let value = context_string(error, ContextKind::InvalidValue).unwrap_or_default();
            let source = std::error::Error::source(error).map(|s| s.to_string());
            match source {
                Some(reason) if reason.starts_with("must") => {
                    Some(format!("{} {reason} (got '{value}')", flag_of(&argument)))
                }
                Some(reason) => Some(format!("invalid value '{value}' for {}: {reason}", flag_of(&argument))),
                None => None,
            }
        }
        ErrorKind::ArgumentConflict => Some(first_line(error)),
        _ => None,
    }
}

/// The shells `microslip completions` writes for, as typed on the command line.
fn shells() -> String {
    use clap::ValueEnum;
    clap_complete::Shell::value_variants()
        .iter()
        .filter_map(|shell| shell.to_possible_value())
        .map(|value| value.get_name().to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

fn first_line(error: &clap::Error) -> String {
    let rendered = error.render().to_string();
    rendered
        .lines()
        .next()
        .unwrap_or("invalid arguments")
        .trim_start_matches("error: ")
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::{flag_of, joined_lines};

    #[test]
    fn flags_and_groups_of_flags_read_as_typed() {
        assert_eq!(flag_of("--digits <DIGITS>"), "--digits");
        assert_eq!(flag_of("--json"), "--json");
        assert_eq!(flag_of("<--rho <RHO>|--p0 <P0>>"), "--rho or --p0");
        assert_eq!(flag_of("<SHELL>"), "<SHELL>");
    }

    #[test]
    fn a_rendered_error_is_one_line_with_its_tip_and_usage() {
        let rendered = "error: unrecognized subcommand 'tabel'\n\n  tip: a similar subcommand exists: 'table'\n\n\
                        Usage: microslip <COMMAND>\n\nFor more information, try '--help'.\n";
        assert_eq!(
            joined_lines(rendered),
            "unrecognized subcommand 'tabel'; tip: a similar subcommand exists: 'table'; Usage: microslip <COMMAND>; \
             For more information, try '--help'."
        );
    }
}
