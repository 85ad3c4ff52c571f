//! Progress of long runs: the stages a job goes through and how far each has come, for a
//! front end to show (the CLI draws a spinner on a terminal). The library only reports; it
//! never prints.

/// Receives a run's progress. Called from the planning threads too, so it is `Sync`; every
/// method has a default that does nothing.
pub trait Progress: Sync {
    /// A stage begins (`"planning"`, `"linking"`, …), with how many steps it has when known.
    fn stage(&self, _name: &str, _steps: Option<u64>) {}
    /// `n` more steps of the stage are done.
    fn advance(&self, _n: u64) {}
}

/// Progress that goes nowhere.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Progress for Silent {}
