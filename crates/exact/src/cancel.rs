//! Cooperative cancellation of long computations (the REPL's Ctrl-C).
//!
//! A thread that may be abandoned takes a [`ticket`] and [`enter`]s it; a
//! front end that gives up on it calls [`cancel`] with that ticket. The
//! hot entry points of exact arithmetic (polynomial products and GCDs,
//! canonicalization of quotients) call [`check`], which unwinds a
//! cancelled thread with [`Cancelled`] (by `resume_unwind`, so no panic
//! message is printed); the front end has already moved on. Threads that
//! never `enter` a ticket — the CLI, the library's users — are never
//! cancelled, and `check` costs them a thread-local read and an atomic
//! load.

use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};

/// Tickets below this one are cancelled.
static CANCELLED_BELOW: AtomicU64 = AtomicU64::new(0);
static NEXT: AtomicU64 = AtomicU64::new(0);

thread_local! {
    static TICKET: Cell<u64> = const { Cell::new(u64::MAX) };
}

/// The payload a cancelled computation unwinds with.
#[derive(Debug)]
pub struct Cancelled;

/// A new ticket, for a computation that may be cancelled.
pub fn ticket() -> u64 {
    NEXT.fetch_add(1, Ordering::SeqCst)
}

/// Make the current thread's computations cancellable under `ticket`.
pub fn enter(ticket: u64) {
    TICKET.with(|t| t.set(ticket));
}

/// Cancel the computation holding `ticket` (and every older one).
pub fn cancel(ticket: u64) {
    CANCELLED_BELOW.fetch_max(ticket.saturating_add(1), Ordering::SeqCst);
}

/// Unwind with [`Cancelled`] if this thread's computation was cancelled.
#[inline]
pub fn check() {
    if TICKET.with(Cell::get) < CANCELLED_BELOW.load(Ordering::Relaxed) {
        std::panic::resume_unwind(Box::new(Cancelled));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cancelled_thread_unwinds_and_others_go_on() {
        let t = ticket();
        let h = std::thread::spawn(move || {
            enter(t);
            std::panic::catch_unwind(|| loop {
                check();
                std::thread::yield_now();
            })
        });
        cancel(t);
        let r = h.join().expect("the thread ends");
        let payload = r.expect_err("it unwound");
        assert!(payload.downcast_ref::<Cancelled>().is_some());
        // this thread never entered a ticket: not cancelled
        check();
        // a newer ticket is not cancelled by the older cancel
        let t2 = ticket();
        let ok = std::thread::spawn(move || {
            enter(t2);
            check();
            7
        })
        .join()
        .expect("not cancelled");
        assert_eq!(ok, 7);
    }
}
