//! The flags shared by subcommands: a load cycle on a contact, how an answer is asked
//! for (proven digits, a time budget, JSON), and how many threads do the work.

use std::num::NonZeroUsize;
use std::time::Duration;

use clap::Args;

use microslip::case::CaseText;
use microslip::compliance::{spec_help, spec_summary};

use super::parse;
use super::report::Failure;

/// A load cycle P = P0 + P1 cos θ, Q = Q0 + Q1 cos(θ − φ) on a contact.
#[derive(Args)]
pub struct CaseArgs {
    #[command(flatten)]
    pub cycle: CycleArgs,
    #[command(flatten)]
    pub contact: ContactArgs,
}

/// A load cycle P = P0 + P1 cos θ, Q = Q0 + Q1 cos(θ − φ).
#[derive(Args)]
pub struct CycleArgs {
    /// Mean normal load P0 (> 0).
    #[arg(long, allow_hyphen_values = true)]
    pub p0: String,
    /// Normal load amplitude P1 (0 ≤ P1 < P0).
    #[arg(long, allow_hyphen_values = true)]
    pub p1: String,
    /// Mean tangential load Q0.
    #[arg(long, allow_hyphen_values = true, default_value = "0")]
    pub q0: String,
    /// Tangential load amplitude Q1 (≥ 0).
    #[arg(long, allow_hyphen_values = true)]
    pub q1: String,
    /// Phase lag φ of Q behind P: radians (`1.2`), a multiple of π (`pi/2`, `3pi/4`, `0.4pi`, `π/2`),
    /// plus or minus radians (`pi-1e-6`), or degrees (`72deg`, `72°`); read exactly
    #[arg(long, allow_hyphen_values = true)]
    pub phi: String,
}

/// The contact a load acts on: friction, compliance ratio and compliance.
#[derive(Args)]
pub struct ContactArgs {
    /// Coulomb friction coefficient f (> 0).
    #[arg(long, allow_hyphen_values = true)]
    pub friction: String,
    /// Tangential/normal compliance ratio λ, in [1, 2].
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "nu",
        required_unless_present = "nu"
    )]
    pub lambda: Option<String>,
    /// Poisson's ratio ν in [0, 2/3], giving λ = (2 − ν)/(2(1 − ν)) in [1, 2].
    #[arg(long, allow_hyphen_values = true)]
    pub nu: Option<String>,
    #[arg(long, allow_hyphen_values = true, help = spec_summary(), long_help = spec_help())]
    pub compliance: String,
}

impl CaseArgs {
    pub fn text(&self) -> CaseText {
        self.cycle.text(&self.contact)
    }
}

impl CycleArgs {
    /// The cycle on `contact`, as written.
    pub fn text(&self, contact: &ContactArgs) -> CaseText {
        CaseText {
            p0: self.p0.clone(),
            p1: self.p1.clone(),
            q0: self.q0.clone(),
            q1: self.q1.clone(),
            phi: self.phi.clone(),
            friction: contact.friction.clone(),
            lambda: contact.lambda.clone(),
            nu: contact.nu.clone(),
            compliance: contact.compliance.clone(),
        }
    }
}

/// How an answer is asked for: proven digits or f64, within a time budget, as text or JSON.
/// (A command describes its `--digits` with `mut_arg`.)
#[derive(Args)]
pub struct Answer {
    /// Significant digits to compute and prove by a rigorous enclosure (1–1000).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::digits)]
    pub digits: Option<u32>,
    /// Time budget, in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "60")]
    pub max_seconds: Duration,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// How many worker threads a command that runs on all cores (batch, verify, figures) uses.
#[derive(Args)]
pub struct Jobs {
    /// Worker threads (1–1024); default: RAYON_NUM_THREADS if set, else one per core.
    #[arg(long, short = 'j', allow_hyphen_values = true, value_parser = parse::jobs)]
    pub jobs: Option<NonZeroUsize>,
}

impl Jobs {
    /// Sizes the one pool of worker threads (rayon's global pool) that the command's
    /// parallel work runs on; call once, before any of that work starts.
    pub fn install(&self) -> Result<(), Failure> {
        let Some(jobs) = self.jobs else {
            return Ok(());
        };
        rayon::ThreadPoolBuilder::new()
            .num_threads(jobs.get())
            .build_global()
            .map_err(|error| Failure::failed(format!("cannot start {jobs} worker threads: {error}")))
    }
}
