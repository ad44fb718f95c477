//! Ctrl-C inside a law written in Python. The solvers stop at their next step once asked
//! (`integrators::interrupt`), but a law that never returns never gives them that step. So
//! every thread that may call a law is registered while it can, and a stop raises
//! `KeyboardInterrupt` in each of them asynchronously (`PyThreadState_SetAsyncExc`): the law
//! raises it at its next bytecode, which stops the run as any exception of a law does. A law
//! blocked in a call into C (a `time.sleep`) raises it when that call returns.

use pyo3::ffi;
use pyo3::Python;
use std::ffi::{c_long, c_ulong};
use std::sync::Mutex;

/// The Python thread identifiers of the threads that may call a law now.
static THREADS: Mutex<Vec<c_ulong>> = Mutex::new(Vec::new());

/// A thread registered as one that may call a law ([`register`]); dropping it unregisters it.
pub struct Registered(c_ulong);

/// Registers the calling thread, attached to Python, as one that may call a law.
pub fn register(_py: Python<'_>) -> Registered {
    // SAFETY: the thread is attached to the interpreter (`_py`).
    let id = unsafe { ffi::PyThread_get_thread_ident() };
    THREADS.lock().unwrap_or_else(|e| e.into_inner()).push(id);
    Registered(id)
}

impl Drop for Registered {
    fn drop(&mut self) {
        let mut threads = THREADS.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(i) = threads.iter().position(|&id| id == self.0) {
            threads.swap_remove(i);
        }
    }
}

/// Raises `KeyboardInterrupt` in every registered thread at its next bytecode.
pub fn raise_in_laws(_py: Python<'_>) {
    set_async(unsafe { ffi::PyExc_KeyboardInterrupt });
}

/// Withdraws the exception [`raise_in_laws`] left pending in a thread that ran no Python code
/// since (an idle worker of a pool), so that it does not stop a later run.
pub fn withdraw(_py: Python<'_>) {
    set_async(std::ptr::null_mut());
}

/// `PyThreadState_SetAsyncExc(id, exception)` for every registered thread (null withdraws).
fn set_async(exception: *mut ffi::PyObject) {
    let threads = THREADS.lock().unwrap_or_else(|e| e.into_inner());
    for &id in threads.iter() {
        // SAFETY: called with the GIL held (the callers take `Python`); the exception is a
        // built-in type object or null.
        unsafe {
            ffi::PyThreadState_SetAsyncExc(id as c_long, exception);
        }
    }
}
