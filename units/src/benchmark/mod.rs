//! Units of the coupling benchmarks (B1-B3, B6): problems with known solutions
//! that verify the master's schemes, kept apart from the physics.

pub mod algebraic_loop;
pub mod oscillator;
