//! Progress on a terminal: a spinner with the stage, its steps and the time elapsed, shown on
//! standard error once a run has taken a second, cleared when it ends; nothing when standard
//! error is not a terminal or under `--quiet`.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Set by `--quiet`.
pub static QUIET: AtomicBool = AtomicBool::new(false);

/// How long a run goes before its progress shows, unless `POCKETEER_PROGRESS_DELAY_MS` says
/// otherwise (the tests show it at once).
fn delay() -> Duration {
    std::env::var("POCKETEER_PROGRESS_DELAY_MS")
        .ok()
        .and_then(|v| v.parse().ok())
        .map_or(Duration::from_secs(1), Duration::from_millis)
}

/// The progress of one run; cleared when dropped.
pub struct Spinner {
    bar: ProgressBar,
}

impl Spinner {
    /// A spinner at `stage`, drawn after a second when standard error is a terminal and
    /// `--quiet` was not given.
    pub fn start(stage: &str) -> Spinner {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        let s = Spinner { bar };
        s.set_stage(stage, None);
        if !QUIET.load(Ordering::Relaxed) && std::io::stderr().is_terminal() {
            let show = |bar: &ProgressBar| {
                bar.set_draw_target(ProgressDrawTarget::stderr());
                bar.enable_steady_tick(Duration::from_millis(120));
            };
            let wait = delay();
            if wait.is_zero() {
                // At once, not from a thread that a loaded machine may start only after a
                // short run has ended.
                show(&s.bar);
            } else {
                let bar = s.bar.clone();
                std::thread::spawn(move || {
                    std::thread::sleep(wait);
                    if !bar.is_finished() {
                        show(&bar);
                    }
                });
            }
        }
        s
    }

    fn set_stage(&self, name: &str, steps: Option<u64>) {
        let template = match steps {
            Some(_) => "{spinner} {elapsed:>3} {msg}: {pos}/{len}",
            None => "{spinner} {elapsed:>3} {msg}",
        };
        if let Ok(style) = ProgressStyle::with_template(template) {
            self.bar.set_style(style);
        }
        match steps {
            Some(n) => {
                self.bar.set_length(n);
                self.bar.set_position(0);
            }
            None => self.bar.unset_length(),
        }
        self.bar.set_message(name.to_string());
    }

    /// Runs `f` (which prints) with the spinner off the screen.
    pub fn bar_suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        self.bar.suspend(f)
    }

    /// Moves on to `stage`.
    pub fn stage(&self, stage: &str) {
        self.set_stage(stage, None);
    }
}

impl pocketeer::progress::Progress for Spinner {
    fn stage(&self, name: &str, steps: Option<u64>) {
        self.set_stage(name, steps);
    }
    fn advance(&self, n: u64) {
        self.bar.inc(n);
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}
