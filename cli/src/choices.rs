//! The tools' choices among named options, as clap value enums: parsed once into the
//! library's types, so a binary never compares strings.

use std::fmt;

use clap::ValueEnum;
use foldchain::model::Dynamics;
use foldchain::tolerance::Printer;

/// The physics of the local solves and of the reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DynamicsChoice {
    /// First order, drag only: the stiff limit of negligible mass.
    Overdamped,
    /// Mass, drag and walls the magnets and folds bounce at (docs/physics.md, "Physical parameters").
    Inertial,
}

impl DynamicsChoice {
    /// The library's dynamics (inertial with the default inertia).
    pub fn to_dynamics(self) -> Dynamics {
        match self {
            DynamicsChoice::Overdamped => Dynamics::Overdamped,
            DynamicsChoice::Inertial => Dynamics::Inertial,
        }
    }
}

/// How `fold-run`'s event engine times its events.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum EngineChoice {
    /// The local solves up to 2,000 distinct joint neighbourhoods, the kinematic baseline
    /// beyond.
    Auto,
    /// Local solves of the reference's physics, one joint at a time from the RI end.
    Local,
    /// The kinematic baseline: a start rule and a closed-form speed law.
    Kinematic,
}

/// The kinematic baseline's speed law.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SpeedChoice {
    /// Overdamped magnets under drag `--drag` (seconds).
    Overdamped,
    /// 1 mm/s, the thesis' transition diagram's timeline.
    Unit,
}

/// The kinematic baseline's start rule.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum StartRuleChoice {
    /// The thesis' path-length inequalities, nearest neighbours.
    Distance,
    /// The pair forces of every magnet within 3 in chain index.
    Force,
}

/// How step frames are framed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FramesViewChoice {
    /// Each frame on the chain as it stands, or on the part that moves when a long chain
    /// seen whole would be a hairline.
    Auto,
    /// Every frame in one view holding the whole run.
    Fixed,
}

/// The printer whose tolerances are the defaults of printed dimensions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PrinterChoice {
    /// Fused deposition: +-0.1 mm.
    Fdm,
    /// Resin: +-0.05 mm.
    Resin,
}

impl PrinterChoice {
    /// The library's printer.
    pub fn to_printer(self) -> Printer {
        match self {
            PrinterChoice::Fdm => Printer::Fdm,
            PrinterChoice::Resin => Printer::Resin,
        }
    }
}

/// The file format of printed parts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FormatChoice {
    /// 3MF: named objects in mm, plates as one file each (what slicers prefer).
    #[value(name = "3mf")]
    ThreeMf,
    /// Binary STL: one mesh per file.
    Stl,
}

impl FormatChoice {
    /// The library's format.
    pub fn to_format(self) -> foldchain_print::Format {
        match self {
            FormatChoice::ThreeMf => foldchain_print::Format::ThreeMf,
            FormatChoice::Stl => foldchain_print::Format::Stl,
        }
    }
}

/// Shows a choice by its name on the command line.
macro_rules! display_by_name {
    ($($t:ty),*) => {$(
        impl fmt::Display for $t {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                match self.to_possible_value() {
                    Some(v) => f.write_str(v.get_name()),
                    None => Ok(()),
                }
            }
        }
    )*};
}

display_by_name!(
    DynamicsChoice,
    PrinterChoice,
    EngineChoice,
    SpeedChoice,
    StartRuleChoice,
    FramesViewChoice,
    FormatChoice
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_the_documented_ones() {
        let names = |v: &[DynamicsChoice]| -> Vec<String> {
            v.iter()
                .filter_map(|c| c.to_possible_value().map(|p| p.get_name().to_string()))
                .collect()
        };
        assert_eq!(
            names(DynamicsChoice::value_variants()),
            ["overdamped", "inertial"]
        );
        assert_eq!(
            PrinterChoice::from_str("resin", false),
            Ok(PrinterChoice::Resin)
        );
        assert_eq!(PrinterChoice::Fdm.to_string(), "fdm");
        assert!(matches!(
            DynamicsChoice::Inertial.to_dynamics(),
            Dynamics::Inertial
        ));
    }
}
