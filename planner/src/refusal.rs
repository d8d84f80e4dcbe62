//! Refusals a user can act on: when a shape cannot be planned, the error says in a sentence
//! or two what is wrong, where (in drawing units and in mm) and what to change; what every
//! planner tried goes to the error's `detail`, for a verbose report (issue 26: refusals ran
//! to 0.5-5.4 KB of repeated clauses and named nothing to change).

use kurbo::{Point, Rect};

use crate::empty::REFUSE_EMPTY_TILES;
use crate::error::{PlanError, Rejected};
use crate::parts::Part;
use crate::plan::mm;

/// Parts listed in a refusal's detail (the short reason names the largest two).
const LISTED_PARTS: usize = 12;

/// A point in drawing units and in mm: `(120, 45) = (31.7, 11.9) mm`.
fn at(p: Point, mm_per_unit: f64) -> String {
    format!(
        "({}, {}) = ({}, {}) mm",
        units(p.x),
        units(p.y),
        mm(p.x * mm_per_unit),
        mm(p.y * mm_per_unit)
    )
}

/// A length in drawing units, to three significant digits (at least whole units).
fn units(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-3..1e7).contains(&a) {
        format!("{v:.3e}")
    } else if a == 0.0 {
        // not "-0" for a negative zero
        "0".into()
    } else if a >= 100.0 {
        format!("{v:.0}")
    } else if a >= 10.0 {
        format!("{v:.1}")
    } else if a >= 1.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    }
}

/// A box (SVG units, y down) as `x 10 to 90, y 5 to 40 (20 x 9 mm)`.
fn span(b: Rect, mm_per_unit: f64) -> String {
    format!(
        "x {} to {}, y {} to {} ({} x {} mm)",
        units(b.x0),
        units(b.x1),
        units(b.y0),
        units(b.y1),
        mm(b.width() * mm_per_unit),
        mm(b.height() * mm_per_unit)
    )
}

/// A box of the physical frame (y up) in the SVG frame (y down).
fn svg_box(b: Rect) -> Rect {
    Rect::new(b.x0, -b.y1, b.x1, -b.y0)
}

/// A part as `x 10 to 90, y 5 to 40 (20 x 9 mm), 12% of the area`, of a drawing whose
/// parts have the area `total`.
fn part_span(p: &Part, total: f64, mm_per_unit: f64) -> String {
    format!(
        "{}, {} of the area",
        span(svg_box(p.bbox), mm_per_unit),
        percent(p.area / total)
    )
}

/// A share as a percentage: `12%`, `0.8%`, `0.03%`.
fn percent(share: f64) -> String {
    let v = 100.0 * share;
    if v >= 10.0 || v.fract() == 0.0 {
        format!("{v:.0}%")
    } else if v >= 1.0 {
        format!("{v:.1}%")
    } else {
        format!("{v:.2}%")
    }
}

/// The refusal of a drawing in two or more parts besides its islands (`large`, largest
/// first; [`crate::parts`]), whatever the count: the short reason names the largest two,
/// the detail every part and the islands.
pub(crate) fn separate_parts(
    name: &str,
    large: &[Part],
    islands: &[Part],
    mm_per_unit: f64,
) -> PlanError {
    let total: f64 = large.iter().chain(islands).map(|p| p.area).sum();
    let at = |p: &Part| span(svg_box(p.bbox), mm_per_unit);
    let which = match large {
        [a, b] => format!(": {} and {}", at(a), at(b)),
        [a, b, ..] => format!(", the largest {} and {}", at(a), at(b)),
        _ => String::new(),
    };
    let detail = large
        .iter()
        .take(LISTED_PARTS)
        .enumerate()
        .map(|(i, p)| format!("part {}: {}", i + 1, part_span(p, total, mm_per_unit)))
        .chain(
            (large.len() > LISTED_PARTS)
                .then(|| format!("and {} smaller parts", large.len() - LISTED_PARTS)),
        )
        .chain((!islands.is_empty()).then(|| {
            format!(
                "and {} ({} of the area together), which a plan would leave out",
                islands_word(islands.len()),
                percent(islands.iter().map(|p| p.area).sum::<f64>() / total)
            )
        }))
        .collect();
    PlanError::Unplannable {
        name: name.into(),
        reason: format!(
            "the drawing is in {} separate parts{which}; one chain cannot cross a gap: join the parts in the drawing, or plan each on its own",
            large.len()
        ),
        detail,
        rejected: None,
    }
}

