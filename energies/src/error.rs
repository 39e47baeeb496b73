//! Errors of the energy layer.

/// The deformation is outside the domain of an energy (for example `J <= 0` where `log J`
/// appears). A line search treats this as "step too long" and backs off.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("J = {j:e} is outside the domain of {energy} (it requires J > 0)")]
pub struct OutOfDomain {
    /// Name of the energy or penalty that refused.
    pub energy: &'static str,
    /// The volume ratio it was given.
    pub j: f64,
}

impl OutOfDomain {
    /// `j` if it is positive, else the error of `energy` at `j` (also for NaN).
    pub fn positive(energy: &'static str, j: f64) -> Result<f64, OutOfDomain> {
        if j > 0.0 {
            Ok(j)
        } else {
            Err(OutOfDomain { energy, j })
        }
    }
}

/// An invalid material parameter, named.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid material parameter {name} = {value}: {reason}")]
pub struct ParameterError {
    /// Parameter name as users write it (`E`, `nu`, `mu`, `lambda`, `beta`, `epsilon`, ...).
    pub name: &'static str,
    /// The offending value.
    pub value: f64,
    /// What is required.
    pub reason: &'static str,
}
