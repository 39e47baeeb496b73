//! The commands of the `isochor` program, as library functions. Inside this layer `run` is at
//! the bottom; `check` and `penalties` stand alone; `compare` and `study` run scenes through
//! `run`.

pub mod check;
pub mod compare;
pub mod penalties;
pub mod run;
pub mod study;