/// `1 island`, `3 islands`.
fn islands_word(n: usize) -> String {
    if n == 1 {
        "1 island".into()
    } else {
        format!("{n} islands")
    }
}

/// Islands whose boxes the warning that they were left out names.
const LISTED_ISLANDS: usize = 2;

/// The warning that `islands` (the smallest parts, together under
/// [`crate::parts::ISLAND_SHARE`] of the drawing's area `total`, largest first) were left out
/// of the plan, naming the largest two.
pub(crate) fn islands_left_out(islands: &[Part], total: f64, mm_per_unit: f64) -> Option<String> {
    if islands.is_empty() {
        return None;
    }
    let mut named: Vec<String> = islands
        .iter()
        .take(LISTED_ISLANDS)
        .map(|p| span(svg_box(p.bbox), mm_per_unit))
        .collect();
    if islands.len() > LISTED_ISLANDS {
        named.push(format!("{} smaller", islands.len() - LISTED_ISLANDS));
    }
    Some(format!(
        "{} apart from the rest, {} of the drawing's area, left out (one chain cannot reach a part apart): {}; join {} to the rest to plan {}",
        islands_word(islands.len()),
        percent(islands.iter().map(|p| p.area).sum::<f64>() / total),
        named.join("; "),
        if islands.len() == 1 { "it" } else { "them" },
        if islands.len() == 1 { "it" } else { "them" },
    ))
}

/// The refusal of a drawing no tile fits in: no point lies half a tile inside its outline
/// ([`crate::narrow`]). `asked` tiles (or, with `by_width`, the count a tile width gives)
/// are tiles `w` wide; `fits` is the first smaller width at which one fits, `k` halvings of
/// the tile area down (so about `asked * 2^k` tiles), if any.
pub(crate) fn too_narrow(
    name: &str,
    asked: usize,
    w: f64,
    by_width: bool,
    fits: Option<(u32, f64)>,
    mm_per_unit: f64,
) -> PlanError {
    let tile = format!("{} units ({} mm)", units(w), mm(w * mm_per_unit));
    let what = if by_width {
        format!("no part of the drawing is wide enough for a tile {tile} wide")
    } else {
        format!("no part of the drawing is wide enough for a tile: at {asked} tiles a tile is {tile} wide")
    };
    let advice = match fits {
        Some((_, v)) if by_width => format!(
            "try a tile width of {} units ({} mm) or less, or draw it wider",
            units(v),
            mm(v * mm_per_unit)
        ),
        Some((k, v)) => format!(
            "try {} tiles or more (tiles {} units wide fit), or draw it wider",
            asked.saturating_mul(1usize << k.min(40)),
            units(v)
        ),
        None => "draw it wider: no tile count the planner takes fits".into(),
    };
    PlanError::Unplannable {
        name: name.into(),
        reason: format!("{what}; {advice}"),
        detail: Vec::new(),
        rejected: None,
    }
}

/// Tile counts a refusal tries, as shares of the count asked, largest first: a count that
/// plans is named in the refusal (checked, not estimated).
const FEWER: [f64; 4] = [2.0 / 3.0, 1.0 / 2.0, 1.0 / 3.0, 1.0 / 4.0];
/// Counts below this are not tried.
const MIN_TRIED: usize = 10;

/// How a refusal looks for a count to advise: `plans_at` plans the shape at another count
/// and returns the plan's tile count, or `None`; a count is advised only when its plan's
/// count is within `tolerance` (a share, as [`crate::PlanOptions::tiles_tolerance`]) of it,
/// so the advice never names a count whose plan has a fraction of its tiles (issue 26: 67
/// tiles advised for a plan of 12).
pub(crate) struct Retry<'a> {
    /// Plans the shape at a count, returning the plan's tile count.
    pub plans_at: &'a dyn Fn(usize) -> Option<usize>,
    /// The share by which an advised count's plan may miss it.
    pub tolerance: f64,
}

impl Retry<'_> {
    /// The tile count of the plan at `n` tiles, if it plans within the tolerance of `n`.
    fn plans_within(&self, n: usize) -> Option<usize> {
        let tol = (self.tolerance * n as f64) as usize;
        (self.plans_at)(n).filter(|got| got.abs_diff(n) <= tol)
    }
}

