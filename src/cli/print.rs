//! Printing for the commands: a closed standard output (`canstar ... | head`)
//! ends the command quietly, as a pipe's reader expects, instead of a panic.
//! Outputs not yet committed are removed ([`canstar::output`]); the exit status
//! is 141, as for a tool ended by SIGPIPE.

use std::io::Write;

/// Exit status when standard output was closed under the command.
pub const CLOSED_STDOUT: i32 = 141;

/// Write to standard output (see [`outln!`]).
pub fn out(args: std::fmt::Arguments) {
    let mut o = std::io::stdout().lock();
    if let Err(e) = o.write_fmt(args).and_then(|()| o.flush()) {
        closed(&e);
    }
}

/// Standard output failed: end the command.
pub fn closed(e: &std::io::Error) -> ! {
    if e.kind() != std::io::ErrorKind::BrokenPipe {
        let _ = writeln!(std::io::stderr(), "error: cannot write to standard output: {e}");
        canstar::output::abandon_and_exit(1);
    }
    canstar::output::abandon_and_exit(CLOSED_STDOUT)
}

/// Write to standard error; errors are ignored (there is nowhere to report them).
pub fn err(args: std::fmt::Arguments) {
    let _ = std::io::stderr().lock().write_fmt(args);
}

/// Is `e` (or an error in its chain) a closed pipe?
pub fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| c.downcast_ref::<std::io::Error>().is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe))
}
