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
//! Modules hidden from this documentation (`quad`, `files`, `batch`, `verified`, `ball`,
//! `phase`, `doubts`, `interval`, and with feature `cli` `accuracy`, `catalogue`, `figures`, `plot`) are
//! public only for the command line, the tests and the benches; they are not part of
//! the API and change without notice.
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
#[doc(hidden)]
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
#[doc(hidden)]
pub mod accuracy;
#[cfg(feature = "certified")]
#[doc(hidden)]
pub mod arb;
#[cfg(feature = "certified")]
#[doc(hidden)]
pub use arb::ball;
#[cfg(feature = "certified")]
use arb::gauss as ball_gauss;
#[doc(hidden)]
pub mod batch;
#[cfg(feature = "cli")]
#[doc(hidden)]
pub mod catalogue;
#[cfg(feature = "cli")]
#[doc(hidden)]
pub mod figures;
#[doc(hidden)]
pub mod files;
#[doc(hidden)]
pub mod interval;
#[doc(hidden)]
pub mod messages;
#[doc(hidden)]
pub mod phase;
#[cfg(feature = "cli")]
#[doc(hidden)]
pub mod plot;
#[doc(hidden)]
pub mod quad;
#[doc(hidden)]
pub mod verified;
mod workers;
