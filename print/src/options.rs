//! What a printed part and a print job are made with: the printer, the clearance of the
//! channels, the tile's height and floor, the engraved mark, the bed and the file format.
//! Every default is documented where it is defined, with the estimate behind it.

use foldchain::tolerance::{Printer, Tolerances};

use crate::PrintError;

/// The thesis' tile height, mm (section 7.3: "3cm x 3cm x 7.5mm tiles").
pub const THESIS_HEIGHT: f64 = 7.5;

/// Default floor under the channels, mm: six 0.2 mm FDM layers, stiff enough under a magnet
/// and thin enough to keep the magnet's centre of mass low (1.2 + 5/2 = 3.7 mm < 7.5 mm).
pub const DEFAULT_FLOOR: f64 = 1.2;

/// Default depth of the engraved mark, mm: three 0.2 mm FDM layers, about ten resin layers.
pub const DEFAULT_MARK_DEPTH: f64 = 0.6;

/// Default stroke width of the engraved letters, mm: a 0.4 mm FDM nozzle's line and half
/// again, so that an FDM slicer keeps the groove open.
pub const DEFAULT_MARK_STROKE: f64 = 0.6;

/// Default height of the engraved capitals, mm.
pub const DEFAULT_MARK_HEIGHT: f64 = 3.2;

/// Default thinnest wall a part may have, mm: one 0.4 mm FDM extrusion line (resin printers
/// make about 0.3-0.5 mm walls). A design that leaves less is refused.
pub const DEFAULT_MIN_WALL: f64 = 0.4;

/// Default greatest distance between a curved channel wall and its chords, mm (the walls
/// are polygons; this bounds the error of the channel's width to about twice it).
pub const DEFAULT_ARC_TOLERANCE: f64 = 0.002;

/// The clearance a printer's channels get by default, mm: the channel must still take the
/// largest magnet when both walls are printed at their worst, so twice the printer's
/// tolerance of a printed dimension (+-0.1 mm FDM, +-0.05 mm resin, the values
/// `fold-tolerance --printer` uses) plus the magnet's diameter tolerance (+-0.05 mm, the
/// catalogue value `fold-tolerance` uses): 0.25 mm for FDM, 0.15 mm for resin.
pub fn default_clearance(printer: Printer) -> f64 {
    let c = 2.0 * printer.tolerance() + Tolerances::printed(printer).diameter;
    // to the micrometre, so that 0.15 is not written 0.15000000000000002
    (c * 1e6).round() / 1e6
}

/// How one tile part is built. Lengths in mm.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct PartOptions {
    /// The printer the clearance is for. Default FDM.
    pub printer: Printer,
    /// Channel width minus magnet diameter. Default [`default_clearance`] of the printer.
    pub clearance: f64,
    /// Tile height. Default [`THESIS_HEIGHT`].
    pub height: f64,
    /// Floor under the channels. Default [`DEFAULT_FLOOR`].
    pub floor: f64,
    /// Depth of the engraved mark. Default [`DEFAULT_MARK_DEPTH`].
    pub mark_depth: f64,
    /// Stroke width of the engraved mark. Default [`DEFAULT_MARK_STROKE`].
    pub mark_stroke: f64,
    /// Capital height of the engraved mark (smaller when the tile has no room). Default
    /// [`DEFAULT_MARK_HEIGHT`].
    pub mark_height: f64,
    /// Thinnest wall allowed. Default [`DEFAULT_MIN_WALL`].
    pub min_wall: f64,
    /// Chord tolerance of curved walls. Default [`DEFAULT_ARC_TOLERANCE`].
    pub arc_tolerance: f64,
}

impl Default for PartOptions {
    fn default() -> PartOptions {
        PartOptions::for_printer(Printer::Fdm)
    }
}

impl PartOptions {
    /// The defaults for `printer` (its clearance).
    pub fn for_printer(printer: Printer) -> PartOptions {
        PartOptions {
            printer,
            clearance: default_clearance(printer),
            height: THESIS_HEIGHT,
            floor: DEFAULT_FLOOR,
            mark_depth: DEFAULT_MARK_DEPTH,
            mark_stroke: DEFAULT_MARK_STROKE,
            mark_height: DEFAULT_MARK_HEIGHT,
            min_wall: DEFAULT_MIN_WALL,
            arc_tolerance: DEFAULT_ARC_TOLERANCE,
        }
    }

    /// The same options with another clearance, mm.
    pub fn with_clearance(mut self, clearance: f64) -> PartOptions {
        self.clearance = clearance;
        self
    }

