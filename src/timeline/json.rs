//! `timeline.json`: the tiles, the speed law, and every event as `[time, "kind", index]`,
//! one event a line.
//!
//! ```text
//! {"tiles":3,"speed_law":"unit","index":"...","events":[
//! [0.0,"ri_contact",0],
//! [0.0,"magnet_starts",0]
//! ]}
//! ```

use std::io;

use serde::Serialize;
use serde_json::ser::{CompactFormatter, Formatter};

use crate::timeline::Event;

/// How the events index the chain, written into every timeline.
pub(crate) const EVENT_INDEX: &str =
    "magnet k is magnet k mod 2 of tile k/2; joint events index the joint";

/// A timeline as its JSON writes it; `L` is the speed law's form.
#[derive(Clone, Debug, Serialize)]
pub struct TimelineJson<'a, L: Serialize> {
    /// Number of tiles.
    pub tiles: usize,
    /// The law the times are in.
    pub speed_law: L,
    /// Every event of the run, when fewer are written (else absent).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub events_total: Option<usize>,
    /// Whether fewer events are written than the run has (absent when not counted).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub truncated: Option<bool>,
    /// [`EVENT_INDEX`].
    pub index: &'static str,
    /// The events, in time order.
    pub events: &'a [Event],
}

impl<L: Serialize> TimelineJson<'_, L> {
    /// The JSON text, one event a line, ending with a newline.
    pub fn to_json(&self) -> String {
        let mut out = Vec::with_capacity(40 * self.events.len() + 200);
        let mut ser = serde_json::Serializer::with_formatter(&mut out, EventPerLine::default());
        if self.serialize(&mut ser).is_err() {
            // writing into memory the types above cannot fail
            return String::new();
        }
        out.push(b'\n');
        String::from_utf8(out).unwrap_or_default()
    }
}

/// Compact JSON with a line break before each item of the arrays one level inside the
/// top-level object (the events).
#[derive(Default)]
struct EventPerLine {
    depth: usize,
}

impl Formatter for EventPerLine {
    fn begin_object<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.depth += 1;
        CompactFormatter.begin_object(w)
    }

    fn end_object<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.depth -= 1;
        CompactFormatter.end_object(w)
    }

    fn begin_array<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.depth += 1;
        CompactFormatter.begin_array(w)
    }

    fn end_array<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.depth -= 1;
        if self.depth == 1 {
            w.write_all(b"\n")?;
        }
        CompactFormatter.end_array(w)
    }

    fn begin_array_value<W: ?Sized + io::Write>(
        &mut self,
        w: &mut W,
        first: bool,
    ) -> io::Result<()> {
        if self.depth == 2 {
            w.write_all(if first { b"\n" } else { b",\n" })
        } else {
            CompactFormatter.begin_array_value(w, first)
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::timeline::{EventKind, SpeedLaw};

    #[test]
    fn one_event_a_line_and_valid_json() {
        let events = [
            Event {
                time: 0.0,
                index: 0,
                kind: EventKind::RiContact,
            },
            Event {
                time: 1.5e-7,
                index: 3,
                kind: EventKind::FoldStarts,
            },
        ];
        let text = TimelineJson {
            tiles: 3,
            speed_law: SpeedLaw::default(),
            events_total: Some(2),
            truncated: Some(false),
            index: EVENT_INDEX,
            events: &events,
        }
        .to_json();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 4, "{text}");
        assert_eq!(lines[1], r#"[0.0,"ri_contact",0],"#);
        assert_eq!(lines[2], r#"[1.5e-7,"fold_starts",3]"#);
        assert_eq!(lines[3], "]}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["speed_law"]["overdamped"]["drag"], 5.0);
        assert_eq!(v["events_total"], 2);
        assert_eq!(v["events"][1][0], 1.5e-7);
        // the optional counts are left out when not given
        let text = TimelineJson {
            tiles: 3,
            speed_law: "law",
            events_total: None,
            truncated: None,
            index: EVENT_INDEX,
            events: &[],
        }
        .to_json();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v.as_object().unwrap().len(), 4, "{text}");
        assert_eq!(v["events"], serde_json::json!([]));
    }
}
