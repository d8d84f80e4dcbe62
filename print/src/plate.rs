//! Laying tiles out on print beds: a grid of cells one tile wide, `spacing` apart, centred
//! on the bed, filled part by part (so that a plate holds few kinds and the tiles come off
//! sorted), as many plates as the tiles need.

use crate::options::Bed;
use crate::PrintError;

/// One tile placed on a plate: which part (an index the caller gives) and where its centre
/// goes, mm from the bed's front left corner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// The part's index.
    pub part: usize,
    /// Centre x, mm.
    pub x: f64,
    /// Centre y, mm.
    pub y: f64,
}

/// The grid a bed holds for tiles of footprint `size` x `size` mm: columns and rows.
pub fn grid(bed: &Bed, size: f64, name: &str) -> Result<(usize, usize), PrintError> {
    let pitch = size + bed.spacing;
    // `spacing` between neighbours; the grid is centred, so the margins take what is left
    let fit = |span: f64| ((span + bed.spacing) / pitch + 1e-9).floor().max(0.0) as usize;
    let (cols, rows) = (fit(bed.width), fit(bed.depth));
    if cols == 0 || rows == 0 {
        return Err(PrintError::PartTooLarge {
            part: name.to_string(),
            w: size,
            h: size,
            bed_w: bed.width,
            bed_h: bed.depth,
        });
    }
    Ok((cols, rows))
}

/// The plates: `counts[k]` tiles of part `k`, each `size` mm square, laid out on `bed` in part
/// order, row by row from the front left. Every plate but the last is full.
pub fn lay_out(counts: &[usize], size: f64, bed: &Bed) -> Result<Vec<Vec<Placement>>, PrintError> {
    let (cols, rows) = grid(bed, size, "tile")?;
    let per_plate = cols * rows;
    let pitch = size + bed.spacing;
    // the grid centred on the bed
    let x0 = 0.5 * (bed.width - (cols as f64 * pitch - bed.spacing)) + 0.5 * size;
    let y0 = 0.5 * (bed.depth - (rows as f64 * pitch - bed.spacing)) + 0.5 * size;
    let mut plates: Vec<Vec<Placement>> = Vec::new();
    let mut slot = 0usize;
    for (part, &n) in counts.iter().enumerate() {
        for _ in 0..n {
            if slot.is_multiple_of(per_plate) {
                plates.push(Vec::with_capacity(per_plate));
            }
            let k = slot % per_plate;
            let (c, r) = (k % cols, k / cols);
            if let Some(p) = plates.last_mut() {
                p.push(Placement {
                    part,
                    x: x0 + c as f64 * pitch,
                    y: y0 + (rows - 1 - r) as f64 * pitch,
                });
            }
            slot += 1;
        }
    }
    Ok(plates)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn a_default_bed_holds_42_thesis_tiles_inside_its_edges() {
        let bed = Bed::default();
        assert_eq!(grid(&bed, 30.0, "SS").unwrap(), (7, 6));
        let plates = lay_out(&[50, 3, 40], 30.0, &bed).unwrap();
        assert_eq!(plates.iter().map(Vec::len).collect::<Vec<_>>(), [42, 42, 9]);
        for p in plates.iter().flatten() {
            assert!(p.x - 15.0 >= 0.0 && p.x + 15.0 <= 250.0, "{p:?}");
            assert!(p.y - 15.0 >= 0.0 && p.y + 15.0 <= 210.0, "{p:?}");
        }
        // no two tiles closer than a tile plus the spacing
        for plate in &plates {
            for (i, a) in plate.iter().enumerate() {
                for b in &plate[i + 1..] {
                    let d = (a.x - b.x).abs().max((a.y - b.y).abs());
                    assert!(d >= 35.0 - 1e-9, "{a:?} {b:?}");
                }
            }
        }
        let e = grid(&Bed { width: 20.0, ..bed }, 30.0, "SS").unwrap_err();
        assert!(e.to_string().contains("does not fit"), "{e}");
    }
}
