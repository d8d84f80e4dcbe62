//! A serpentine that leaves a small part empty, sized again at widths near its own (issue
//! 26; BENCHMARKS, "What leaves a part empty at 100 and 300 tiles, rings aside"). The size
//! search settles on the rows' fit alone, and where a lobe, a point or a foot juts out
//! beyond the rows' ends, whether a row reaches into it turns on the rows' phase: the same
//! drawing asked for a count 1-3% off plans with nothing empty inside the same count band
//! (the letter K at 100 tiles: 99 tiles leaving 13.7 tile areas of its upper arm empty,
//! asked for 102 it plans 102 tiles leaving none). So a serpentine that leaves a part over
//! [`MIN_EMPTY_TILES`] empty (but not so large that the plan is set aside, which
//! [`crate::plan_shape`]'s own retries handle) is sized again at [`FACTORS`] times its
//! width, and the best that ranks better ([`rank_key`]: the fit, the turns and the part
//! left empty priced together), leaves less empty, keeps the count within the tolerance and
//! folds is kept.

use crate::check::check_folds;
use crate::empty::{note_empty, rank_key, MIN_EMPTY_TILES};
use crate::options::PlanOptions;
use crate::plan::Plan;
use crate::rows::Style;
use crate::serpentine::{size_style, Sized};
use crate::shape::Shape;
use crate::Progress;

/// Factors on the serpentine's width tried in turn, the nearest first.
const FACTORS: [f64; 4] = [1.01, 0.99, 1.02, 0.98];

/// The serpentine `first` (measured: its largest part left empty in its metrics), or a
/// serpentine at a width near its own that ranks better and leaves less empty (see the
/// module's documentation); `miss` is the number of tiles by which a plan misses the count
/// band (0 within it). With a tile width asked, `first` as it is.
#[allow(clippy::too_many_arguments)]
pub(crate) fn fewer_empty(
    shape: &Shape,
    opts: &PlanOptions,
    styles: &[Style],
    directions: &[f64],
    name: &str,
    progress: Progress<'_>,
    miss: &dyn Fn(&Plan) -> usize,
    first: Plan,
) -> Plan {
    if opts.tile_size.is_some() || first.metrics.largest_empty_tiles <= MIN_EMPTY_TILES {
        return first;
    }
    let near = crate::empty::near(opts.turns);
    let key = |p: &Plan| rank_key(p, opts.turn_cost);
    let w = first.tile_size;
    let mut best = first;
    for (f, &style) in FACTORS
        .iter()
        .flat_map(|f| styles.iter().map(move |s| (f, s)))
    {
        let Some((p, sz)) =
            serpentine_at(shape, opts, w * f, style, directions, name, progress, miss)
        else {
            continue;
        };
        // a part too large to keep the plan for is no better
        let Ok(p) = note_empty(shape, p, near) else {
            continue;
        };
        if p.metrics.largest_empty_tiles >= best.metrics.largest_empty_tiles
            || key(&p) >= key(&best)
        {
            continue;
        }
        // the fold check (the costly part on long chains) only for a plan that would be kept
        if !folds(&sz, style) {
            continue;
        }
        best = p;
        if best.metrics.largest_empty_tiles <= MIN_EMPTY_TILES {
            break;
        }
    }
    best
}

/// The best serpentine of turn style `style` at the tile width `w` (unchecked), with its
/// sizing, if its count is within the band (`miss` 0).
#[allow(clippy::too_many_arguments)]
pub(crate) fn serpentine_at(
    shape: &Shape,
    opts: &PlanOptions,
    w: f64,
    style: Style,
    directions: &[f64],
    name: &str,
    progress: Progress<'_>,
    miss: &dyn Fn(&Plan) -> usize,
) -> Option<(Plan, Sized)> {
    let at = PlanOptions {
        tile_size: Some(w),
        ..opts.clone()
    };
    let sz = size_style(shape, &at, style, directions, progress).ok()?;
    let p = sz.best_unchecked(shape, name)?;
    (miss(&p) == 0).then_some((p, sz))
}

/// True if the best serpentine of the sizing `sz` (turn style `style`) folds without
/// collision.
pub(crate) fn folds(sz: &Sized, style: Style) -> bool {
    sz.all
        .first()
        .is_some_and(|c| check_folds(&c.word(style)).is_ok())
}
