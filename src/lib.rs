//! microslip: frictional (microslip) energy dissipation per cycle in elastic
//! contacts of rough surfaces under oscillating normal and tangential loads.
//!
//! Read top-down: [`real`] (the number type), [`quad`] (quadrature rules),
//! [`compliance`] (the contact's normal compliance v(P)), [`cycle`] (the load
//! cycle and its ellipse), [`dissipation`] (W over the four segments, and the
//! closed forms).

pub mod accuracy;
pub mod batch;
pub mod catalogue;
pub mod compliance;
pub mod cycle;
pub mod dissipation;
pub mod exact;
pub mod figures;
pub mod files;
pub mod inputs;
pub mod plot;
pub mod quad;
pub mod real;
pub mod reference;
pub mod simulate;
pub mod verified;
pub mod verify;
