//! Everything that calls FLINT/Arb directly: the ball type, the enclosure of a phase's
//! multiple of π, and rigorous Gauss–Legendre on balls with its node table. The crate's
//! other code reaches Arb only through these (and the Arb rung of `certified`, which
//! hands pieces to `acb_calc_integrate`).

pub mod ball;
pub(crate) mod gauss;
mod pi;

pub use pi::enclose_pi_multiple;
#[cfg(test)]
pub(crate) use pi::relatively_within;
