//! The heap a recording's buffers pass through. Every hand-over ([`crate::sink::cadence`])
//! copies the buffered rows into new Arrow arrays of a megabyte or more, which Rerun's thread
//! encodes and frees. glibc's allocator gives blocks that large their own mapping, or trims
//! them off the top of its heap when freed, so each hand-over faulted its arrays in again,
//! page by page, on both threads. Kept in the heap, the freed blocks are reused: on the paper
//! case this halves the run's page faults (about 5 200 to 2 700) and takes Rerun's threads from
//! about 66 ms to 57 ms of CPU time ([docs/performance.md](../../docs/performance.md), "The
//! recording's heap").

/// Blocks smaller than this come from the heap, not from mappings of their own (glibc's
/// default starts at 128 KiB and grows with the blocks freed, up to this).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const MMAP_THRESHOLD: libc::c_int = 32 << 20;

/// Free memory at the heap's top that glibc keeps instead of returning it to the system.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const TRIM_THRESHOLD: libc::c_int = 64 << 20;

/// Keeps freed blocks of up to [`MMAP_THRESHOLD`] in the process's heap for reuse. Affects the
/// allocator only, never a result; a C library other than glibc keeps its own policy.
pub fn keep_freed_blocks() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets the allocator's parameters, under the allocator's own lock.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD);
        libc::mallopt(libc::M_TRIM_THRESHOLD, TRIM_THRESHOLD);
    }
}
