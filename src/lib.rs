//! microslip: frictional (microslip) energy dissipation per cycle in elastic
//! contacts of rough surfaces under oscillating normal and tangential loads.
//!
//! Read top-down: [`real`] (the number type), [`quad`] (quadrature rules),
//! [`compliance`] (the contact's normal compliance v(P)), [`cycle`] (the load
//! cycle and its ellipse), [`dissipation`] (W over the four segments, and the
//! closed forms), and [`case`] (a case read once from its text, at any precision).
//!
//! The default feature `cli` adds the tools around the library: the plots (`plot`,
//! `figures`), the accuracy benchmark (`accuracy`) and the catalogue of reference
//! values (`catalogue`). Built without it (no default features) the
//! library needs no argument parser, plotting, progress display or JSON text.

#[cfg(feature = "cli")]
pub mod accuracy;
pub mod answer;
#[cfg(feature = "certified")]
pub mod ball;
pub mod batch;
pub mod case;
#[cfg(feature = "cli")]
pub mod catalogue;
#[cfg(feature = "certified")]
pub mod certified;
pub mod compliance;
pub mod cycle;
mod decimal;
pub mod dissipation;
pub mod dissipation_answer;
pub mod exact;
#[cfg(feature = "cli")]
pub mod figures;
pub mod files;
pub mod inputs;
pub mod phase;
#[cfg(feature = "cli")]
pub mod plot;
pub mod quad;
pub mod real;
pub mod reference;
pub mod simulate;
pub mod verified;
pub mod verify;
