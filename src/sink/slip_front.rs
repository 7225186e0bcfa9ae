//! The slip front, scrubbable: where along the surface it slips, and when.
//!
//! * `contact/state`: a `StateChange` lane per recorded segment (`stick` or `slip`, the event
//!   threshold on the slip rate), written only where a segment changes state, so a rupture
//!   reads as lanes switching one after another.
//! * `profile/*`: bar charts over the segments' centres (arc length along the contact in m, the
//!   block's x) at every recorded step, one set per contact (`profile/{contact}/*` where the
//!   body has several), so the playhead shows the profile along each contact: tangential traction `f_t` between the static
//!   strength `μ_k f_n / R*` (the superloading surface) and the kinetic strength `μ_k f_n` (the
//!   normal sliding-yield surface), the slip rate on a log scale ([`slip_rate_decades`]), and
//!   the degree of structure `1/R*`. The
//!   current strength `(R/R*) μ_k f_n` (the subloading surface) is `|f_t|` itself: the surface
//!   passes through the current traction ([model](../../docs/model.md#surfaces-and-state)).

use rerun::datatypes::TensorData;
use rerun::{BarChart, RecordingStream, StateChange, StateConfiguration, TimeColumn};

use crate::frame::{Frame, Layout};
use crate::record::schema;

/// The profiles (the last part of their entity paths, [`schema::profile_entity`]), what each
/// shows of a segment, and its bars' colour and relative width: the strengths wide and pale
/// behind the traction.
const PROFILES: [(&str, Profile, [u8; 4], f32); 5] = [
    ("static_strength", Profile::StaticStrength, [190, 190, 190, 255], 0.9),
    ("kinetic_strength", Profile::KineticStrength, [120, 160, 210, 255], 0.7),
    ("traction_t", Profile::Traction, [230, 120, 40, 255], 0.4),
    ("slip_rate", Profile::SlipRate, [220, 60, 60, 255], 0.8),
    ("structure", Profile::Structure, [90, 170, 110, 255], 0.8),
];

#[derive(Debug, Clone, Copy)]
enum Profile {
    StaticStrength,
    KineticStrength,
    Traction,
    SlipRate,
    Structure,
}

/// The colour of an open segment, in the lanes and the block view: grey, neither stick's blue
/// nor slip's orange.
pub const OPEN_COLOUR: u32 = 0xA0A0A0FF;

/// The state lanes and profiles of a run, buffered between flushes.
pub struct SlipFront {
    threshold: f64,
    mu_k: Option<f64>,
    /// The recorded segments (the lanes).
    segments: Vec<usize>,
    /// Each contact's name (where the body has several) and segments.
    contacts: Vec<(Option<String>, std::ops::Range<usize>)>,
    /// Whether the profiles are written (bodies of more than one segment).
    profiles: bool,
    /// Whether a segment can be open (a contact's normal traction evolves).
    opens: bool,
    last_state: Option<Vec<&'static str>>,
    state_steps: Vec<i64>,
    state_times: Vec<f64>,
    states: Vec<&'static str>,
    /// One tensor per row, per contact and profile (`bars[contact][profile]`).
    bars: Vec<Vec<Vec<TensorData>>>,
}

impl SlipFront {
    /// The slip front of a run over `layout` recording `segments`; `mu_k` scales the strength
    /// profiles (without it only the traction, slip rate and structure profiles are written).
    pub fn new(layout: &Layout, segments: &[usize], threshold: f64, mu_k: Option<f64>) -> Self {
        Self {
            threshold,
            mu_k,
            segments: segments.to_vec(),
            contacts: contacts(layout),
            profiles: layout.kind.has_body() && layout.segments.len() > 1,
            opens: layout.evolving_normal,
            last_state: None,
            state_steps: Vec::new(),
            state_times: Vec::new(),
            states: Vec::new(),
            bars: vec![vec![Vec::new(); PROFILES.len()]; layout.contact_ranges().len()],
        }
    }

    /// Whether the profiles need the full segment state (`f_n`, `R`, `R*`).
    pub fn needs_state(&self) -> bool {
        self.profiles
    }

