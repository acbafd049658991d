//! `microslip`: the command line, parsing and printing only; the work is in the library.
//! This file is the command tree and the dispatch; each subcommand's flags and run are
//! in `cli/<command>.rs`, beside the shared helpers (parsers, JSON reports, progress, output).

mod cli;

use std::process::ExitCode;

use clap::{CommandFactory, Parser, Subcommand};

use cli::budget::within;
use cli::case::Jobs;
use cli::parse::radians_warning;
use cli::report::{emit, emit_on_stderr, fail, parse_error, warn};
use cli::{
    accuracy::AccuracyArgs, batch::BatchArgs, completions::CompletionsArgs, dissipation::DissipationArgs,
    figures::FiguresArgs, man::ManArgs, path::PathArgs, reference::ReferenceArgs, series::SeriesArgs,
    simulate::SimulateArgs, small_amplitude::SmallAmplitudeArgs, table::TableArgs, verify::VerifyArgs,
};

#[derive(Parser)]
#[command(
    name = "microslip",
    version,
    about = "Frictional microslip dissipation per cycle in rough elastic contacts",
    arg_required_else_help = true
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// No progress bars and no warnings on standard error (errors still print).
    #[arg(long, short = 'q', global = true)]
    quiet: bool,
}

#[derive(Subcommand)]
enum Command {
    /// The dissipation per cycle W and its four segment contributions.
    Dissipation(Box<DissipationArgs>),
    /// W by brute-force simulation of the contact's loading history (an independent check).
    Simulate(Box<SimulateArgs>),
    /// W, amplitudes, loss factor and harmonics of Q and u for any periodic load path (a file).
    Path(Box<PathArgs>),
    /// Accuracy against cost of every quadrature rule and precision, against 100-digit references.
    Accuracy(AccuracyArgs),
    /// Run the theorem gate: every claim over seeded random draws, in f64 and at 256 bits.
    Verify(VerifyArgs),
    /// The small-amplitude coefficient I(ρ, φ) of W ≈ λ f² P1³ v''(P0) I.
    SmallAmplitude(SmallAmplitudeArgs),
    /// The small-amplitude series: Iₙ(ρ, φ) for n = 0 … N, or a case's partial sums beside W.
    Series(Box<SeriesArgs>),
    /// Check the reference values of a catalogue of cases against a fresh computation
    /// (or, with --write, replace them).
    Reference(ReferenceArgs),
    /// A table of W against the phase φ for a few amplitudes Q1, as text, CSV or JSON; by default
    /// Ŵ = W/(γσλf²) for Persson's compliance v' = γσ/P, P0 = 1, P1 = 0.4 (the paper's Fig. 5).
    Table(Box<TableArgs>),
    /// Regenerate the paper's Figures 4–8 (CSV; SVG, PNG or PDF) and the facts it states (facts.json).
    Figures(FiguresArgs),
    /// W for every load cycle (row) of a CSV file, on all cores, in input order.
    Batch(BatchArgs),
    /// A shell completion script (bash, zsh, fish, elvish, powershell) on standard output.
    Completions(CompletionsArgs),
    /// The manual page (roff) on standard output, e.g. `microslip man > microslip.1`.
    Man(ManArgs),
}

impl Command {
    /// The thread count of a command that runs on all cores.
    fn jobs(&self) -> Option<&Jobs> {
        match self {
            Command::Batch(args) => Some(&args.jobs),
            Command::Verify(args) => Some(&args.jobs),
            Command::Figures(args) => Some(&args.jobs),
            _ => None,
        }
    }

    /// The phase of a command that takes one on its command line.
    fn phase(&self) -> Option<&str> {
        match self {
            Command::Dissipation(args) => Some(&args.case.cycle.phi),
            Command::Simulate(args) => args.cycle.as_ref().map(|cycle| cycle.phi.as_str()),
            Command::SmallAmplitude(args) => Some(&args.phi),
            Command::Series(args) => Some(&args.phi),
            _ => None,
        }
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => return parse_error(&error),
    };
    if cli.quiet {
        cli::report::set_quiet();
    }
    if let Err(failure) = cli::signals::install() {
        return fail(&failure);
    }
    if let Some(Err(failure)) = cli.command.jobs().map(Jobs::install) {
        return fail(&failure);
    }
    // Said once the run has succeeded: a refusal stays one line.
    let phase_warning = cli.command.phase().and_then(|phi| radians_warning("--phi", phi));
    let warn_of_phase = || {
        if let Some(warning) = &phase_warning {
            warn(warning);
        }
    };
    let outcome = match &cli.command {
        Command::Dissipation(args) => within(args.answer.max_seconds, || cli::dissipation::run(args)),
        Command::Verify(args) => match cli::verify::run(args) {
            Ok((text, passed)) => {
                return emit(&text, if passed { ExitCode::SUCCESS } else { ExitCode::from(1) });
            }
            Err(failure) => Err(failure),
        },
        Command::SmallAmplitude(args) => within(args.answer.max_seconds, || cli::small_amplitude::run(args)),
        Command::Series(args) => within(args.answer.max_seconds, || cli::series::run(args)),
        Command::Simulate(args) => match within(args.max_seconds, || cli::simulate::run(args)) {
            // The loop took standard output: the report goes to standard error.
            Ok(text) if args.loop_on_standard_output() => {
                warn_of_phase();
                return emit_on_stderr(&text);
            }
            outcome => outcome,
        },
        Command::Path(args) => match within(args.max_seconds, || cli::path::run(args)) {
            // The loop took standard output: the report goes to standard error.
            Ok(text) if args.loop_on_standard_output() => return emit_on_stderr(&text),
            outcome => outcome,
        },
        Command::Accuracy(args) => cli::accuracy::run(args),
        Command::Reference(args) => cli::reference::run(args),
        Command::Table(args) => cli::table::run(args),
        Command::Figures(args) => cli::figures::run(args),
        Command::Completions(args) => cli::completions::run(args, Cli::command()),
        Command::Man(args) => cli::man::run(args, Cli::command()),
        Command::Batch(args) => match cli::batch::run(args) {
            Ok(0) => return ExitCode::SUCCESS,
            Ok(_) => return ExitCode::from(cli::report::FAILED),
            Err(failure) => Err(failure),
        },
    };
    match outcome {
        Ok(text) => {
            warn_of_phase();
            emit(&text, ExitCode::SUCCESS)
        }
        Err(failure) => fail(&failure),
    }
}
