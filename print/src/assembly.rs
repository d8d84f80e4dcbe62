//! The assembly sheet: the chain at rest, tile by tile in order, in rows read left to right
//! like text, drawn from the printed parts themselves. Each tile shows its index, its type
//! (as its engraved mark reads upright: lay it so), which part it is and whether that part is
//! turned, its channels, and its two magnets at rest with the pole that faces up. The
//! reaction initiator stands before tile 0, on the left; the joints that fold are marked.
//!
//! Poles: magnet `k` (tile `k / 2`, first magnet when `k` is even) has its north pole up when
//! `k` is even, so neighbours always attract; the RI then goes south pole up (it attracts
//! magnet 0, as `foldchain::physics` counts it as magnet -1).

use std::fmt::Write as _;

use foldchain::{PathKind, Tile};

use crate::region::{Contour, Pt};
use crate::TilePart;

/// One tile of the sheet.
#[derive(Clone, Copy, Debug)]
pub struct SheetTile<'a> {
    /// The tile type.
    pub tile: Tile,
    /// The part's label (its file's name).
    pub part_label: &'a str,
    /// The part as built (its canonical tile); the tile is it turned when they differ.
    pub part: &'a TilePart,
}

/// Tiles per row of the sheet.
pub const SHEET_COLUMNS: usize = 10;

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The pole colour and letter of magnet `k`.
fn pole(k: usize) -> (&'static str, &'static str) {
    if k.is_multiple_of(2) {
        ("#2e9e4f", "N")
    } else {
        ("#d23c3c", "S")
    }
}

fn path_d(c: &Contour, f: &dyn Fn(Pt) -> Pt) -> String {
    let mut d = String::new();
    for (i, p) in c.iter().enumerate() {
        let q = f(*p);
        let _ = write!(
            d,
            "{}{:.2},{:.2}",
            if i == 0 { "M" } else { "L" },
            q[0],
            q[1]
        );
    }
    d.push('Z');
    d
}

/// Where the sheet puts its tiles: px per mm of tile and the cells of its grid.
struct Layout {
    /// px per mm (64 px per tile width, whatever the tile's size in mm).
    k: f64,
    cell_w: f64,
    cell_h: f64,
    left: f64,
    top: f64,
}

/// The sheet as an SVG document. `joints[i]` is the fold letter of joint `i` (between tiles
/// `i` and `i + 1`), when the chain has a fold word.
pub fn assembly_svg(title: &str, tiles: &[SheetTile<'_>], joints: Option<&[PathKind]>) -> String {
    let w = tiles
        .iter()
        .map(|t| t.part.design.tile_width)
        .fold(0.0, f64::max)
        .max(1.0);
    let layout = Layout {
        k: 64.0 / w,
        cell_w: 80.0,
        cell_h: 126.0,
        left: 90.0,
        top: 118.0,
    };
    let cols = SHEET_COLUMNS.min(tiles.len().max(1));
    let rows = tiles.len().div_ceil(SHEET_COLUMNS).max(1);
    // wide enough for the instructions above the tiles
    let width = (layout.left + cols as f64 * layout.cell_w + 30.0).max(880.0);
    let height = layout.top + rows as f64 * layout.cell_h + 20.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{height:.0}\" viewBox=\"0 0 {width:.0} {height:.0}\" font-family=\"sans-serif\">"
    );
    s.push_str("<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n");
    let _ = writeln!(
        s,
        "<text x=\"20\" y=\"30\" font-size=\"18\" font-weight=\"bold\">{}</text>",
        esc(title)
    );
    let lines = [
        format!(
            "{} tiles in chain order, read each row left to right. Lay every tile so its type (engraved, and printed under it here) reads upright:",
            tiles.len()
        ),
        "its arrow then points left, to the reaction initiator (RI). Insert each magnet at its rest point with the pole shown up:".to_string(),
        "N up (green) and S up (red) alternate along the chain; the RI goes S up, before tile 0. Orange letters mark the joints that fold (L or R).".to_string(),
    ];
    for (i, l) in lines.iter().enumerate() {
        let _ = writeln!(
            s,
            "<text x=\"20\" y=\"{}\" font-size=\"12\" fill=\"#333\">{}</text>",
            54 + 16 * i,
            esc(l)
        );
    }
    for (i, t) in tiles.iter().enumerate() {
        draw_tile(&mut s, &layout, i, t, tiles.len(), joints);
    }
    s.push_str("</svg>\n");
    s
}

