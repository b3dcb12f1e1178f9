//! Output into a pipe that closes early (`dtg-vib export --lang text | head`).
//!
//! Rust programs ignore SIGPIPE, so a write to a closed pipe returns an error
//! and `println!` turns it into a panic with a backtrace: a reader that has
//! seen enough is not a failure of the writer. Restoring the default
//! disposition makes the program end quietly on that write, as `cat`, `grep`
//! and every other Unix filter do.

/// Lets a write to a closed stdout end the program quietly (Unix; elsewhere
/// nothing changes). Call it first thing in `main`.
///
/// ```
/// cli_support::pipe::end_quietly_on_closed_pipe();
/// println!("still prints while the reader reads");
/// ```
pub fn end_quietly_on_closed_pipe() {
    #[cfg(unix)]
    // SAFETY: called at start-up before any other thread exists; SIG_DFL is a
    // valid disposition for SIGPIPE and nothing in these programs installs a
    // handler of its own.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}
