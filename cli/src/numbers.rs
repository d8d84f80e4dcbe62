//! Numbers on the command line, read once with their range: counts (`200000`, `1e6`,
//! `1_000_000`) and quantities with a unit, each refused with the range and the unit when out
//! of it (clap prints the message on one line, [`crate::report::parse_args`]).

use foldchain::short_number;

/// A whole number from `min` to `max`, written plainly, with `_` between digits, or in
/// scientific notation when that is a whole number (`1e6`). `what` names the unit in the
/// message (`tiles`, `samples`).
pub fn count_in(text: &str, min: u64, max: u64, what: &str) -> Result<u64, String> {
    let t = text.trim().replace('_', "");
    let value = match t.parse::<u64>() {
        Ok(v) => Some(v),
        Err(_) => t
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && v.fract() == 0.0 && *v >= 0.0 && *v < 1.8e19)
            .map(|v| v as u64),
    };
    match value {
        Some(v) if (min..=max).contains(&v) => Ok(v),
        Some(_) => Err(format!(
            "expected a whole number of {what} from {} to {}",
            thousands(min),
            thousands(max)
        )),
        None => Err(format!(
            "expected a whole number of {what} from {} to {}{}",
            thousands(min),
            thousands(max),
            if max >= 1_000_000 {
                " (e.g. 1000 or 1e6)"
            } else {
                ""
            }
        )),
    }
}

/// A number from `min` to `max` (inclusive), in `unit`, with `why` after the range when not
/// empty.
pub fn number_in(text: &str, min: f64, max: f64, unit: &str, why: &str) -> Result<f64, String> {
    let why = if why.is_empty() {
        String::new()
    } else {
        format!(" ({why})")
    };
    let range = format!(
        "expected a number from {} to {} {unit}{why}",
        short_number(min),
        short_number(max)
    );
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && (min..=max).contains(&v) => Ok(v),
        _ => Err(range),
    }
}

/// A clap value parser of [`number_in`]'s numbers from `min` to `max` in `unit` (`why`
/// after the range when not empty): `#[arg(value_parser = in_range(0.0, 2.0, "mm", ""))]`.
pub fn in_range(
    min: f64,
    max: f64,
    unit: &'static str,
    why: &'static str,
) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |text| number_in(text, min, max, unit, why)
}

/// A number that [`number_in`] read (`parsed`), kept when `keep` holds for it, else the
/// message `expected {expected}`: for a range open at one end (`above 0`, `below 0.01`).
pub fn open_range(
    parsed: Result<f64, String>,
    keep: impl Fn(f64) -> bool,
    expected: &str,
) -> Result<f64, String> {
    let v = parsed?;
    if keep(v) {
        Ok(v)
    } else {
        Err(format!("expected {expected}"))
    }
}

/// `n` with thin groups of three digits: `1,000,000`.
pub fn thousands(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, ch) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(ch);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_in_every_notation_and_out_of_range() {
        assert_eq!(count_in("1e6", 1, u64::MAX, "samples"), Ok(1_000_000));
        assert_eq!(count_in("1_000", 1, 10_000, "samples"), Ok(1000));
        assert_eq!(count_in(" 42 ", 1, 100, "tiles"), Ok(42));
        let e = count_in("1e12", 1, 10_000_000, "samples").unwrap_err();
        assert_eq!(e, "expected a whole number of samples from 1 to 10,000,000");
        for bad in ["1.5", "-3", "x", "", "1e400", "NaN"] {
            assert!(count_in(bad, 1, 10, "tiles").is_err(), "{bad}");
        }
    }

    #[test]
    fn numbers_say_their_range_and_unit() {
        assert_eq!(number_in("5", 1e-3, 1e3, "N s/m", ""), Ok(5.0));
        let e = number_in("1e-300", 1e-3, 1e3, "N s/m", "").unwrap_err();
        assert_eq!(e, "expected a number from 0.001 to 1000 N s/m");
        assert!(number_in("inf", 0.0, 1.0, "", "").is_err());
        assert_eq!(thousands(1234567), "1,234,567");
    }

    #[test]
    fn an_open_end_is_refused_with_its_own_words() {
        let above_0 = |s| open_range(number_in(s, 0.0, 2.0, "mm", ""), |v| v > 0.0, "above 0");
        assert_eq!(above_0("0.5"), Ok(0.5));
        assert_eq!(above_0("0").unwrap_err(), "expected above 0");
        // out of the closed range: number_in's message
        assert_eq!(
            above_0("3").unwrap_err(),
            "expected a number from 0 to 2 mm"
        );
    }
}
