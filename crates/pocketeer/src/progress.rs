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

/// Progress kept in memory: the stages begun, with their steps, and the steps done in all. For
/// a front end that shows progress its own way, and for tests of what a run reports.
///
/// ```
/// use pocketeer::progress::{Progress, Recorded};
/// let r = Recorded::default();
/// r.stage("linking 3 loops", Some(3));
/// r.advance(2);
/// assert_eq!(r.stages(), vec![("linking 3 loops".to_owned(), Some(3))]);
/// assert_eq!(r.steps(), 2);
/// ```
#[derive(Debug, Default)]
pub struct Recorded {
    stages: std::sync::Mutex<Vec<(String, Option<u64>)>>,
    steps: std::sync::atomic::AtomicU64,
}

impl Recorded {
    /// The stages begun so far, in order, with the steps each announced.
    pub fn stages(&self) -> Vec<(String, Option<u64>)> {
        self.stages.lock().map(|s| s.clone()).unwrap_or_default()
    }

    /// The steps done so far, over all stages.
    pub fn steps(&self) -> u64 {
        self.steps.load(std::sync::atomic::Ordering::Relaxed)
    }
}

impl Progress for Recorded {
    fn stage(&self, name: &str, steps: Option<u64>) {
        if let Ok(mut s) = self.stages.lock() {
            s.push((name.to_owned(), steps));
        }
    }
    fn advance(&self, n: u64) {
        self.steps.fetch_add(n, std::sync::atomic::Ordering::Relaxed);
    }
}
