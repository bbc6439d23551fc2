//! Time integrators shared by the units; one integrator per file.

pub mod newmark;
