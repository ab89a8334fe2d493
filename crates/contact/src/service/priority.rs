//! The solve and read threads run at a lower scheduling priority than zenoh's.
//!
//! `busy` and the other refusals at the door are decided in microseconds on
//! zenoh's receiving thread and sent by zenoh's transmitting task; both must
//! get a core while solves hold them. Under Linux's scheduler a thread at
//! nice 10 weighs 110 against 1024 at nice 0, so a woken zenoh thread is
//! picked well ahead of a solve; a solve with the core to itself loses
//! nothing. On 2 loaded cores this about halved the median `busy` at the
//! client, while the service's own part stayed at microseconds, and slowed a
//! burst's solves by about a quarter: the figures and how they were measured
//! are in `docs/howto/service.md` (how the service behaves under a burst).
//!
//! The cost: on a machine shared with other busy processes the solves yield
//! to theirs too. Linux only (`setpriority` with the thread's id sets one
//! thread's niceness there; elsewhere it would set the whole process's,
//! zenoh's threads included); a no-op on other systems.

/// The niceness of solve and read threads (0 normal, 19 lowest).
pub const BACKGROUND_NICE: i32 = 10;

/// Lowers the calling thread to `BACKGROUND_NICE` once; later calls on the
/// same thread do nothing. Lowering needs no privilege; raising it back
/// would (so a thread, once lowered, stays so: only solves and reads run on
/// the blocking pool). A refusal by the system is logged once and ignored.
pub fn lower_this_thread() {
    #[cfg(target_os = "linux")]
    {
        use std::cell::Cell;
        thread_local!(static LOWERED: Cell<bool> = const { Cell::new(false) });
        if LOWERED.with(|l| l.replace(true)) {
            return;
        }
        // SAFETY: gettid and setpriority take and return plain integers; the
        // id is this thread's own, alive for the call.
        let rc = unsafe {
            let tid = libc::gettid();
            libc::setpriority(libc::PRIO_PROCESS, tid as libc::id_t, BACKGROUND_NICE)
        };
        if rc != 0 {
            static WARNED: std::sync::Once = std::sync::Once::new();
            WARNED.call_once(|| {
                tracing::warn!(
                    "cannot lower the solve threads' priority ({}); `busy` may wait behind solves",
                    std::io::Error::last_os_error()
                )
            });
        }
    }
}

/// The calling thread's niceness (Linux), for tests.
#[cfg(all(test, target_os = "linux"))]
fn this_thread_nice() -> i32 {
    // SAFETY: as above; errno is cleared first since -1 is a valid niceness.
    unsafe {
        *libc::__errno_location() = 0;
        libc::getpriority(libc::PRIO_PROCESS, libc::gettid() as libc::id_t)
    }
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;

    #[test]
    fn lowers_only_the_calling_thread() {
        let before = this_thread_nice();
        let inside = std::thread::spawn(|| {
            lower_this_thread();
            lower_this_thread();
            this_thread_nice()
        })
        .join()
        .unwrap();
        // setpriority sets the niceness, it does not add to it (from a process
        // already above 10, going back to 10 would need privilege).
        if before <= BACKGROUND_NICE {
            assert_eq!(inside, BACKGROUND_NICE);
        }
        assert_eq!(this_thread_nice(), before, "the other threads keep their priority");
    }
}
