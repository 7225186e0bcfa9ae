//! The protobuf messages of a slipfront MCAP log, and their `FileDescriptorSet`.
//!
//! The descriptor is built in code (no `protoc`): [`MESSAGES`] lists every field once, and
//! [`file_descriptor_set`] turns the list into the schema data MCAP readers need (Foxglove, the
//! Python `mcap-protobuf-support`, Rerun's protobuf decoder). The structs below must agree with
//! it field by field; `tests/mcap.rs` decodes each through the descriptor to prove they do.
//!
//! ```proto
//! syntax = "proto3";
//! package slipfront;
//! message Run { string header = 1; }                      // TOML: plan, layout, selection
//! message SegmentStates {                                 // one per recorded step
//!   double time = 1; uint32 step = 2;
//!   repeated double traction_t = 3; repeated double traction_n = 4; repeated double R = 5;
//!   repeated double R_star = 6; repeated double structure = 7; repeated double slip_rate = 8;
//!   repeated double slip = 9;                             // index = segment from the left
//! }
//! message NodeDisplacements { double time = 1; uint32 step = 2; repeated uint32 nodes = 3;
//!   repeated double u_x = 4; repeated double u_y = 5; }
//! message MeshDisplacements { double time = 1; uint32 step = 2;
//!   repeated double u_x = 3; repeated double u_y = 4; }  // index = node id, row by row
//! message Totals { double time = 1; uint32 step = 2; double friction_force = 3;
//!   double base_u_x = 4; double block_x = 5; double block_v = 6; }
//! message SlipEvent { uint32 segment = 1; double onset = 2; double end = 3; double slip = 4;
//!   double peak_slip_rate = 5; double traction_before = 6; double traction_after = 7;
//!   double friction_force_before = 8; double friction_force_after = 9;
//!   double structure_before = 10; }                       // NaN where not recorded
//! message Rupture { double onset = 1; double end = 2; uint32 nucleation_segment = 3;
//!   uint32 first_segment = 4; uint32 last_segment = 5; uint32 segments_slipped = 6;
//!   double max_slip = 7; double friction_force_drop = 8; }
//! message Ending { string ending = 1; }                   // TOML: how the run ended
//! ```

use prost::Message as _;
use prost_types::field_descriptor_proto::{Label, Type};
use prost_types::{DescriptorProto, FieldDescriptorProto, FileDescriptorProto, FileDescriptorSet};

/// Protobuf package of every message.
pub const PACKAGE: &str = "slipfront";

