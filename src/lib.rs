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
//! - [`exact`]: the small-amplitude series and its exact coefficients;
//! - [`case`]: a case built from numbers or decimals ([`case::CaseText::builder`]) or read
//!   once from its text ([`case::CaseText`] → [`case::CaseSpec`]), computed at any precision;
//! - [`simulate`]: the independent check by a time-stepped simulation;
//! - [`digits`]: where digits are decided — the one loop over working precisions that
//!   every proven digit climbs, its rungs `digits::enclosure` (feature `certified`: W
//!   enclosed in f64 intervals and Arb balls) and [`digits::agreement`] (two precisions
//!   agreeing);
//! - [`decimal`]: exact decimals in, the one printing rule out ([`decimal::printing`]);
//! - [`answer`]: a printed value with its digits, enclosure and provenance, and the one
//!   policy per quantity that builds it: [`answer::dissipation`] (how W is computed and
//!   vouched for, [`answer::dissipation::dissipation_of`]), [`answer::agreed`] (W by
//!   agreement), [`answer::series`] (I, Iₙ, W_N), [`answer::path`] (a path's W),
//!   [`answer::simulation`]; each error says how a command ends on it
//!   ([`answer::ExitStatus`]);
//! - [`verify`]: the theorem gate ([`verify::run`]).
//!
//! Beside them: [`batch`] (many cases from a CSV, on all cores), [`path`] (any periodic
//! load path), [`aft`] (the harmonic-balance friction element), [`interval`] (f64
//! intervals as a [`real::Real`]), `ball` (feature `certified`: Arb balls), [`doubts`]
//! (how those number types report a comparison they cannot decide), [`quad`],
//! [`phase`], [`files`] (atomic output), [`messages`], and with feature `cli` `accuracy` and
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
pub mod compliance;
pub mod cycle;
pub mod decimal;
pub mod digits;
pub mod dissipation;
pub mod doubts;
pub mod exact;
pub mod path;
pub mod real;
pub mod simulate;
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
mod workers;
