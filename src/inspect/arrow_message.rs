//! Checks the lengths inside one Rerun `ArrowMsg` before Rerun's decoder trusts them.
//!
//! An `ArrowMsg` (a protobuf message) carries an Arrow IPC stream, LZ4-compressed or not, and
//! Rerun's decoder allocates two lengths it finds there before reading what they describe: the
//! protobuf's `uncompressed_size` (`re_log_encoding` 0.36 resizes a buffer to it), and each IPC
//! message's `bodyLength` (`arrow-ipc` 58 allocates it zeroed). A damaged file that claims
//! exabytes in either aborts the process, which no panic handler catches (fuzzing found the
//! second: `fuzz/regressions/rrd_read/crash-90d08cdc…`). This walks the same structure with every length
//! checked against what follows it, so that the reader stops before such a message.

use rerun::external::arrow::ipc::{self, MessageHeader};

/// The largest ratio of LZ4 block compression (a run of one byte): 255 bytes out per byte in.
const LZ4_MAX_RATIO: u64 = 255;

/// The fields of Rerun's `rerun.log_msg.v1alpha1.ArrowMsg` that frame its payload (the others
/// are skipped).
#[derive(Clone, PartialEq, prost::Message)]
struct ArrowMsgFrame {
    #[prost(int32, tag = "2")]
    compression: i32,
    #[prost(uint64, tag = "3")]
    uncompressed_size: u64,
    #[prost(bytes = "vec", tag = "5")]
    payload: Vec<u8>,
}

/// `rerun.common.v1alpha1.Compression::Lz4`.
const LZ4: i32 = 2;

/// What is wrong with the lengths of the `ArrowMsg` encoded in `message`, if anything: a
/// protobuf that does not decode is left to Rerun's decoder, which reports it without
/// allocating anything it claims.
pub fn problem(message: &[u8]) -> Option<String> {
    let frame = <ArrowMsgFrame as prost::Message>::decode(message).ok()?;
    if frame.compression != LZ4 {
        return ipc_stream_problem(&frame.payload);
    }
    let most = (frame.payload.len() as u64).saturating_mul(LZ4_MAX_RATIO);
    if frame.uncompressed_size > most {
        return Some(format!(
            "an Arrow message claims {} bytes uncompressed from {} compressed (LZ4 gives at most {most})",
            frame.uncompressed_size,
            frame.payload.len()
        ));
    }
    let mut uncompressed = vec![0; frame.uncompressed_size as usize];
    match lz4_flex::block::decompress_into(&frame.payload, &mut uncompressed) {
        Ok(_) => ipc_stream_problem(&uncompressed),
        // The decoder fails on it too, with its own message.
        Err(_) => None,
    }
}

/// Walks an Arrow IPC stream: each message is an optional `0xFFFFFFFF` continuation marker, a
/// metadata length (i32), a `Message` flatbuffer of that length and a body of its
/// `bodyLength`; a zero length ends the stream. Every length must fit in what follows, and
/// every buffer of a record or dictionary batch in its body; a compressed batch (whose buffers
/// declare their uncompressed lengths, which Rerun never writes) is refused.
fn ipc_stream_problem(stream: &[u8]) -> Option<String> {
    let mut rest = stream;
    while rest.len() >= 4 {
        let mut word = i32::from_le_bytes(rest[..4].try_into().expect("4 bytes"));
        rest = &rest[4..];
        if word == -1 {
            let next = rest.get(..4)?;
            word = i32::from_le_bytes(next.try_into().expect("4 bytes"));
            rest = &rest[4..];
        }
        if word == 0 {
            return None;
        }
        let Some(metadata) = usize::try_from(word).ok().and_then(|len| rest.get(..len)) else {
            return Some(format!("an Arrow IPC message claims {word} bytes of metadata; {} follow", rest.len()));
        };
        // A flatbuffer that does not verify is reported by the decoder without allocating.
        let Ok(message) = ipc::root_as_message(metadata) else { return None };
        rest = &rest[metadata.len()..];
        let body = message.bodyLength();
        let Some(fits) = usize::try_from(body).ok().filter(|&b| b <= rest.len()) else {
            return Some(format!("an Arrow IPC message claims a body of {body} bytes; {} follow", rest.len()));
        };
        if let Some(problem) = batch_problem(&message, body) {
            return Some(problem);
        }
        rest = &rest[fits..];
    }
    None
}

/// The buffers of a record batch (or of a dictionary batch's data) must lie in the message's
/// body of `body` bytes, and must not be compressed.
fn batch_problem(message: &ipc::Message<'_>, body: i64) -> Option<String> {
    let batch = match message.header_type() {
        MessageHeader::RecordBatch => message.header_as_record_batch(),
        MessageHeader::DictionaryBatch => message.header_as_dictionary_batch().and_then(|d| d.data()),
        _ => None,
    }?;
    if batch.compression().is_some() {
        return Some("an Arrow IPC record batch declares compressed buffers, which Rerun does not write".into());
    }
    batch.buffers()?.iter().find_map(|buffer| {
        let end = buffer.offset().checked_add(buffer.length());
        let inside = buffer.offset() >= 0 && buffer.length() >= 0 && end.is_some_and(|end| end <= body);
        (!inside).then(|| {
            format!("an Arrow IPC buffer claims bytes {} + {} of a body of {body}", buffer.offset(), buffer.length())
        })
    })
}
