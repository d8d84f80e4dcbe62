//! Manufacturing tolerances: how far each printed dimension and each magnet may differ from
//! its design, tile by tile, with presets for the two common printers.
//!
//! Each tile's parameters are drawn independently and uniformly within `nominal +- tol`: a
//! tolerance is read as the limit a part stays within, and the uniform draw puts as much
//! weight at the limits as in the middle (harsher than a normal law with the same limits).
//!
//! Sources of the defaults (estimates, not measurements of this project's parts):
//! - FDM printers (0.4 mm nozzle) hold about +-0.1 mm on small features and hole positions;
//!   resin (SLA/MSLA) printers about +-0.05 mm (printer makers' stated accuracies and
//!   calibration-print surveys; the issue's "printers hold 0.05-0.2 mm").
//! - Sintered NdFeB: remanence within about +-2-3% of its grade's nominal value (an N42 is
//!   sold as 1.28-1.32 T, +-1.5%, batches spread further); a relative +-2.5% is the default.
//! - Magnet dimensions: +-0.05 mm (the usual catalogue tolerance of small NdFeB cylinders is
//!   +-0.05 to +-0.1 mm).

use std::fmt;

/// The design parameter a tolerance applies to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Parameter {
    /// `s`, mm: where a magnet's rest point (the inner end of its path) is printed.
    S,
    /// `e`, mm: where a straight path's outer end is printed.
    E,
    /// The wall in front of a curved path's final point, mm (its final point).
    Wall,
    /// The tile's width, mm; `d = w/2` follows it (the design keeps the magnet track
    /// centred in the tile, `d <= w/2`).
    Width,
    /// Magnet remanence, relative (0.025 = +-2.5%).
    Br,
    /// Magnet diameter, mm.
    Diameter,
    /// Magnet height, mm.
    Height,
}

impl Parameter {
    /// Every parameter, in the order samples draw them.
    pub const ALL: [Parameter; 7] = [
        Parameter::S,
        Parameter::E,
        Parameter::Wall,
        Parameter::Width,
        Parameter::Br,
        Parameter::Diameter,
        Parameter::Height,
    ];

    /// The key on the command line.
    pub fn key(self) -> &'static str {
        match self {
            Parameter::S => "s",
            Parameter::E => "e",
            Parameter::Wall => "wall",
            Parameter::Width => "width",
            Parameter::Br => "br",
            Parameter::Diameter => "diameter",
            Parameter::Height => "height",
        }
    }

    /// The unit of a tolerance and of a sensitivity's denominator.
    pub fn unit(self) -> &'static str {
        match self {
            Parameter::Br => "relative",
            _ => "mm",
        }
    }
}

impl fmt::Display for Parameter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}

/// A printer whose tolerances are the defaults of the printed dimensions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Printer {
    /// Fused deposition: +-0.1 mm.
    Fdm,
    /// Resin: +-0.05 mm.
    Resin,
}

impl Printer {
    /// The tolerance of a printed dimension, mm.
    pub fn tolerance(self) -> f64 {
        match self {
            Printer::Fdm => 0.1,
            Printer::Resin => 0.05,
        }
    }
}

/// A tolerance that could not be read.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ToleranceError {
    /// Not `KEY=VALUE`.
    #[error("tolerance '{text}': expected KEY=VALUE, e.g. s=0.05 or br=2.5%")]
    Form {
        /// The text given.
        text: String,
    },
    /// An unknown key.
    #[error("tolerance '{text}': unknown key '{key}' (expected one of s, e, wall, width, d, br, diameter, height)")]
    Key {
        /// The text given.
        text: String,
        /// The key.
        key: String,
    },
    /// A value that is not a finite number >= 0 in range.
    #[error("tolerance '{text}': bad value '{value}': expected {expected}")]
    Value {
        /// The text given.
        text: String,
        /// The value.
        value: String,
        /// What was expected.
        expected: &'static str,
    },
}

/// The tolerance of every parameter: `nominal +- tol`, uniform, per tile.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Tolerances {
    /// `s`, mm.
    pub s: f64,
    /// `e`, mm.
    pub e: f64,
    /// The curved paths' wall, mm.
    pub wall: f64,
    /// Tile width, mm.
    pub width: f64,
    /// Remanence, relative.
    pub br: f64,
    /// Magnet diameter, mm.
    pub diameter: f64,
    /// Magnet height, mm.
    pub height: f64,
}

