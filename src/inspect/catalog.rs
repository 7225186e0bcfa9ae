//! The event catalogs read back (`<stem>.events.csv`, `<stem>.ruptures.csv`, as
//! [`crate::sink::catalog`] writes them), for a study's summary. Numbers are written in Rust's
//! shortest round-trip form, so every value read is the value written.

use std::str::FromStr;

use crate::catalog::events::{Rupture, SlipEvent};
use crate::sink::catalog::{EVENTS_HEADER, RUPTURES_HEADER, RUPTURES_HEADER_RING};

/// The slip events of an events CSV; `name` stands for the file in messages. The CSV does not
/// hold the friction force or `1/R*` at the onset: those are NaN and `None`.
pub fn events(text: &str, name: &str) -> Result<Vec<SlipEvent>, String> {
    rows(text, name, EVENTS_HEADER)?
        .map(|(line, fields)| {
            let value = |i: usize| number::<f64>(fields[i], name, line);
            Ok(SlipEvent {
                segment: number::<usize>(fields[0], name, line)?,
                onset: value(1)?,
                end: value(2)?,
                slip: value(3)?,
                peak_slip_rate: value(4)?,
                traction_before: value(5)?,
                traction_after: value(6)?,
                friction_force_before: f64::NAN,
                friction_force_after: f64::NAN,
                structure_before: None,
            })
        })
        .collect()
}

/// The ruptures of a ruptures CSV (of a plane body, force drops in N/m, or of a ring, in N);
/// `name` stands for the file in messages.
pub fn ruptures(text: &str, name: &str) -> Result<Vec<Rupture>, String> {
    let ring = text.lines().next() == Some(RUPTURES_HEADER_RING);
    let header = if ring { RUPTURES_HEADER_RING } else { RUPTURES_HEADER };
    rows(text, name, header)?
        .map(|(line, fields)| {
            let index = |i: usize| number::<usize>(fields[i], name, line);
            let value = |i: usize| number::<f64>(fields[i], name, line);
            Ok(Rupture {
                onset: value(0)?,
                end: value(1)?,
                nucleation_segment: index(2)?,
                first_segment: index(3)?,
                last_segment: index(4)?,
                segments_slipped: index(5)?,
                max_slip: value(6)?,
                friction_force_drop: value(7)?,
            })
        })
        .collect()
}

/// The data lines of a catalog with `header`, numbered from 2, split into as many fields as
/// the header has.
fn rows<'t>(
    text: &'t str,
    name: &str,
    header: &str,
) -> Result<impl Iterator<Item = (usize, Vec<&'t str>)> + use<'t>, String> {
    let mut lines = text.lines();
    if lines.next() != Some(header) {
        return Err(format!("{name} does not start with the catalog's header ({header})"));
    }
    let columns = header.split(',').count();
    let rows: Vec<(usize, Vec<&str>)> = lines
        .enumerate()
        .filter(|(_, line)| !line.is_empty())
        .map(|(i, line)| (i + 2, line.split(',').collect::<Vec<_>>()))
        .collect();
    if let Some((line, fields)) = rows.iter().find(|(_, fields)| fields.len() != columns) {
        return Err(format!("{name}, line {line}: {} fields where the header has {columns}", fields.len()));
    }
    Ok(rows.into_iter())
}

fn number<T: FromStr>(field: &str, name: &str, line: usize) -> Result<T, String> {
    field.parse().map_err(|_| format!("{name}, line {line}: {field:?} is not a number"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sink::catalog::{events_csv, ruptures_csv};

    #[test]
    fn a_catalog_reads_back_as_written() {
        let event = SlipEvent {
            segment: 3,
            onset: 420.123456789,
            end: 421.5,
            slip: 1.25e-7,
            peak_slip_rate: 3.0e-3,
            traction_before: 399.99999999999994,
            traction_after: -12.5,
            friction_force_before: f64::NAN,
            friction_force_after: f64::NAN,
            structure_before: None,
        };
        let read = events(&events_csv(&[event]), "e.csv").unwrap();
        assert_eq!(read.len(), 1);
        let r = read[0];
        assert_eq!(
            (r.segment, r.onset, r.end, r.slip, r.peak_slip_rate, r.traction_before, r.traction_after),
            (3, 420.123456789, 421.5, 1.25e-7, 3.0e-3, 399.99999999999994, -12.5)
        );
        let rupture = Rupture {
            onset: 1.0,
            end: 2.0,
            nucleation_segment: 0,
            first_segment: 0,
            last_segment: 9,
            segments_slipped: 10,
            max_slip: 1e-6,
            friction_force_drop: 12.0,
        };
        assert_eq!(ruptures(&ruptures_csv(std::slice::from_ref(&rupture)), "r.csv").unwrap(), vec![rupture.clone()]);
        // A ring's header ends in `_n`, a prefix of the plane body's `_n_per_m`: both read back.
        let ring = crate::sink::catalog::ruptures_csv_in(std::slice::from_ref(&rupture), true);
        assert!(ring.starts_with(crate::sink::catalog::RUPTURES_HEADER_RING));
        assert_eq!(ruptures(&ring, "r.csv").unwrap(), vec![rupture]);
        assert!(events("segment\n", "e.csv").unwrap_err().contains("does not start with the catalog's header"));
        let short = format!("{EVENTS_HEADER}\n1,2\n");
        assert_eq!(events(&short, "e.csv").unwrap_err(), "e.csv, line 2: 2 fields where the header has 7");
        let word = format!("{EVENTS_HEADER}\n1,x,3,4,5,6,7\n");
        assert_eq!(events(&word, "e.csv").unwrap_err(), "e.csv, line 2: \"x\" is not a number");
    }
}