/// The refusal when no plan was found: `asked` tiles (or the count a tile width gives),
/// what each planner said (`failures`), whether the shape is monotone in no direction,
/// and the best plan rejected for a part it leaves empty. `retry`, when the count was
/// asked (not a tile width): the counts of [`FEWER`] are tried in turn and the first whose
/// plan is within the tolerance of it is named.
pub(crate) fn no_plan(
    name: &str,
    asked: usize,
    nowhere_monotone: bool,
    failures: Vec<String>,
    rejected: Option<Box<Rejected>>,
    mm_per_unit: f64,
    retry: Option<Retry<'_>>,
) -> PlanError {
    let mut detail: Vec<String> = Vec::new();
    if nowhere_monotone {
        detail.push("the shape is monotone in no direction: no single serpentine fills it".into());
    }
    for f in failures {
        if !detail.contains(&f) {
            detail.push(f);
        }
    }
    let what = match &rejected {
        Some(r) => format!(
            "the best plan ({} tiles of {} mm) leaves {:.0} tile areas empty around {}, at most {REFUSE_EMPTY_TILES:.0} may be",
            r.plan.tiles,
            mm(r.plan.tile_size * mm_per_unit),
            r.empty.tiles,
            at(r.empty.centre, mm_per_unit)
        ),
        None => format!(
            "no chain of about {asked} tiles was found that folds without collision{}",
            if nowhere_monotone {
                " (the shape is monotone in no direction)"
            } else {
                ""
            }
        ),
    };
    let part = if rejected.is_some() {
        "draw that part wider"
    } else {
        "simplify the outline"
    };
    let advice = match retry {
        None => format!("try another tile width, or {part}"),
        Some(retry) => {
            let tried: Vec<usize> = FEWER
                .iter()
                .map(|f| (asked as f64 * f).round() as usize)
                .filter(|&n| n >= MIN_TRIED)
                .collect();
            match tried
                .iter()
                .find_map(|&n| retry.plans_within(n).map(|got| (n, got)))
            {
                Some((n, got)) => format!("try {n} tiles: that plans ({got} tiles), or {part}"),
                None if tried.is_empty() => part.to_string(),
                None => format!(
                    "{} tiles do not plan within {:.0}% either: {part}",
                    list(&tried),
                    100.0 * retry.tolerance
                ),
            }
        }
    };
    PlanError::Unplannable {
        name: name.into(),
        reason: format!("{what}; {advice}"),
        detail,
        rejected,
    }
}

/// `a, b, c or d`.
fn list(v: &[usize]) -> String {
    match v {
        [] => String::new(),
        [one] => one.to_string(),
        [init @ .., last] => format!(
            "{} or {last}",
            init.iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    /// Lengths in the refusals' words: no "-0" (a box edge at -0.0 was "y -0 to 24.0"),
    /// and sizes too small or large for fixed decimals in scientific notation.
    #[test]
    fn lengths_read_as_numbers() {
        assert_eq!(units(-0.0), "0");
        assert_eq!(units(0.0), "0");
        assert_eq!(units(-2.148e-4), "-2.148e-4");
        assert_eq!(units(123.4), "123");
        assert_eq!(units(0.5), "0.500");
        assert_eq!(units(3e9), "3.000e9");
    }

    use super::*;

    fn reason(e: PlanError) -> String {
        match e {
            PlanError::Unplannable { reason, .. } => reason,
            other => other.to_string(),
        }
    }

    /// A count is advised only when its plan lands within the tolerance of it: a plan of 12
    /// tiles at 67 asked is no reason to advise 67 (issue 26's narrowb-at), one of 66 is.
    #[test]
    fn a_count_is_advised_only_when_it_plans_within_the_tolerance() {
        let refuse = |plans_at: &dyn Fn(usize) -> Option<usize>| {
            reason(no_plan(
                "x.svg",
                100,
                false,
                Vec::new(),
                None,
                1.0,
                Some(Retry {
                    plans_at,
                    tolerance: 0.03,
                }),
            ))
        };
        let tiny = refuse(&|n| (n >= 60).then_some(12));
        assert!(!tiny.contains("try 67"), "{tiny}");
        assert!(
            tiny.contains("67, 50, 33 or 25 tiles do not plan within 3% either"),
            "{tiny}"
        );
        let near = refuse(&|n| (n <= 70).then_some(n - 1));
        assert!(
            near.contains("try 67 tiles: that plans (66 tiles)"),
            "{near}"
        );
        // the first count that plans within the tolerance is named, not the first that plans
        let later = refuse(&|n| Some(if n == 67 { 12 } else { n }));
        assert!(
            later.contains("try 50 tiles: that plans (50 tiles)"),
            "{later}"
        );
    }
}
