//! The file formats, owned in one place: the Rerun recording's timelines, entity paths, units
//! and run descriptions ([`schema`]), the series digests ([`digest`]), the colour maps, and the MCAP log's topics and protobuf
//! messages ([`mcap`], [`proto`]). Writers ([`crate::sink`]) and readers ([`crate::inspect`],
//! [`crate::study`]) both use it.

pub mod checkpoint;
pub mod colormap;
pub mod compact;
pub mod continuation;
pub mod digest;
pub mod mcap;
pub mod proto;
pub mod schema;
pub mod table;
