//! Numbers in messages: short enough to read, whatever their size (a user who types `1e308`
//! reads back `1e308`, not 309 digits).

/// `v` in at most six significant digits: plain notation from 0.001 up to a million,
/// scientific beyond (`1e308`, `2.5e-7`), trailing zeros dropped; `NaN`, `inf`, `-inf` as
/// Rust writes them.
///
/// ```
/// use foldchain::short_number;
/// assert_eq!(short_number(0.3), "0.3");
/// assert_eq!(short_number(4.7 / 3.0), "1.56667");
/// assert_eq!(short_number(1e308), "1e308");
/// assert_eq!(short_number(-2.5e-7), "-2.5e-7");
/// assert_eq!(short_number(1_000_000_000_000.0), "1e12");
/// ```
pub fn short_number(v: f64) -> String {
    if !v.is_finite() || v == 0.0 {
        return format!("{v}");
    }
    let a = v.abs();
    // Rounded to six digits first: 999999.9 is 1e6 and written as such.
    let rounded_abs = format!("{a:.5e}").parse::<f64>().unwrap_or(a);
    if (1e-3..1e6).contains(&rounded_abs) {
        let digits = (5 - rounded_abs.log10().floor() as i32).clamp(0, 8) as usize;
        let text = format!("{v:.digits$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            text
        }
    } else {
        let text = format!("{v:.5e}");
        match text.split_once('e') {
            Some((mantissa, exp)) => {
                let m = if mantissa.contains('.') {
                    mantissa.trim_end_matches('0').trim_end_matches('.')
                } else {
                    mantissa
                };
                format!("{m}e{exp}")
            }
            None => text,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::short_number;

    #[test]
    fn short_at_every_scale() {
        for (v, text) in [
            (0.0, "0"),
            (30.0, "30"),
            (1.0 / 3.0, "0.333333"),
            (123456.7, "123457"),
            (999999.9, "1e6"),
            (0.001, "0.001"),
            (0.000999, "9.99e-4"),
            (f64::MAX, "1.79769e308"),
            (f64::NAN, "NaN"),
            (-f64::INFINITY, "-inf"),
            (-1e-300, "-1e-300"),
        ] {
            assert_eq!(short_number(v), text, "{v:e}");
        }
    }
}
