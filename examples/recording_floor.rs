//! What Rerun alone costs to write a recording: reads every chunk of a `.rrd` that slipfront
//! wrote into memory and, unless `--decode-only`, sends them all again, unchanged, through a
//! recording stream into a new file, the way slipfront's sinks hand their columns to Rerun
//! (`send_chunk`, the file encoded with LZ4 as slipfront's are).
//!
//! The CPU time of a run with the second path over one with `--decode-only` is Rerun's share of
//! writing that recording (Arrow IPC, LZ4, the file), with none of slipfront's work in it: the
//! floor under what the recording can add to a run that records the same rows.
//!
//! cargo run --release --example recording_floor -- IN.rrd OUT.rrd
//! cargo run --release --example recording_floor -- IN.rrd --decode-only
//! cargo run --release --example recording_floor -- IN.rrd --entities   (rows and bytes by entity)

use std::fs::File;
use std::io::BufReader;

use rerun::external::re_log_encoding::DecoderApp;
use rerun::log::{Chunk, LogMsg};

fn main() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let (Some(input), Some(output)) = (args.next(), args.next()) else {
        return Err("usage: recording_floor IN.rrd (OUT.rrd | --decode-only | --entities)".into());
    };
    let file = File::open(&input).map_err(|e| format!("{input}: {e}"))?;
    let decoder = DecoderApp::decode_eager(BufReader::new(file)).map_err(|e| format!("{input}: {e}"))?;
    let mut chunks = Vec::new();
    let mut recording = None;
    for message in decoder {
        let message = match message {
            Ok(message) => message,
            Err(e) if chunks.is_empty() => return Err(format!("{input}: not a readable recording ({e})")),
            Err(e) => {
                eprintln!("{input}: read up to damaged data ({e}); measuring the {} chunks before it", chunks.len());
                break;
            }
        };
        let LogMsg::ArrowMsg(store, arrow) = message else { continue };
        if store.is_blueprint() {
            continue;
        }
        recording.get_or_insert(store);
        chunks.push(Chunk::from_arrow_msg(&arrow).map_err(|e| format!("{input}: {e}"))?);
    }
    if chunks.is_empty() {
        return Err(format!("{input}: holds no recorded chunks (not a recording, or damaged from its start)"));
    }
    let rows: usize = chunks.iter().map(Chunk::num_rows).sum();
    match output.as_str() {
        "--decode-only" => {
            println!("{} chunks, {rows} rows decoded", chunks.len());
            return Ok(());
        }
        "--entities" => {
            print_entities(&chunks);
            return Ok(());
        }
        _ => {}
    }
    let store = recording.ok_or_else(|| format!("{input} holds no recording"))?;
    let rec = rerun::RecordingStreamBuilder::from_store_id(&store)
        .send_properties(false)
        .save(&output)
        .map_err(|e| format!("{output}: {e}"))?;
    let count = chunks.len();
    for chunk in chunks {
        rec.send_chunk(chunk);
    }
    rec.flush_blocking().map_err(|e| format!("{output}: {e}"))?;
    drop(rec);
    println!("{count} chunks, {rows} rows written to {output}");
    Ok(())
}

/// Each entity's rows and the bytes of its decoded chunks, largest first.
fn print_entities(chunks: &[Chunk]) {
    use rerun::external::re_byte_size::SizeBytes as _;
    let mut by_entity = std::collections::BTreeMap::<String, (usize, u64)>::new();
    for chunk in chunks {
        let entry = by_entity.entry(chunk.entity_path().to_string()).or_default();
        entry.0 += chunk.num_rows();
        entry.1 += chunk.heap_size_bytes();
    }
    let total: u64 = by_entity.values().map(|(_, bytes)| bytes).sum();
    let mut rows: Vec<_> = by_entity.into_iter().collect();
    rows.sort_by_key(|(_, (_, bytes))| std::cmp::Reverse(*bytes));
    println!("{:<32} {:>8} {:>10} {:>6}", "entity", "rows", "bytes", "share");
    for (entity, (count, bytes)) in rows {
        println!("{entity:<32} {count:>8} {bytes:>10} {:>5.1}%", 100.0 * bytes as f64 / total as f64);
    }
    println!("{:<32} {:>8} {total:>10}", "all", "");
}
