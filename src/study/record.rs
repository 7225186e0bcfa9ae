//! A member's record, `<member>.done.toml`, and what a study trusts of it.
//!
//! A record says what ran and how it ended, and carries digests: of what makes the member (its
//! case as resolved, the slipfront version, the study's stop rules and whether it records), of
//! each of its output files, and of the record itself. A member counts as done only while all of
//! them verify: a record edited by hand, outputs deleted or changed, or a study file edited since
//! (other parameters) make it a member to run again. Counts and verdicts are never taken from a
//! record: the summary reads them from the member's catalogs ([`crate::study::summary`]).

use std::io::Read;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use xxhash_rust::xxh32::Xxh32;

use crate::record::schema::recording_id;
use crate::study::spec::{Member, Study};

/// The suffix of a member's record.
pub const DONE: &str = ".done.toml";
/// The suffixes of the outputs a member may write.
pub const OUTPUTS: [&str; 3] = [".events.csv", ".ruptures.csv", ".rrd"];
/// The largest record read (bytes).
pub const MAX_RECORD_BYTES: u64 = 1 << 20;
/// Seed of every digest of a record.
const SEED: u32 = 0x51f0_0d0e;

/// What a member leaves as `<name>.done.toml`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MemberRecord {
    pub index: usize,
    pub row: usize,
    pub k: usize,
    /// The varying keys and their values (TOML text), in the study's order.
    pub parameters: Vec<(String, String)>,
    /// The digest of what makes the member ([`identity`]).
    pub identity: String,
    /// `completed`, `failed`, or `stopped` and why, by a stop rule (an interrupted member has
    /// no record).
    pub ending: String,
    /// Why the run failed, if it did.
    pub error: Option<String>,
    /// Contact segments of its scene.
    pub segments: usize,
    /// `1/R*` at the onset of each slip event, in the order of its events catalog (whose CSV
    /// does not hold it), for the paper's verdicts; NaN where the run did not give it.
    pub onset_structure: Vec<f64>,
    /// Each output file (its name in the study's folder) and the digest of its bytes
    /// ([`file_digest`]).
    pub outputs: Vec<(String, String)>,
    /// The digest of the record's own values, this one left empty ([`MemberRecord::sealed`]).
    pub digest: String,
}

impl MemberRecord {
    /// The record with its [`MemberRecord::digest`] set.
    pub fn sealed(mut self) -> Result<Self, String> {
        self.digest = self.own_digest()?;
        Ok(self)
    }

    /// The digest of the record's values, with `digest` empty.
    fn own_digest(&self) -> Result<String, String> {
        let text = toml::to_string(&Self { digest: String::new(), ..self.clone() }).map_err(|e| e.to_string())?;
        Ok(format!("{:08x}", xxhash_rust::xxh32::xxh32(text.as_bytes(), SEED)))
    }

    pub fn failed(&self) -> bool {
        self.ending == "failed"
    }
}

/// Where a member of a study stands in its folder.
#[derive(Debug, Clone, PartialEq)]
pub enum Standing {
    /// Its record and outputs verify, and its run completed or was stopped by a rule.
    Finished(MemberRecord),
    /// Its record and outputs verify, and its run failed.
    Failed(MemberRecord),
    /// No record: never run, or interrupted.
    NotRun,
    /// The record of a member with other parameters (the study file was edited since).
    Stale,
    /// A record, or outputs, that do not verify, and why.
    Unverified(String),
}

/// The digest of what makes `member` of `study`: its recording id (its case as resolved and
/// the slipfront version, [`recording_id`]), the study's stop rules, and whether it records.
pub fn identity(study: &Study, member: &Member) -> String {
    let run = recording_id(&run_name(study, member), &member.case);
    let text = format!("{run} {:?} recordings = {}", study.stop, study.recordings);
    format!("{:08x}", xxhash_rust::xxh32::xxh32(text.as_bytes(), SEED))
}

/// The name a member's recording is given: `<study>-<member>`.
pub fn run_name(study: &Study, member: &Member) -> String {
    format!("{}-{}", study.name, member.name)
}

/// The path of a member's output or record in `dir`.
pub fn output(dir: &Path, member: &str, suffix: &str) -> PathBuf {
    dir.join(format!("{member}{suffix}"))
}

/// Where `member` stands in `dir` ([`Standing`]).
pub fn standing(dir: &Path, study: &Study, member: &Member) -> Standing {
    let path = output(dir, &member.name, DONE);
    if std::fs::symlink_metadata(&path).is_err() {
        return Standing::NotRun;
    }
    match verify(dir, study, member, &path) {
        Ok(Some(record)) if record.failed() => Standing::Failed(record),
        Ok(Some(record)) => Standing::Finished(record),
        Ok(None) => Standing::Stale,
        Err(why) => Standing::Unverified(why),
    }
}

/// The record at `path`, if it verifies ([`Standing`]); `None` if it is another member's.
fn verify(dir: &Path, study: &Study, member: &Member, path: &Path) -> Result<Option<MemberRecord>, String> {
    let text = crate::files::read_text_capped(path, MAX_RECORD_BYTES, "a member record is a few lines of TOML")?;
    let record: MemberRecord =
        toml::from_str(&text).map_err(|e| format!("{} is not a member record ({})", path.display(), e.message()))?;
    if record.own_digest()? != record.digest {
        return Err(format!("{} was changed after its member ran (its digest does not match)", path.display()));
    }
    if record.identity != identity(study, member)
        || (record.index, record.row, record.k) != (member.index, member.row, member.k)
    {
        return Ok(None);
    }
    let allowed: Vec<String> = OUTPUTS.iter().map(|suffix| format!("{}{suffix}", member.name)).collect();
    if !record.failed() && !record.outputs.iter().any(|(name, _)| *name == allowed[0]) {
        return Err(format!("{} names no events catalog", path.display()));
    }
    for (name, digest) in &record.outputs {
        if !allowed.contains(name) {
            return Err(format!("{} names {name}, which is not one of the member's outputs", path.display()));
        }
        let file = dir.join(name);
        match file_digest(&file) {
            Ok(found) if found == *digest => {}
            Ok(_) => {
                return Err(format!("{} is not the file its member's run wrote (its digest differs)", file.display()));
            }
            Err(e) => return Err(e),
        }
    }
    Ok(Some(record))
}

/// The digest of a file's bytes: `xxh32` over its length (u64, little-endian) and its bytes,
/// as 8 hexadecimal digits. The file is streamed, never held whole.
pub fn file_digest(path: &Path) -> Result<String, String> {
    let (mut file, len) = crate::files::open_regular(path, "a member's output is a file its run wrote")?;
    let mut digest = Xxh32::new(SEED);
    digest.update(&len.to_le_bytes());
    let mut buffer = vec![0u8; 1 << 16];
    loop {
        let n = file.read(&mut buffer).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        if n == 0 {
            break;
        }
        digest.update(&buffer[..n]);
    }
    Ok(format!("{:08x}", digest.digest()))
}
