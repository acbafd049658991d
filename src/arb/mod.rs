//! Everything that calls FLINT/Arb directly: the ball type, the enclosure of a phase's
//! multiple of π, rigorous Gauss–Legendre on balls with its node table, and Arb's own
//! adaptive integration. The crate's other code reaches Arb only through these.

pub mod ball;
pub(crate) mod bisection;
pub(crate) mod gauss;
mod pi;

pub use pi::enclose_pi_multiple;
#[cfg(test)]
pub(crate) use pi::relatively_within;