/// A field of the schema: name, number, type, repeated.
type Field = (&'static str, i32, Type, bool);

/// Every message and its fields: the single source of the descriptor.
pub const MESSAGES: &[(&str, &[Field])] = &[
    ("Run", &[("header", 1, Type::String, false)]),
    (
        "SegmentStates",
        &[
            ("time", 1, Type::Double, false),
            ("step", 2, Type::Uint32, false),
            ("traction_t", 3, Type::Double, true),
            ("traction_n", 4, Type::Double, true),
            ("R", 5, Type::Double, true),
            ("R_star", 6, Type::Double, true),
            ("structure", 7, Type::Double, true),
            ("slip_rate", 8, Type::Double, true),
            ("slip", 9, Type::Double, true),
        ],
    ),
    (
        "NodeDisplacements",
        &[
            ("time", 1, Type::Double, false),
            ("step", 2, Type::Uint32, false),
            ("nodes", 3, Type::Uint32, true),
            ("u_x", 4, Type::Double, true),
            ("u_y", 5, Type::Double, true),
        ],
    ),
    (
        "MeshDisplacements",
        &[
            ("time", 1, Type::Double, false),
            ("step", 2, Type::Uint32, false),
            ("u_x", 3, Type::Double, true),
            ("u_y", 4, Type::Double, true),
        ],
    ),
    (
        "Totals",
        &[
            ("time", 1, Type::Double, false),
            ("step", 2, Type::Uint32, false),
            ("friction_force", 3, Type::Double, false),
            ("base_u_x", 4, Type::Double, false),
            ("block_x", 5, Type::Double, false),
            ("block_v", 6, Type::Double, false),
        ],
    ),
    (
        "SlipEvent",
        &[
            ("segment", 1, Type::Uint32, false),
            ("onset", 2, Type::Double, false),
            ("end", 3, Type::Double, false),
            ("slip", 4, Type::Double, false),
            ("peak_slip_rate", 5, Type::Double, false),
            ("traction_before", 6, Type::Double, false),
            ("traction_after", 7, Type::Double, false),
            ("friction_force_before", 8, Type::Double, false),
            ("friction_force_after", 9, Type::Double, false),
            ("structure_before", 10, Type::Double, false),
        ],
    ),
    (
        "Rupture",
        &[
            ("onset", 1, Type::Double, false),
            ("end", 2, Type::Double, false),
            ("nucleation_segment", 3, Type::Uint32, false),
            ("first_segment", 4, Type::Uint32, false),
            ("last_segment", 5, Type::Uint32, false),
            ("segments_slipped", 6, Type::Uint32, false),
            ("max_slip", 7, Type::Double, false),
            ("friction_force_drop", 8, Type::Double, false),
        ],
    ),
    ("Ending", &[("ending", 1, Type::String, false)]),
];

/// The serialized `FileDescriptorSet` of every message (proto3, package `slipfront`).
pub fn file_descriptor_set() -> Vec<u8> {
    let message_type = MESSAGES
        .iter()
        .map(|(name, fields)| DescriptorProto {
            name: Some((*name).into()),
            field: fields
                .iter()
                .map(|&(field, number, kind, repeated)| FieldDescriptorProto {
                    name: Some(field.into()),
                    number: Some(number),
                    label: Some(if repeated { Label::Repeated } else { Label::Optional } as i32),
                    r#type: Some(kind as i32),
                    json_name: Some(field.into()),
                    ..Default::default()
                })
                .collect(),
            ..Default::default()
        })
        .collect();
    let file = FileDescriptorProto {
        name: Some("slipfront/log.proto".into()),
        package: Some(PACKAGE.into()),
        syntax: Some("proto3".into()),
        message_type,
        ..Default::default()
    };
    FileDescriptorSet { file: vec![file] }.encode_to_vec()
}

/// Fully qualified name of message `name`.
pub fn full_name(name: &str) -> String {
    format!("{PACKAGE}.{name}")
}

#[derive(Clone, PartialEq, prost::Message)]
pub struct Run {
    #[prost(string, tag = "1")]
    pub header: String,
}

#[derive(Clone, PartialEq, prost::Message)]
pub struct SegmentStates {
    #[prost(double, tag = "1")]
    pub time: f64,
    #[prost(uint32, tag = "2")]
    pub step: u32,
    #[prost(double, repeated, tag = "3")]
    pub traction_t: Vec<f64>,
    #[prost(double, repeated, tag = "4")]
    pub traction_n: Vec<f64>,
    #[prost(double, repeated, tag = "5")]
    pub sliding_ratio: Vec<f64>,
    #[prost(double, repeated, tag = "6")]
    pub r_star: Vec<f64>,
    #[prost(double, repeated, tag = "7")]
    pub structure: Vec<f64>,
    #[prost(double, repeated, tag = "8")]
    pub slip_rate: Vec<f64>,
    #[prost(double, repeated, tag = "9")]
    pub slip: Vec<f64>,
}

#[derive(Clone, PartialEq, prost::Message)]
pub struct NodeDisplacements {
    #[prost(double, tag = "1")]
    pub time: f64,
    #[prost(uint32, tag = "2")]
    pub step: u32,
    #[prost(uint32, repeated, tag = "3")]
    pub nodes: Vec<u32>,
    #[prost(double, repeated, tag = "4")]
    pub u_x: Vec<f64>,
    #[prost(double, repeated, tag = "5")]
    pub u_y: Vec<f64>,
}

#[derive(Clone, PartialEq, prost::Message)]
pub struct MeshDisplacements {
    #[prost(double, tag = "1")]
    pub time: f64,
    #[prost(uint32, tag = "2")]
    pub step: u32,
    #[prost(double, repeated, tag = "3")]
    pub u_x: Vec<f64>,
    #[prost(double, repeated, tag = "4")]
    pub u_y: Vec<f64>,
}

#[derive(Clone, PartialEq, prost::Message)]
pub struct Totals {
    #[prost(double, tag = "1")]
    pub time: f64,
    #[prost(uint32, tag = "2")]
    pub step: u32,
    #[prost(double, tag = "3")]
    pub friction_force: f64,
    #[prost(double, tag = "4")]
    pub base_u_x: f64,
    #[prost(double, tag = "5")]
    pub block_x: f64,
    #[prost(double, tag = "6")]
    pub block_v: f64,
}

#[derive(Clone, PartialEq, prost::Message)]
pub struct SlipEvent {
    #[prost(uint32, tag = "1")]
    pub segment: u32,
    #[prost(double, tag = "2")]
    pub onset: f64,
    #[prost(double, tag = "3")]
    pub end: f64,
    #[prost(double, tag = "4")]
    pub slip: f64,
    #[prost(double, tag = "5")]
    pub peak_slip_rate: f64,
    #[prost(double, tag = "6")]
    pub traction_before: f64,
    #[prost(double, tag = "7")]
    pub traction_after: f64,
    #[prost(double, tag = "8")]
    pub friction_force_before: f64,
    #[prost(double, tag = "9")]
    pub friction_force_after: f64,
    #[prost(double, tag = "10")]
    pub structure_before: f64,
}

#[derive(Clone, PartialEq, prost::Message)]
pub struct Rupture {
    #[prost(double, tag = "1")]
    pub onset: f64,
    #[prost(double, tag = "2")]
    pub end: f64,
    #[prost(uint32, tag = "3")]
    pub nucleation_segment: u32,
    #[prost(uint32, tag = "4")]
    pub first_segment: u32,
    #[prost(uint32, tag = "5")]
    pub last_segment: u32,
    #[prost(uint32, tag = "6")]
    pub segments_slipped: u32,
    #[prost(double, tag = "7")]
    pub max_slip: f64,
    #[prost(double, tag = "8")]
    pub friction_force_drop: f64,
}

#[derive(Clone, PartialEq, prost::Message)]
pub struct Ending {
    #[prost(string, tag = "1")]
    pub ending: String,
}

impl From<&crate::catalog::events::SlipEvent> for SlipEvent {
    fn from(e: &crate::catalog::events::SlipEvent) -> Self {
        Self {
            segment: e.segment as u32,
            onset: e.onset,
            end: e.end,
            slip: e.slip,
            peak_slip_rate: e.peak_slip_rate,
            traction_before: e.traction_before,
            traction_after: e.traction_after,
            friction_force_before: e.friction_force_before,
            friction_force_after: e.friction_force_after,
            structure_before: e.structure_before.unwrap_or(f64::NAN),
        }
    }
}

impl From<SlipEvent> for crate::catalog::events::SlipEvent {
    fn from(e: SlipEvent) -> Self {
        Self {
            segment: e.segment as usize,
            onset: e.onset,
            end: e.end,
            slip: e.slip,
            peak_slip_rate: e.peak_slip_rate,
            traction_before: e.traction_before,
            traction_after: e.traction_after,
            friction_force_before: e.friction_force_before,
            friction_force_after: e.friction_force_after,
            structure_before: (!e.structure_before.is_nan()).then_some(e.structure_before),
        }
    }
}

impl From<&crate::catalog::events::Rupture> for Rupture {
    fn from(r: &crate::catalog::events::Rupture) -> Self {
        Self {
            onset: r.onset,
            end: r.end,
            nucleation_segment: r.nucleation_segment as u32,
            first_segment: r.first_segment as u32,
            last_segment: r.last_segment as u32,
            segments_slipped: r.segments_slipped as u32,
            max_slip: r.max_slip,
            friction_force_drop: r.friction_force_drop,
        }
    }
}

impl From<Rupture> for crate::catalog::events::Rupture {
    fn from(r: Rupture) -> Self {
        Self {
            onset: r.onset,
            end: r.end,
            nucleation_segment: r.nucleation_segment as usize,
            first_segment: r.first_segment as usize,
            last_segment: r.last_segment as usize,
            segments_slipped: r.segments_slipped as usize,
            max_slip: r.max_slip,
            friction_force_drop: r.friction_force_drop,
        }
    }
}