    /// The profile entities this run writes, contact by contact.
    pub fn profile_entities(&self) -> Vec<String> {
        self.contacts
            .iter()
            .flat_map(|(contact, _)| {
                PROFILES.iter().filter(|p| self.writes(p.1)).map(|p| schema::profile_entity(contact.as_deref(), p.0))
            })
            .collect()
    }

    fn writes(&self, profile: Profile) -> bool {
        self.profiles && (self.mu_k.is_some() || !matches!(profile, Profile::StaticStrength | Profile::KineticStrength))
    }

    /// Logs the static parts: the lanes' states and colours, the bars' positions and widths.
    pub fn begin(&self, rec: &RecordingStream, layout: &Layout) -> rerun::RecordingStreamResult<()> {
        let states = if self.opens {
            StateConfiguration::new()
                .with_values([schema::STICK, schema::SLIP, schema::OPEN])
                .with_labels([" ", "slip", "open"])
                .with_colors([0x4682C8FF_u32, 0xF0782AFF_u32, OPEN_COLOUR])
        } else {
            StateConfiguration::new()
                .with_values([schema::STICK, schema::SLIP])
                .with_labels([" ", "slip"])
                .with_colors([0x4682C8FF_u32, 0xF0782AFF_u32])
        };
        rec.log_static(schema::CONTACT_STATE, &states)?;
        if !self.profiles {
            return Ok(());
        }
        for (contact, range) in &self.contacts {
            let segments = &layout.segments[range.clone()];
            let centres: Vec<f64> = segments.iter().map(|s| 0.5 * (s.left + s.right)).collect();
            for (quantity, profile, [r, g, b, a], share) in PROFILES {
                if !self.writes(profile) {
                    continue;
                }
                let widths: Vec<f32> = segments.iter().map(|s| (share as f64 * (s.right - s.left)) as f32).collect();
                rec.log_static(
                    schema::profile_entity(contact.as_deref(), quantity),
                    &BarChart::update_fields()
                        .with_abscissa(TensorData::from(centres.clone()))
                        .with_widths(widths)
                        .with_color(rerun::Color::from_unmultiplied_rgba(r, g, b, a)),
                )?;
            }
        }
        Ok(())
    }

    /// Adds a recorded frame: a state row where a segment changed.
    pub fn push_state(&mut self, frame: &Frame) {
        let state: Vec<&'static str> = self
            .segments
            .iter()
            .map(|&k| {
                let s = &frame.segments[k];
                if s.open {
                    schema::OPEN
                } else if s.slip_rate > self.threshold {
                    schema::SLIP
                } else {
                    schema::STICK
                }
            })
            .collect();
        if self.last_state.as_ref() != Some(&state) {
            self.state_steps.push(frame.step as i64);
            self.state_times.push(frame.time);
            self.states.extend(state.iter().copied());
            self.last_state = Some(state);
        }
    }

    /// Which lanes slipped at the last recorded frame, for a checkpoint (an open lane counts
    /// as not slipping: a resumed run writes its state again).
    pub fn memory(&self) -> Option<Vec<bool>> {
        self.last_state.as_ref().map(|s| s.iter().map(|&s| s == schema::SLIP).collect())
    }

    /// Continues from [`Self::memory`].
    pub fn resume(&mut self, last_state: Option<Vec<bool>>) {
        self.last_state =
            last_state.map(|s| s.into_iter().map(|slip| if slip { schema::SLIP } else { schema::STICK }).collect());
    }

    /// Adds a view frame's profiles.
    pub fn push_profiles(&mut self, frame: &Frame) {
        if !self.profiles {
            return;
        }
        for (c, (_, range)) in self.contacts.iter().enumerate() {
            for (i, (_, profile, _, _)) in PROFILES.iter().enumerate() {
                if self.writes(*profile) {
                    let values: Vec<f32> = frame.segments[range.clone()]
                        .iter()
                        .map(|s| value(*profile, s, self.mu_k, self.threshold) as f32)
                        .collect();
                    self.bars[c][i].push(TensorData::from(values));
                }
            }
        }
    }

    /// Drops the buffered rows, sending nothing (a measuring build's hand-over,
    /// [`crate::sink::WITHOUT_RERUN`]).
    pub fn discard(&mut self) {
        self.bars.iter_mut().flatten().for_each(Vec::clear);
        self.state_steps.clear();
        self.state_times.clear();
        self.states.clear();
    }