    /// The same options with another tile height, mm.
    pub fn with_height(mut self, height: f64) -> PartOptions {
        self.height = height;
        self
    }

    /// The same options with another floor, mm.
    pub fn with_floor(mut self, floor: f64) -> PartOptions {
        self.floor = floor;
        self
    }

    /// Checks every value (finite and in range).
    pub fn validate(&self) -> Result<(), PrintError> {
        let bad = |name: &'static str, value: f64, expected: &str| PrintError::BadOption {
            name,
            value: value.to_string(),
            expected: expected.to_string(),
        };
        let checks: [(&'static str, f64, bool, &str); 8] = [
            (
                "clearance",
                self.clearance,
                self.clearance >= 0.0,
                "a finite number >= 0 mm",
            ),
            (
                "height",
                self.height,
                self.height > 0.0,
                "a finite number > 0 mm",
            ),
            (
                "floor",
                self.floor,
                self.floor > 0.0,
                "a finite number > 0 mm",
            ),
            (
                "mark depth",
                self.mark_depth,
                self.mark_depth > 0.0,
                "a finite number > 0 mm",
            ),
            (
                "mark stroke",
                self.mark_stroke,
                self.mark_stroke > 0.0,
                "a finite number > 0 mm",
            ),
            (
                "mark height",
                self.mark_height,
                self.mark_height > 0.0,
                "a finite number > 0 mm",
            ),
            (
                "min wall",
                self.min_wall,
                self.min_wall > 0.0,
                "a finite number > 0 mm",
            ),
            (
                "arc tolerance",
                self.arc_tolerance,
                self.arc_tolerance > 0.0 && self.arc_tolerance <= 0.1,
                "a number in (0, 0.1] mm",
            ),
        ];
        for (name, value, ok, expected) in checks {
            if !value.is_finite() || !ok {
                return Err(bad(name, value, expected));
            }
        }
        if self.floor >= self.height {
            return Err(bad("floor", self.floor, "less than the tile height"));
        }
        if self.mark_depth >= self.height - self.floor {
            return Err(bad(
                "mark depth",
                self.mark_depth,
                "less than the height above the floor",
            ));
        }
        Ok(())
    }
}

/// The file format of the parts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// 3MF: a zip of XML, in mm, several named objects per file (what slicers prefer). The
    /// default.
    #[default]
    #[serde(rename = "3mf")]
    ThreeMf,
    /// Binary STL: one mesh per file, in mm by convention.
    Stl,
}

impl Format {
    /// The file extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Format::ThreeMf => "3mf",
            Format::Stl => "stl",
        }
    }
}

/// The print bed and how parts are spaced on it, mm.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Bed {
    /// Width (x). Default 250 (a Prusa MK4's 250 x 210 mm bed).
    pub width: f64,
    /// Depth (y). Default 210.
    pub depth: f64,
    /// Gap between neighbouring parts (the grid is centred on the bed). Default 5.
    pub spacing: f64,
}

impl Default for Bed {
    fn default() -> Bed {
        Bed {
            width: 250.0,
            depth: 210.0,
            spacing: 5.0,
        }
    }
}

impl Bed {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), PrintError> {
        for (name, v, ok) in [
            ("bed width", self.width, self.width > 0.0),
            ("bed depth", self.depth, self.depth > 0.0),
            ("spacing", self.spacing, self.spacing >= 0.0),
        ] {
            if !v.is_finite() || !ok || v > 10_000.0 {
                return Err(PrintError::BadOption {
                    name,
                    value: v.to_string(),
                    expected: "a finite number of mm in (0, 10000] (spacing may be 0)".into(),
                });
            }
        }
        Ok(())
    }
}

/// Everything a print job is made with.
#[derive(Clone, Copy, Debug, PartialEq, Default, serde::Serialize)]
pub struct PrintOptions {
    /// How each part is built.
    pub part: PartOptions,
    /// The bed the plates are laid out on.
    pub bed: Bed,
    /// The parts' file format. Default 3MF.
    pub format: Format,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clearances_follow_the_printer_tolerances() {
        assert!((default_clearance(Printer::Fdm) - 0.25).abs() < 1e-12);
        assert!((default_clearance(Printer::Resin) - 0.15).abs() < 1e-12);
        assert!(PartOptions::default().validate().is_ok());
        let e = PartOptions::default()
            .with_floor(8.0)
            .validate()
            .unwrap_err();
        assert!(e.to_string().contains("floor"), "{e}");
        let e = PartOptions::default()
            .with_clearance(f64::NAN)
            .validate()
            .unwrap_err();
        assert!(e.to_string().contains("clearance"), "{e}");
    }
}
