//! The temporary files this process is writing, listed so that a signal handler can remove
//! them: fixed slots of NUL-terminated paths, each claimed and handed back by an atomic
//! compare-and-swap of its state, so that reading the list takes no lock and allocates
//! nothing (what a handler may do: a lock held by the interrupted code would never be
//! released).
//!
//! A slot goes `FREE → FILLING → HELD` while its writer lists a file, back to `FREE` when the
//! file is committed or dropped, and `HELD → TAKEN` when [`take`] hands it to a handler; a
//! taken slot is never reused (the process is ending), so a handler never reads a path being
//! overwritten. A file beyond the [`SLOTS`], or whose path does not fit a slot, is not listed:
//! a signal leaves it behind, and the next write to its target removes it as stale.

use std::cell::UnsafeCell;
use std::ffi::CStr;
use std::path::Path;
use std::sync::atomic::{AtomicU8, Ordering};

/// Files written at the same time (the CLI writes at most two: `--output` and `--plot`).
const SLOTS: usize = 16;
/// Bytes of a path, with its terminating NUL (Linux's `PATH_MAX`).
const PATH_BYTES: usize = 4096;

const FREE: u8 = 0;
const FILLING: u8 = 1;
const HELD: u8 = 2;
const TAKEN: u8 = 3;

/// The slots' states, side by side (a scan touches one cache line, not a page per slot).
static STATES: [AtomicU8; SLOTS] = [const { AtomicU8::new(FREE) }; SLOTS];

/// The slots' paths; a page is touched only when its slot is first used.
static PATHS: Paths = Paths([const { UnsafeCell::new([0; PATH_BYTES]) }; SLOTS]);

struct Paths([UnsafeCell<[u8; PATH_BYTES]>; SLOTS]);

// SAFETY: a slot's path is written only by the thread that moved its state from FREE to
// FILLING, and read only by the one that moved it from HELD to TAKEN (after the writer's
// release store of HELD); no two threads access it at the same time.
unsafe impl Sync for Paths {}

/// A listed file: handed back (its slot freed) when dropped.
pub(super) struct Listed(usize);

impl Drop for Listed {
    fn drop(&mut self) {
        // A slot taken by a handler stays taken.
        let _ = STATES[self.0].compare_exchange(HELD, FREE, Ordering::AcqRel, Ordering::Relaxed);
    }
}

/// Lists `tmp` as being written: `None` when every slot is in use or the path does not fit.
pub(super) fn list(tmp: &Path) -> Option<Listed> {
    let bytes = tmp.as_os_str().as_encoded_bytes();
    if bytes.len() >= PATH_BYTES || bytes.contains(&0) {
        return None;
    }
    let k = STATES.iter().position(|state| {
        state
            .compare_exchange(FREE, FILLING, Ordering::Acquire, Ordering::Relaxed)
            .is_ok()
    })?;
    // SAFETY: this thread moved the slot to FILLING: nobody else reads or writes its path.
    let path = unsafe { &mut *PATHS.0[k].get() };
    path[..bytes.len()].copy_from_slice(bytes);
    path[bytes.len()] = 0;
    STATES[k].store(HELD, Ordering::Release);
    Some(Listed(k))
}

/// Takes every listed file out of the list and passes its path to `each`, without locking or
/// allocating: callable from a signal handler (which then removes the files and ends the
/// process). The taken slots are not reused.
pub fn take(mut each: impl FnMut(&CStr)) {
    for (state, path) in STATES.iter().zip(&PATHS.0) {
        if state
            .compare_exchange(HELD, TAKEN, Ordering::Acquire, Ordering::Relaxed)
            .is_ok()
        {
            // SAFETY: this thread moved the slot from HELD to TAKEN: its path is complete
            // (released before HELD) and no writer touches it any more.
            let path = unsafe { &*path.get() };
            if let Ok(p) = CStr::from_bytes_until_nul(path) {
                each(p);
            }
        }
    }
}
