//! The nonlinear iterations: Newton on the total energy (`standard`, `condensed`), saddle-point
//! Newton on the KKT system (`mixed-*`, `zonal`) and dual ascent around a primal Newton solve
//! (`dual`), each driven by the [`target::StepTarget`] of one load or time step.

pub mod dual;
pub mod forcing;
pub mod krylov;
pub mod newton;
pub mod report;
pub mod saddle;
pub mod target;