impl Default for Tolerances {
    /// An FDM printer and catalogue magnets.
    fn default() -> Tolerances {
        Tolerances::printed(Printer::Fdm)
    }
}

impl Tolerances {
    /// Printed dimensions at `printer`'s tolerance; remanence +-2.5%, magnet dimensions
    /// +-0.05 mm (see the module documentation for the sources).
    pub fn printed(printer: Printer) -> Tolerances {
        let t = printer.tolerance();
        Tolerances {
            s: t,
            e: t,
            wall: t,
            width: t,
            br: 0.025,
            diameter: 0.05,
            height: 0.05,
        }
    }

    /// No variation at all.
    pub fn none() -> Tolerances {
        Tolerances {
            s: 0.0,
            e: 0.0,
            wall: 0.0,
            width: 0.0,
            br: 0.0,
            diameter: 0.0,
            height: 0.0,
        }
    }

    /// The tolerance of `p`.
    pub fn get(&self, p: Parameter) -> f64 {
        match p {
            Parameter::S => self.s,
            Parameter::E => self.e,
            Parameter::Wall => self.wall,
            Parameter::Width => self.width,
            Parameter::Br => self.br,
            Parameter::Diameter => self.diameter,
            Parameter::Height => self.height,
        }
    }

    fn slot(&mut self, p: Parameter) -> &mut f64 {
        match p {
            Parameter::S => &mut self.s,
            Parameter::E => &mut self.e,
            Parameter::Wall => &mut self.wall,
            Parameter::Width => &mut self.width,
            Parameter::Br => &mut self.br,
            Parameter::Diameter => &mut self.diameter,
            Parameter::Height => &mut self.height,
        }
    }

    /// Sets one tolerance from `KEY=VALUE`: lengths in mm (`s=0.05`, `s=0.05mm`), the
    /// remanence relative or in per cent (`br=0.02`, `br=2%`); `d=X` is `width=2X` (d = w/2).
    pub fn set(&mut self, text: &str) -> Result<(), ToleranceError> {
        let (key, value) = text.split_once('=').ok_or_else(|| ToleranceError::Form {
            text: text.to_string(),
        })?;
        let (key, value) = (key.trim().to_ascii_lowercase(), value.trim());
        let (param, factor) = match key.as_str() {
            "d" => (Parameter::Width, 2.0),
            k => match Parameter::ALL.iter().find(|p| p.key() == k) {
                Some(&p) => (p, 1.0),
                None => {
                    return Err(ToleranceError::Key {
                        text: text.to_string(),
                        key,
                    })
                }
            },
        };
        let bad = |expected| ToleranceError::Value {
            text: text.to_string(),
            value: value.to_string(),
            expected,
        };
        let v = if param == Parameter::Br {
            let expected = "a relative tolerance in [0, 0.5] or a percentage in [0%, 50%]";
            let (num, scale) = match value.strip_suffix('%') {
                Some(n) => (n, 0.01),
                None => (value, 1.0),
            };
            let v: f64 = num.trim().parse().map_err(|_| bad(expected))?;
            let v = v * scale;
            if !(0.0..=0.5).contains(&v) {
                return Err(bad(expected));
            }
            v
        } else {
            let expected = "a length in mm, finite, in [0, 2] (0.05, 0.05mm)";
            let num = value.strip_suffix("mm").unwrap_or(value);
            let v: f64 = num.trim().parse().map_err(|_| bad(expected))?;
            if !(0.0..=2.0).contains(&v) {
                return Err(bad(expected));
            }
            v * factor
        };
        *self.slot(param) = v;
        Ok(())
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn keys_and_values() {
        let mut t = Tolerances::default();
        assert_eq!(t.s, 0.1);
        t.set("s=0.05").unwrap();
        t.set("br=2%").unwrap();
        t.set("d=0.05mm").unwrap();
        t.set("WALL = 0.2").unwrap();
        assert_eq!((t.s, t.br, t.width, t.wall), (0.05, 0.02, 0.1, 0.2));
        for (bad, says) in [
            ("s", "KEY=VALUE"),
            ("q=1", "unknown key 'q'"),
            ("s=-1", "bad value '-1'"),
            ("s=abc", "bad value 'abc'"),
            ("s=NaN", "bad value"),
            ("br=70%", "percentage"),
            ("s=3", "[0, 2]"),
        ] {
            let e = t.set(bad).unwrap_err().to_string();
            assert!(e.contains(says), "{bad}: {e}");
        }
        assert_eq!(Tolerances::printed(Printer::Resin).s, 0.05);
    }
}
