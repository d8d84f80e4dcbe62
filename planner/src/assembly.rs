//! Assembly of a plan: a checked fold word and the frames it was laid in become a [`Plan`]
//! (poses from the exact kinematics, mapped into the drawing, the parts list, the fit).

use foldchain::{BillOfMaterials, FoldWord};
use kurbo::{Affine, Point, Vec2};

use crate::fit::measure;
use crate::frame::stacking_axis_deg;
use crate::plan::{Metrics, Plan, PlanPose};
use crate::rows::Style;
use crate::shape::Shape;

/// What turns a checked fold word into a plan: the frames and the counts.
pub(crate) struct Assembly<'a> {
    /// The shape in the work frame (unit tiles), where the fit is measured.
    pub work: &'a Shape,
    /// The chain's own frame (tile 0 at the origin heading +x, w = 1) to the work frame.
    pub chain_to_work: Affine,
    /// The work frame to SVG user units.
    pub work_to_svg: Affine,
    /// The row direction of the stacking axis (physical frame, radians).
    pub row_angle: f64,
    pub style: Style,
    /// The tile width, SVG user units.
    pub w: f64,
    pub u_turns: usize,
    pub quarter_turns: usize,
    pub cells: usize,
}

/// Rounds to 1e-9 (degrees): headings and axes are multiples of 45 degrees plus the row
/// angle, and rounding keeps 90 from printing as 89.99999999999999. `+ 0.0` turns -0 into 0.
fn round_deg(d: f64) -> f64 {
    (d * 1e9).round() / 1e9 + 0.0
}

impl Assembly<'_> {
    /// True if the exact kinematics of `word` put the tile centres where `centres` (work
    /// frame) says, within 1e-6 tile widths.
    pub(crate) fn agrees(&self, word: &FoldWord, centres: &[Point]) -> bool {
        let exact = word.final_poses();
        exact.len() == centres.len()
            && exact.iter().zip(centres).all(|(p, c)| {
                let (x, y) = p.centre.to_f64(1.0);
                let q = self.chain_to_work * Point::new(x, y);
                (q.x - c.x).abs() < 1e-6 && (q.y - c.y).abs() < 1e-6
            })
    }

    /// The plan: poses from the exact kinematics, mapped into the drawing, and the fit
    /// measured on them.
    pub(crate) fn to_plan(&self, word: &FoldWord, name: &str) -> Plan {
        let mut plan = self.to_plan_unmeasured(word, name);
        self.measure(&mut plan, word);
        plan
    }

    /// Measures the fit of `plan`, made by [`Assembly::to_plan_unmeasured`] from `word`
    /// (the part left empty, noted by [`crate::empty::note_empty`], is kept).
    pub(crate) fn measure(&self, plan: &mut Plan, word: &FoldWord) {
        let work_centres: Vec<Point> = word
            .final_poses()
            .iter()
            .map(|p| {
                let (x, y) = p.centre.to_f64(1.0);
                self.chain_to_work * Point::new(x, y)
            })
            .collect();
        let empty = plan.metrics.largest_empty_tiles;
        plan.metrics = measure(self.work, &work_centres, self.w);
        plan.metrics.largest_empty_tiles = empty;
    }

    /// [`Assembly::to_plan`] without the fit (its metrics are zero but for the areas): the
    /// fit is measured on many sample points, and the cell router checks more plans than it
    /// keeps.
    pub(crate) fn to_plan_unmeasured(&self, word: &FoldWord, name: &str) -> Plan {
        let c2w = self.chain_to_work;
        let c2s = self.work_to_svg * c2w;
        // directions move by the linear part only
        let c2s_linear = c2s.with_translation(Vec2::ZERO);
        let exact = word.final_poses();
        let chain_centres: Vec<Point> = exact
            .iter()
            .map(|p| {
                let (x, y) = p.centre.to_f64(1.0);
                Point::new(x, y)
            })
            .collect();
        let poses: Vec<PlanPose> = exact
            .iter()
            .zip(&chain_centres)
            .map(|(p, &c)| {
                let q = c2s * c;
                let a = p.heading.to_radians();
                let d = c2s_linear * Point::new(a.cos(), a.sin());
                let mut h = d.y.atan2(d.x).to_degrees().rem_euclid(360.0);
                if h >= 360.0 - 1e-9 {
                    h = 0.0;
                }
                PlanPose {
                    x: q.x,
                    y: q.y,
                    heading_deg: round_deg(h),
                }
            })
            .collect();
        let oct_area = 2.0 * (std::f64::consts::SQRT_2 - 1.0);
        let metrics = Metrics {
            covered_share: 0.0,
            outside_share: 0.0,
            shape_area: self.work.area() * self.w * self.w,
            chain_area: exact.len() as f64 * oct_area * self.w * self.w,
            largest_empty_tiles: 0.0,
        };
        let chain = word.to_chain();
        let bom = BillOfMaterials::from_chain(&chain)
            .parts
            .into_iter()
            .map(|(p, n)| (p.to_string(), n))
            .collect();
        let axis = stacking_axis_deg(self.row_angle);
        let axis = if axis >= 180.0 - 1e-9 { 0.0 } else { axis };
        Plan {
            source: name.to_string(),
            tiles: word.tiles(),
            tile_list: chain.to_tile_list(),
            word: word.to_compact_string(),
            axis_deg: round_deg(axis),
            tile_size: self.w,
            mm_per_unit: 0.0,
            tile_mm: 0.0,
            extent_mm: [0.0, 0.0],
            turns: self.style.turns,
            u_turns: self.u_turns,
            quarter_turns: self.quarter_turns,
            cells: self.cells,
            bom,
            metrics,
            chain_to_svg: c2s.as_coeffs(),
            poses,
            warnings: Vec::new(),
        }
    }
}
