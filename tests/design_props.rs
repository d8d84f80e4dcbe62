//! Property tests of the tile design (issue 2): every parameter is checked by name, with a
//! typed error for values that are not finite, positive or within range.

// Tests may unwrap (CONTRIBUTING.md); the workspace lint is for library code.
#![allow(clippy::unwrap_used)]

use foldchain::design::DesignError;
use foldchain::{Design, Standing};
use proptest::prelude::*;

// ---------------------------------------------------------------------------------------------
// Design parameters
// ---------------------------------------------------------------------------------------------

const FIELDS: [&str; 9] = [
    "tile_width",
    "d",
    "s",
    "e",
    "c",
    "magnet_diameter",
    "magnet_height",
    "remanence",
    "magnet_mass",
];

fn set_field(d: &mut Design, name: &str, v: f64) {
    match name {
        "tile_width" => d.tile_width = v,
        "d" => d.d = v,
        "s" => d.s = v,
        "e" => d.e = v,
        "c" => d.c = Some(v),
        "magnet_diameter" => d.magnet_diameter = v,
        "magnet_height" => d.magnet_height = v,
        "remanence" => d.remanence = v,
        "magnet_mass" => d.magnet_mass = v,
        _ => unreachable!("{name}"),
    }
}

/// Finite numbers of every scale and sign, zero and the extremes.
fn finite() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => 0.0f64..100.0,
        2 => -100.0f64..100.0,
        1 => prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO,
        1 => Just(f64::MAX),
        1 => Just(-f64::MAX),
        1 => Just(f64::MIN_POSITIVE),
    ]
}

/// Positive finite numbers of every scale.
fn positive() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => 1e-3f64..100.0,
        1 => prop::num::f64::POSITIVE | prop::num::f64::NORMAL,
        1 => Just(f64::MAX),
        1 => Just(f64::MIN_POSITIVE),
    ]
}

/// NaN, infinities and negative numbers.
fn bad_value() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(-f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        -1e300f64..-1e-300,
        Just(-f64::MIN_POSITIVE),
        Just(-f64::MAX),
    ]
}

fn design_from(v: &[f64], c: Option<f64>) -> Design {
    Design {
        tile_width: v[0],
        d: v[1],
        s: v[2],
        e: v[3],
        c,
        magnet_diameter: v[4],
        magnet_height: v[5],
        remanence: v[6],
        magnet_mass: v[7],
        wall: 0.8,
        ..Design::default()
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Any finite parameters: `check` and `report` return, and agree with each other.
    #[test]
    fn design_never_panics(v in prop::collection::vec(finite(), 8), c in prop::option::of(finite())) {
        let d = design_from(&v, c);
        let report = d.report();
        prop_assert_eq!(report.len(), 10);
        let _ = d.warnings();
        let _ = d.rest_force_change();
        let _ = d.moment();
        match d.check() {
            Ok(r) => {
                prop_assert_eq!(&r, &report);
                prop_assert!(r.iter().all(|x| x.standing != Standing::Fails));
                prop_assert!(d.validate().is_ok());
            }
            Err(DesignError::BadParameter { name, .. }) => {
                prop_assert!(d.validate().is_err());
                prop_assert!(FIELDS.contains(&name), "{}", name);
            }
            Err(DesignError::Inequality { id, .. }) => {
                prop_assert!(d.validate().is_ok());
                let first = report.iter().find(|x| x.standing == Standing::Fails).unwrap();
                prop_assert_eq!(id, first.id);
            }
            Err(e) => prop_assert!(false, "unexpected {e:?}"),
        }
    }

    /// NaN, an infinity or a negative number in any one field is a `BadParameter` naming that
    /// field, whatever the other (positive) fields are.
    #[test]
    fn bad_field_is_named(
        v in prop::collection::vec(positive(), 8),
        c in prop::option::of(positive()),
        field in 0usize..9,
        bad in bad_value(),
    ) {
        let mut d = design_from(&v, c);
        let name = FIELDS[field];
        set_field(&mut d, name, bad);
        match d.check() {
            Err(DesignError::BadParameter { name: got, value, expected, .. }) => {
                prop_assert_eq!(got, name);
                prop_assert!(value.to_bits() == bad.to_bits(), "{value} vs {bad}");
                prop_assert!(!expected.is_empty());
            }
            other => prop_assert!(false, "{name} = {bad}: {other:?}"),
        }
        // and the message names it too
        let msg = d.check().unwrap_err().to_string();
        prop_assert!(msg.contains(&format!("`{name}`")), "{}", msg);
    }
}
