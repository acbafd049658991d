//! microslip: frictional (microslip) energy dissipation per cycle in elastic
//! contacts of rough surfaces under oscillating normal and tangential loads.
//!
//! A contact with normal compliance v(P) carries a normal load P = P0 + P1 cos θ and a
//! tangential load Q = Q0 + Q1 cos(θ − φ); with friction coefficient f and
//! tangential/normal compliance ratio λ, the energy W dissipated per cycle is a
//! functional of v'(P) over the loads the cycle reaches.
//!
//! # Library use
//!
//! ```
#![doc = include_str!("../examples/library_use.rs")]
//! ```
//!
//! The surface, top-down:
//! - [`cycle`]: the load cycle ([`cycle::LoadCycle`]) and its validated form
//!   ([`cycle::ValidCycle`], which only a cycle the theory covers becomes);
//! - [`compliance`]: the contact's normal compliance v(P) — the families
//!   ([`compliance::PowerLaw`], [`compliance::Persson`], [`compliance::Hertz`], …), their
//!   combinators, measured tables, and the SPEC text form ([`compliance::parse_spec`]);
//! - [`dissipation`]: W over the four segments ([`dissipation::dissipation`]) and the
//!   closed forms ([`dissipation::in_phase`], [`dissipation::constant_normal_load`],
//!   [`dissipation::MindlinDeresiewicz`]);
//! - [`real`]: the number type every computation is generic over (`f64`, `rug::Float`
//!   at any precision);
//! - [`reference`](mod@reference) (verified digits by two precisions) and `certified` (feature
//!   `certified`: proven digits from Arb ball arithmetic);
//! - [`answer`]: a printed value with its digits, enclosure and provenance;
//! - [`exact`]: the small-amplitude series and its exact coefficients;
//! - [`case`]: a case built from numbers or decimals ([`case::CaseText::builder`]) or read
//!   once from its text ([`case::CaseText`] → [`case::CaseSpec`]), computed at any precision;
//! - [`dissipation_answer`]: the one policy that picks how W is computed and vouched for
//!   ([`dissipation_answer::dissipation_of`]);
//! - [`ladder`]: the one loop over working precisions that every proven digit climbs;
//! - [`simulate`]: the independent check by a time-stepped simulation, and
//!   [`simulation_answer`] its W as an answer;
//! - [`verify`]: the theorem gate ([`verify::run`]).
//!
//! Beside them: [`batch`] (many cases from a CSV, on all cores), [`path`] (any periodic
//! load path), [`aft`] (the harmonic-balance friction element), [`interval`] (f64
//! intervals as a [`real::Real`]), `ball` (feature `certified`: Arb balls), [`doubts`]
//! (how those number types report a comparison they cannot decide), [`quad`],
//! [`phase`], [`verified`] (agreement of two precisions and the printing rule),
//! [`files`] (atomic output), [`messages`], and with feature `cli` `accuracy` and
//! `catalogue`. Only `figures` and `plot` (feature `cli`: the paper's figures and their
//! pictures) are hidden from this documentation: they serve the command line and its
//! tests, and change without notice.
//!
//! The default feature `cli` adds the tools around the library: the plots, the
//! accuracy benchmark and the catalogue of reference values. Built without it (no
//! default features) the library needs no argument parser, plotting, progress display
//! or JSON text.
#![warn(missing_docs)]

pub mod admissibility;
pub mod aft;
pub mod answer;
pub mod boundaries;
pub mod case;
#[cfg(feature = "certified")]
pub mod certified;
pub mod compliance;
pub mod cycle;
mod decimal;
pub mod dissipation;
pub mod dissipation_answer;
pub mod doubts;
pub mod exact;
pub mod ladder;
pub mod path;
pub mod real;
pub mod reference;
mod rounding;
pub mod simulate;
pub mod simulation_answer;
pub mod verify;

#[cfg(feature = "cli")]
pub mod accuracy;
#[cfg(feature = "certified")]
mod arb;
#[cfg(feature = "certified")]
pub use arb::ball;
#[cfg(feature = "certified")]
use arb::gauss as ball_gauss;
pub mod batch;
#[cfg(feature = "cli")]
pub mod catalogue;
#[cfg(feature = "cli")]
#[doc(hidden)]
pub mod figures;
pub mod files;
pub mod interval;
pub mod messages;
pub mod phase;
#[cfg(feature = "cli")]
#[doc(hidden)]
pub mod plot;
pub mod quad;
pub mod verified;
mod workers;
