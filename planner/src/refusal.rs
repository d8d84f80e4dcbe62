//! Refusals a user can act on: when a shape cannot be planned, the error says in a sentence
//! or two what is wrong, where (in drawing units and in mm) and what to change; what every
//! planner tried goes to the error's `detail`, for a verbose report (issue 26: refusals ran
//! to 0.5-5.4 KB of repeated clauses and named nothing to change).

use kurbo::{Point, Rect};

use crate::empty::REFUSE_EMPTY_TILES;
use crate::error::{PlanError, Rejected};
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
    if a >= 100.0 || a == 0.0 {
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

/// The refusal of a drawing in separate parts, given their boxes in the physical frame
/// (y up), largest first.
pub(crate) fn separate_parts(name: &str, parts: &[Rect], mm_per_unit: f64) -> PlanError {
    // SVG frame: y down
    let svg = |b: &Rect| Rect::new(b.x0, -b.y1, b.x1, -b.y0);
    let mut boxes: Vec<Rect> = parts.iter().map(svg).collect();
    boxes.sort_by(|a, b| b.area().total_cmp(&a.area()));
    let largest = boxes.first().map_or(String::new(), |b| {
        format!(" (the largest: {})", span(*b, mm_per_unit))
    });
    let detail = boxes
        .iter()
        .take(LISTED_PARTS)
        .enumerate()
        .map(|(i, b)| format!("part {}: {}", i + 1, span(*b, mm_per_unit)))
        .chain(
            (boxes.len() > LISTED_PARTS)
                .then(|| format!("and {} smaller parts", boxes.len() - LISTED_PARTS)),
        )
        .collect();
    PlanError::Unplannable {
        name: name.into(),
        reason: format!(
            "the drawing is in {} separate parts{largest}; one chain cannot cross a gap: join the parts in the drawing, or plan each on its own",
            boxes.len()
        ),
        detail,
        rejected: None,
    }
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

/// The refusal when no plan was found: `asked` tiles (or the count a tile width gives),
/// what each planner said (`failures`), whether the shape is monotone in no direction,
/// and the best plan rejected for a part it leaves empty. `plans_at`, when the count was
/// asked (not a tile width), plans the shape at another count and returns the plan's tile
/// count, or `None`: the counts of [`FEWER`] are tried in turn and the first that plans is
/// named.
pub(crate) fn no_plan(
    name: &str,
    asked: usize,
    nowhere_monotone: bool,
    failures: Vec<String>,
    rejected: Option<Box<Rejected>>,
    mm_per_unit: f64,
    plans_at: Option<&dyn Fn(usize) -> Option<usize>>,
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
    let advice = match plans_at {
        None => format!("try another tile width, or {part}"),
        Some(plans_at) => {
            let tried: Vec<usize> = FEWER
                .iter()
                .map(|f| (asked as f64 * f).round() as usize)
                .filter(|&n| n >= MIN_TRIED)
                .collect();
            match tried.iter().find_map(|&n| plans_at(n).map(|got| (n, got))) {
                Some((n, got)) => format!("try {n} tiles: that plans ({got} tiles), or {part}"),
                None if tried.is_empty() => part.to_string(),
                None => format!("{} tiles do not plan either: {part}", list(&tried)),
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