    /// Sends the buffered rows: the profiles on the view frames' `times`, the state rows on
    /// their own.
    pub fn send(&mut self, rec: &RecordingStream, times: &[TimeColumn; 2]) -> Result<(), String> {
        let error = |e: &dyn std::fmt::Display| e.to_string();
        for (c, (contact, _)) in self.contacts.iter().enumerate() {
            for (i, (quantity, _, _, _)) in PROFILES.iter().enumerate() {
                let rows = std::mem::take(&mut self.bars[c][i]);
                if rows.is_empty() {
                    continue;
                }
                let columns = BarChart::update_fields()
                    .with_many_values(rows)
                    .columns_of_unit_batches()
                    .map_err(|e| error(&e))?;
                let entity = schema::profile_entity(contact.as_deref(), quantity);
                rec.send_columns(entity, times.clone(), columns).map_err(|e| error(&e))?;
            }
        }
        if self.state_steps.is_empty() {
            return Ok(());
        }
        let rows = self.state_steps.len();
        let state_times = [
            TimeColumn::new_sequence(schema::STEP, std::mem::take(&mut self.state_steps)),
            TimeColumn::new_duration_secs(schema::SIM_TIME, std::mem::take(&mut self.state_times)),
        ];
        let columns = StateChange::update_fields()
            .with_state(std::mem::take(&mut self.states))
            .columns(std::iter::repeat_n(self.segments.len(), rows))
            .map_err(|e| error(&e))?;
        rec.send_columns(schema::CONTACT_STATE, state_times, columns).map_err(|e| error(&e))?;
        Ok(())
    }
}

/// Each contact's name where the layout has several, and its segments.
fn contacts(layout: &Layout) -> Vec<(Option<String>, std::ops::Range<usize>)> {
    let several = layout.contacts.len() > 1;
    layout.contact_ranges().into_iter().map(|(name, segments, _)| (several.then_some(name), segments)).collect()
}

/// A segment's value in `profile`; the strengths are the superloading surface `μ_k f_n / R*`
/// and the normal sliding-yield surface `μ_k f_n`; the slip rate in decades above
/// [`slip_rate_floor`] ([`slip_rate_decades`]).
fn value(profile: Profile, s: &crate::frame::SegmentSample, mu_k: Option<f64>, threshold: f64) -> f64 {
    let kinetic_strength = mu_k.unwrap_or(f64::NAN) * s.traction_n;
    match profile {
        Profile::StaticStrength => kinetic_strength * s.structure,
        Profile::KineticStrength => kinetic_strength,
        Profile::Traction => s.traction_t,
        Profile::SlipRate => slip_rate_decades(s.slip_rate, threshold),
        Profile::Structure => s.structure,
    }
}

/// The slip rate (m/s) the slip-rate profile counts its decades from: a hundredth of the event
/// threshold, as the space-time map's floor.
pub fn slip_rate_floor(threshold: f64) -> f64 {
    threshold / 100.0
}

/// `log10(v / floor)` of a slip rate `v`, 0 at or below the floor ([`slip_rate_floor`]): a
/// segment in stick has no bar, one at the event threshold a bar of 2, one sliding 100 times
/// faster a bar of 4, so that every slipping segment shows, however its rate compares.
pub fn slip_rate_decades(rate: f64, threshold: f64) -> f64 {
    let floor = slip_rate_floor(threshold);
    if rate > floor { (rate / floor).log10() } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_slip_rate_profile_counts_decades_above_a_hundredth_of_the_threshold() {
        let threshold = 3.0e-3;
        assert_eq!(slip_rate_decades(1.0e-9, threshold), 0.0, "stick: no bar");
        assert_eq!(slip_rate_decades(-1.0, threshold), 0.0, "a backward rate: no bar");
        assert!((slip_rate_decades(threshold, threshold) - 2.0).abs() < 1e-12, "the threshold: 2");
        assert!((slip_rate_decades(0.3, threshold) - 4.0).abs() < 1e-12, "100 times the threshold: 4");
    }
}
