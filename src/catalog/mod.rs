//! What happened in a run, in the paper's terms: slip events of each segment (a plastic slip
//! rate above the threshold), ruptures (events that overlap in time, spreading along the
//! surface), the paper's three observations judged on them, and the openings of contacts
//! whose normal traction evolves.

pub mod events;
pub mod observations;
pub mod openings;
