//! isochor solvers
