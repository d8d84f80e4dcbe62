//! Clip paths and masks: the filled area a browser shows is a filled element's area
//! intersected with the regions of the `clip-path` and `mask` of every group around it.
//! Regions are polygon sets, and the boolean operations are `i_overlay`'s (not written
//! here): each element is first made simple by its own fill rule, then intersected.
//!
//! - A drawing of several filled elements is read as the union of their fills
//!   ([`union_paths`]), as a browser paints it: a drawing made of many pieces (pixel art, a
//!   logo's letters drawn over a plate) becomes the outline one sees, without the seams
//!   between touching pieces, and the planner's row queries meet one outline's edges, not
//!   every piece's.
//! - A clip path's region is the union of its children's fills (each by its own rule,
//!   which usvg takes from `clip-rule`), under the clip path's transform and the clipped
//!   group's, and intersected with the clip path's own `clip-path`.
//! - A mask shows where its content is at least half bright: its children are painted in
//!   order inside the mask's rectangle, each with its alpha `a` (its fill opacity times the
//!   opacities of the groups around it) and brightness `L` (luminance masks: the fill
//!   colour's luminance, 0.2125 R + 0.7154 G + 0.0721 B; alpha masks: 1). Painted over a
//!   place that shows (1) it leaves `1 - a + L a`, over one that does not (0) `L a`; so a
//!   child adds its area where `L a >= 1/2`, takes it away where `1 - a + L a < 1/2`, and
//!   otherwise changes nothing (a group of opacity 0 paints nothing). This is exact for
//!   masks of opaque black and white shapes, the way drawing programs make them; grey or
//!   half-transparent content is cut at one half, and gradients and patterns count as
//!   bright.

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::simplify::SimplifyShape;
use i_overlay::float::single::SingleFloatOverlay;
use kurbo::Point;

use crate::flatten::{flatten, path_segments};
use crate::shape::{FilledPath, Ring};
use crate::simplify::clean;

