//! A subcommand's flags defined only when that subcommand runs.
//!
//! clap's derive defines every subcommand's flags before it parses anything: building them
//! for all six subcommands, on code touched for the first time, took about 0.4 ms of each
//! run, a tenth of a small job's whole process (a `pocket` of a 75-hole plate takes 6 ms).
//! [`Deferred`] hands a subcommand's definition to clap's `Command::defer`, which builds it
//! only when that subcommand is parsed or its help is shown; `pocketeer --help` still lists
//! every subcommand with its summary, which the variant's doc comment sets outside it.

use clap::{ArgMatches, Args, Command, Error, FromArgMatches, Id};

/// The flags `T` of one subcommand, defined when that subcommand is run (see the module).
pub struct Deferred<T>(pub T);

impl<T: Args> Args for Deferred<T> {
    fn augment_args(cmd: Command) -> Command {
        cmd.defer(|cmd| keeping_summary(cmd, T::augment_args))
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        cmd.defer(|cmd| keeping_summary(cmd, T::augment_args_for_update))
    }

    fn group_id() -> Option<Id> {
        T::group_id()
    }
}

/// `define(cmd)` with `cmd`'s summary kept: the flags' struct sets its own doc comment as the
/// summary, which clap's derive, defining the flags first, then replaces with the variant's.
fn keeping_summary(cmd: Command, define: fn(Command) -> Command) -> Command {
    let (about, long_about) = (cmd.get_about().cloned(), cmd.get_long_about().cloned());
    let cmd = define(cmd);
    let cmd = match about {
        Some(text) => cmd.about(text),
        None => cmd.about(None::<&str>),
    };
    match long_about {
        Some(text) => cmd.long_about(text),
        None => cmd.long_about(None::<&str>),
    }
}

impl<T: FromArgMatches> FromArgMatches for Deferred<T> {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, Error> {
        T::from_arg_matches(matches).map(Self)
    }

    fn from_arg_matches_mut(matches: &mut ArgMatches) -> Result<Self, Error> {
        T::from_arg_matches_mut(matches).map(Self)
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), Error> {
        self.0.update_from_arg_matches(matches)
    }

    fn update_from_arg_matches_mut(&mut self, matches: &mut ArgMatches) -> Result<(), Error> {
        self.0.update_from_arg_matches_mut(matches)
    }
}