/// Tile `i` of `n` in its cell: outline, channels, magnets, labels, the fold letter of its
/// joint, and the RI before tile 0.
fn draw_tile(
    s: &mut String,
    layout: &Layout,
    i: usize,
    t: &SheetTile<'_>,
    n: usize,
    joints: Option<&[PathKind]>,
) {
    let Layout {
        k,
        cell_w,
        cell_h,
        left,
        top,
    } = *layout;
    let (col, row) = (i % SHEET_COLUMNS, i / SHEET_COLUMNS);
    let cx = left + (col as f64 + 0.5) * cell_w;
    let cy = top + row as f64 * cell_h + 56.0;
    if col == 0 {
        let _ = writeln!(
            s,
            "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"11\" fill=\"#666\">{}-{}</text>",
            left - 70.0,
            cy + 4.0,
            i,
            (i + SHEET_COLUMNS - 1).min(n - 1)
        );
    }
    let turned = t.tile != t.part.tile;
    let (sn, cs) = if turned { (0.0, -1.0) } else { (0.0, 1.0) };
    // tile frame (mm, y up) to the page (px, y down), turned by 180 degrees if need be
    let to_page = move |p: Pt| -> Pt {
        let (x, y) = (cs * p[0] - sn * p[1], sn * p[0] + cs * p[1]);
        [cx + k * x, cy - k * y]
    };
    let fill = match t.part.tile.part() {
        foldchain::Part::SS => "#eef2f7",
        foldchain::Part::RS => "#e8f4e8",
        foldchain::Part::SR => "#f6efe2",
        foldchain::Part::RR => "#f4e6f2",
        _ => "#f2f2e4",
    };
    let _ = writeln!(
        s,
        "<path d=\"{}\" fill=\"{fill}\" stroke=\"#445\" stroke-width=\"1\"/>",
        path_d(&t.part.outline, &to_page)
    );
    for ch in &t.part.channels {
        for c in crate::region::contours(&ch.region) {
            let _ = writeln!(
                s,
                "<path d=\"{}\" fill=\"#ffffff\" stroke=\"#889\" stroke-width=\"0.7\"/>",
                path_d(c, &to_page)
            );
        }
    }
    draw_magnets(s, i, t, turned, k, &to_page);
    let _ = writeln!(
        s,
        "<text x=\"{cx:.1}\" y=\"{:.1}\" font-size=\"11\" text-anchor=\"middle\" fill=\"#555\">#{i}</text>",
        cy - 38.0
    );
    let _ = writeln!(
        s,
        "<text x=\"{cx:.1}\" y=\"{:.1}\" font-size=\"14\" font-weight=\"bold\" text-anchor=\"middle\">{}</text>",
        cy + 50.0,
        t.tile
    );
    let note = if turned {
        format!("part {}, turned", t.part_label)
    } else {
        format!("part {}", t.part_label)
    };
    let _ = writeln!(
        s,
        "<text x=\"{cx:.1}\" y=\"{:.1}\" font-size=\"9\" text-anchor=\"middle\" fill=\"#666\">{}</text>",
        cy + 62.0,
        esc(&note)
    );
    mark_joint(s, layout, i, n, col, (cx, cy), joints);
}

/// Tile `i`'s two magnets at rest, with the pole that faces up.
fn draw_magnets(
    s: &mut String,
    i: usize,
    t: &SheetTile<'_>,
    turned: bool,
    k: f64,
    to_page: &dyn Fn(Pt) -> Pt,
) {
    // magnets at rest: the first path's at -x of the tile as it lies
    for (m, end) in [
        foldchain::magnet_path::PathEnd::First,
        foldchain::magnet_path::PathEnd::Second,
    ]
    .into_iter()
    .enumerate()
    {
        // the tile's first path is the part's second when turned
        let ch = match (end, turned) {
            (foldchain::magnet_path::PathEnd::First, false)
            | (foldchain::magnet_path::PathEnd::Second, true) => &t.part.channels[0],
            _ => &t.part.channels[1],
        };
        let (rx, ry) = ch.path.rest();
        let q = to_page([rx, ry]);
        let (colour, letter) = pole(2 * i + m);
        let r = k * 0.5 * t.part.design.magnet_diameter;
        let _ = writeln!(
            s,
            "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"{:.2}\" fill=\"{colour}\"/><text x=\"{:.2}\" y=\"{:.2}\" font-size=\"7\" text-anchor=\"middle\" fill=\"#fff\" font-weight=\"bold\">{letter}</text>",
            q[0],
            q[1],
            r.max(4.0),
            q[0],
            q[1] + 2.5
        );
    }
}

/// The fold letter of joint `i` beside tile `i` (centred at `(cx, cy)`, in column `col`) when
/// it folds, and the RI before tile 0.
fn mark_joint(
    s: &mut String,
    layout: &Layout,
    i: usize,
    n: usize,
    col: usize,
    (cx, cy): (f64, f64),
    joints: Option<&[PathKind]>,
) {
    let (cell_w, left) = (layout.cell_w, layout.left);
    if let Some(letter) = joints.and_then(|j| j.get(i)) {
        if *letter != PathKind::S && col + 1 < SHEET_COLUMNS && i + 1 < n {
            let _ = writeln!(
                s,
                "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"13\" font-weight=\"bold\" text-anchor=\"middle\" fill=\"#e07800\">{letter}</text>",
                cx + 0.5 * cell_w,
                cy - 36.0
            );
        } else if *letter != PathKind::S {
            let _ = writeln!(
                s,
                "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"13\" font-weight=\"bold\" text-anchor=\"start\" fill=\"#e07800\">{letter}</text>",
                cx + 0.5 * cell_w - 6.0,
                cy + 4.0
            );
        }
    }
    if i == 0 {
        let _ = writeln!(
            s,
            "<circle cx=\"{:.1}\" cy=\"{cy:.1}\" r=\"10\" fill=\"#d23c3c\" stroke=\"#600\" stroke-width=\"1\"/><text x=\"{:.1}\" y=\"{:.1}\" font-size=\"8\" text-anchor=\"middle\" fill=\"#fff\" font-weight=\"bold\">RI S</text>",
            left - 14.0,
            left - 14.0,
            cy + 3.0
        );
    }
}