/// A clip path or mask of a group, with the group's transform to the physical frame's user
/// units (before the y flip).
#[derive(Clone, Copy)]
pub(crate) enum ClipRef<'a> {
    /// `clip-path`.
    Path(&'a usvg::ClipPath, usvg::Transform),
    /// `mask`.
    Mask(&'a usvg::Mask, usvg::Transform),
}

/// A polygon set: contours of `[x, y]` points (outer contours and holes, as `i_overlay`
/// returns them: holes wound against their outer contour).
type Region = Vec<Vec<[f64; 2]>>;

/// The simple polygons of rings filled by `even_odd` or non-zero.
fn simple(rings: &[Ring], even_odd: bool) -> Region {
    let contours: Region = rings
        .iter()
        .map(|r| r.points.iter().map(|p| [p.x, p.y]).collect())
        .collect();
    let rule = if even_odd {
        FillRule::EvenOdd
    } else {
        FillRule::NonZero
    };
    contours
        .simplify_shape(rule)
        .into_iter()
        .flatten()
        .collect()
}

/// `a` combined with `b` by `rule` (both simple, non-zero).
fn combine(a: &Region, b: &Region, rule: OverlayRule) -> Region {
    a.overlay(b, rule, FillRule::NonZero)
        .into_iter()
        .flatten()
        .collect()
}

/// The rings of a path's fill under `ts`, flattened to `tol` and cleaned.
fn path_rings(p: &usvg::Path, ts: usvg::Transform, tol: f64, eps: f64) -> Vec<Ring> {
    path_segments(p, ts)
        .iter()
        .map(|sp| clean(&flatten(sp, tol), eps))
        .filter(|r| r.points.len() >= 3)
        .collect()
}

/// The area filled by the paths below `group` (`ts` maps its user units), each by its own
/// rule, with the clip paths and masks of the groups inside.
fn group_fill(group: &usvg::Group, ts: usvg::Transform, tol: f64, eps: f64) -> Region {
    let mut out: Region = Vec::new();
    for node in group.children() {
        let part = match node {
            usvg::Node::Path(p) => {
                if !p.is_visible() {
                    continue;
                }
                let even_odd = p
                    .fill()
                    .is_some_and(|f| f.rule() == usvg::FillRule::EvenOdd);
                simple(
                    &path_rings(p, p.abs_transform().post_concat(ts), tol, eps),
                    even_odd,
                )
            }
            usvg::Node::Group(g) => {
                let gts = g.abs_transform().post_concat(ts);
                let mut part = group_fill(g, ts, tol, eps);
                if let Some(c) = g.clip_path() {
                    part = combine(
                        &part,
                        &clip_region(c, gts, tol, eps),
                        OverlayRule::Intersect,
                    );
                }
                if let Some(m) = g.mask() {
                    part = combine(
                        &part,
                        &mask_region(m, gts, tol, eps),
                        OverlayRule::Intersect,
                    );
                }
                part
            }
            _ => continue,
        };
        out = if out.is_empty() {
            part
        } else {
            combine(&out, &part, OverlayRule::Union)
        };
    }
    out
}

/// The region a clip path lets through, for a group whose user units `ts` maps.
fn clip_region(c: &usvg::ClipPath, ts: usvg::Transform, tol: f64, eps: f64) -> Region {
    let own = group_fill(c.root(), c.transform().post_concat(ts), tol, eps);
    match c.clip_path() {
        Some(outer) => combine(
            &own,
            &clip_region(outer, ts, tol, eps),
            OverlayRule::Intersect,
        ),
        None => own,
    }
}

/// What painting one of a mask's paths does to the region the mask shows (see the module
/// doc): `Some(Union)` adds its area, `Some(Difference)` takes it away, `None` leaves the
/// region as it is. `opacity` is the product of the opacities of the groups around it.
fn mask_paint(p: &usvg::Path, kind: usvg::MaskType, opacity: f64) -> Option<OverlayRule> {
    let fill = p.fill()?;
    let alpha = opacity * f64::from(fill.opacity().get());
    let bright = match (kind, fill.paint()) {
        (usvg::MaskType::Luminance, usvg::Paint::Color(c)) => {
            (0.2125 * f64::from(c.red) + 0.7154 * f64::from(c.green) + 0.0721 * f64::from(c.blue))
                / 255.0
        }
        // alpha masks: the opacity alone; gradients and patterns: taken as bright
        _ => 1.0,
    };
    if bright * alpha >= 0.5 {
        Some(OverlayRule::Union)
    } else if 1.0 - alpha + bright * alpha < 0.5 {
        Some(OverlayRule::Difference)
    } else {
        None
    }
}

/// Paints the paths below `group` (inside groups of opacities whose product is `opacity`)
/// into `region` in document order (see the module doc).
fn paint_mask(
    group: &usvg::Group,
    (ts, opacity): (usvg::Transform, f64),
    kind: usvg::MaskType,
    region: &mut Region,
    tol: f64,
    eps: f64,
) {
    for node in group.children() {
        match node {
            usvg::Node::Path(p) => {
                if !p.is_visible() {
                    continue;
                }
                let Some(rule) = mask_paint(p, kind, opacity) else {
                    continue;
                };
                let even_odd = p
                    .fill()
                    .is_some_and(|f| f.rule() == usvg::FillRule::EvenOdd);
                let area = simple(
                    &path_rings(p, p.abs_transform().post_concat(ts), tol, eps),
                    even_odd,
                );
                *region = combine(region, &area, rule);
            }
            usvg::Node::Group(g) => {
                let opacity = opacity * f64::from(g.opacity().get());
                if opacity > 0.0 {
                    paint_mask(g, (ts, opacity), kind, region, tol, eps);
                }
            }
            _ => {}
        }
    }
}

/// The region a mask shows, for a group whose user units `ts` maps.
fn mask_region(m: &usvg::Mask, ts: usvg::Transform, tol: f64, eps: f64) -> Region {
    let mut shown: Region = Vec::new();
    paint_mask(m.root(), (ts, 1.0), m.kind(), &mut shown, tol, eps);
    let r = m.rect();
    let corner = |x: f32, y: f32| {
        let mut q = usvg::tiny_skia_path::Point::from_xy(x, y);
        ts.map_point(&mut q);
        [f64::from(q.x), -f64::from(q.y)]
    };
    let rect: Region = vec![vec![
        corner(r.left(), r.top()),
        corner(r.right(), r.top()),
        corner(r.right(), r.bottom()),
        corner(r.left(), r.bottom()),
    ]];
    let rect = rect
        .simplify_shape(FillRule::NonZero)
        .into_iter()
        .flatten()
        .collect();
    let mut out = combine(&shown, &rect, OverlayRule::Intersect);
    if let Some(outer) = m.mask() {
        out = combine(
            &out,
            &mask_region(outer, ts, tol, eps),
            OverlayRule::Intersect,
        );
    }
    out
}

/// A filled element cut to the clip paths and masks around it: its simple polygons (an
/// even-odd path, since holes and outer contours no longer overlap), or nothing when no
/// area is left.
pub(crate) fn clip_element(
    path: FilledPath,
    clips: &[ClipRef<'_>],
    tol: f64,
    eps: f64,
) -> Option<FilledPath> {
    let mut region = simple(&path.rings, path.even_odd);
    for c in clips {
        let cut = match *c {
            ClipRef::Path(c, ts) => clip_region(c, ts, tol, eps),
            ClipRef::Mask(m, ts) => mask_region(m, ts, tol, eps),
        };
        region = combine(&region, &cut, OverlayRule::Intersect);
    }
    let rings: Vec<Ring> = region
        .into_iter()
        .map(|c| Ring {
            points: c.into_iter().map(|[x, y]| Point::new(x, y)).collect(),
        })
        .map(|r| clean(&r, eps))
        .filter(|r| r.points.len() >= 3)
        .collect();
    (!rings.is_empty()).then_some(FilledPath {
        rings,
        even_odd: true,
    })
}

/// The connected pieces of the union of filled paths (each filled by its own rule): each
/// piece's contours, its outer contour first and then its holes, as `i_overlay` groups them
/// (pieces that touch at a point may come apart).
pub(crate) fn filled_pieces(paths: &[FilledPath]) -> Vec<Vec<Ring>> {
    let all: Region = paths
        .iter()
        .flat_map(|p| simple(&p.rings, p.even_odd))
        .collect();
    all.simplify_shape(FillRule::NonZero)
        .into_iter()
        .map(|piece| {
            piece
                .into_iter()
                .map(|c| Ring {
                    points: c.into_iter().map(|[x, y]| Point::new(x, y)).collect(),
                })
                .filter(|r| r.points.len() >= 3)
                .collect::<Vec<Ring>>()
        })
        .filter(|rings| !rings.is_empty())
        .collect()
}

/// The union of filled paths, each filled by its own rule: one path (its contours as
/// `i_overlay` returns them, read under the even-odd rule) when there are several, the path
/// itself when there is one. Contours of touching pieces merge, so that seams between them
/// (edges inside the filled area) are gone. `eps`: the sliver width [`clean`] removes.
pub(crate) fn union_paths(paths: Vec<FilledPath>, eps: f64) -> Vec<FilledPath> {
    if paths.len() < 2 {
        return paths;
    }
    // each path made simple by its own rule: contours wound one way round the filled area,
    // the other way round its holes, so that together they wind 1 inside each path and 0
    // outside; the non-zero rule over all of them is then the union
    let all: Region = paths
        .iter()
        .flat_map(|p| simple(&p.rings, p.even_odd))
        .collect();
    let rings: Vec<Ring> = all
        .simplify_shape(FillRule::NonZero)
        .into_iter()
        .flatten()
        .map(|c| Ring {
            points: c.into_iter().map(|[x, y]| Point::new(x, y)).collect(),
        })
        .map(|r| clean(&r, eps))
        .filter(|r| r.points.len() >= 3)
        .collect();
    if rings.is_empty() {
        return Vec::new();
    }
    vec![FilledPath {
        rings,
        even_odd: true,
    }]
}
