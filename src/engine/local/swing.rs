//! What a fold turning upstream does to a folding joint's face downstream (issue 27 item 2,
//! an experiment behind [`Model::swung_faces`](crate::model::Model)): the free body's
//! held-face rule, one way.
//!
//! While joint `i` turns and everything else is rigid, the chain is two free bodies on a pin
//! with no net momentum ([`crate::model`]'s sides): side A (up to `i`) turns at
//! `omega_a(phi) phi'`, side B (after it) at `omega_b(phi) phi'`, and the hinge moves at
//! `h(phi) phi'` (in tile `i`'s frame). A folding joint `j > i` held shut carries the part
//! `P` after it with side B; the torque about its hinge `H_j` that carrying `P` takes is
//! `J_P alpha_B + s_P x a_Hj + J_D omega_B + s_D x v_Hj` (`J`, `s` the second and first
//! mass (drag) moments of `P` about `H_j`, `alpha_B`, `a_Hj`, `v_Hj` side B's angular
//! acceleration and `H_j`'s acceleration and velocity). The face must pass it to `P`, so
//! it adds to the joint's drive with the sign that opens the fold when the swing pulls `P`
//! away from folding (docs/free-body.md, "Starts and ends of folds"). Side B is taken
//! straight from `i` to the chain's end, as the sides of a sequential fold are; `i`'s
//! motion is read from its track (value, rate and acceleration of the Hermite piece).

use kurbo::Vec2;

use crate::engine::local::unit_forces::Inputs;
use crate::model::sides::{FirstMoments, Sides};
use crate::model::Model;
use crate::Octagon;

/// `a x b`.
fn cross(a: Vec2, b: Vec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// `v` turned by `angle`.
fn turned(v: Vec2, angle: f64) -> Vec2 {
    let (s, c) = angle.sin_cos();
    Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// Joint `k`'s hinge in the straight chain's frame (tile `t`'s centre at `(t w, 0)`), m.
fn hinge(model: &Model, k: usize) -> Vec2 {
    let (x, y) = Octagon::new(model.geometry.w).hinge(model.joint_sign(k) >= 0.0);
    Vec2::new((k as f64 * model.geometry.w + x) * 1e-3, y * 1e-3)
}

/// The motion of a turn of joint `k` (sides `sides`) at angle `phi`, rate `dphi` and
/// acceleration `ddphi`, in the frame of the tile before it, with no net momentum.
struct Turn {
    omega_a: f64,
    alpha_a: f64,
    omega_b: f64,
    alpha_b: f64,
    /// The hinge's velocity and acceleration.
    v: Vec2,
    a: Vec2,
}

fn perp(v: Vec2) -> Vec2 {
    Vec2::new(-v.y, v.x)
}

impl Turn {
    fn of(sides: &Sides, phi: f64, dphi: f64, ddphi: f64) -> Turn {
        let (wa, wb, h) = sides.unit_turn(phi, true);
        let d = 1e-6;
        let (wa1, wb1, h1) = sides.unit_turn(phi + d, true);
        let (wa0, wb0, h0) = sides.unit_turn(phi - d, true);
        let (dwa, dwb, dh) = (
            (wa1 - wa0) / (2.0 * d),
            (wb1 - wb0) / (2.0 * d),
            (h1 - h0) / (2.0 * d),
        );
        let omega_a = wa * dphi;
        let v = h * dphi;
        Turn {
            omega_a,
            alpha_a: wa * ddphi + dwa * dphi * dphi,
            omega_b: wb * dphi,
            alpha_b: wb * ddphi + dwb * dphi * dphi,
            v,
            a: dh * dphi * dphi + h * ddphi + perp(v) * omega_a,
        }
    }

    /// The velocity and acceleration of the point `r` from the hinge on side A (`b`: B).
    fn point(&self, r: Vec2, b: bool) -> (Vec2, Vec2) {
        let (w, al) = if b {
            (self.omega_b, self.alpha_b)
        } else {
            (self.omega_a, self.alpha_a)
        };
        (self.v + perp(r) * w, self.a + perp(r) * al - r * (w * w))
    }
}

/// The torque about point `q` (velocity `vq`, acceleration `aq`) of a rigid part turning
/// at `omega`, `alpha` to which `q` is fixed, with first moments `s`, `sd` and second
/// moments `j`, `jd` (mass, drag) about `q`: its inertia's and the water's.
fn carry(
    q: (Vec2, Vec2),
    omega: f64,
    alpha: f64,
    (s, j): (Vec2, f64),
    (sd, jd): (Vec2, f64),
) -> f64 {
    j * alpha + cross(s, q.1) + jd * omega + cross(sd, q.0)
}

/// The torque (N m, towards joint `j`'s fold) that the folds turning upstream and
/// downstream of `j` at `t` make its face (or its turn) pass to the part after it, summed.
pub(crate) fn swing_drive(model: &Model, j: usize, t: f64, inputs: &Inputs) -> f64 {
    let Some(sj) = model.sides.get(j).copied().flatten() else {
        return 0.0;
    };
    let hj = hinge(model, j);
    let mut need = 0.0;
    for (k, sides) in model.sides.iter().enumerate() {
        let Some(sk) = sides else {
            continue;
        };
        if k == j || (k > j && !model.swung_back) {
            continue;
        }
        let track = inputs.joints[k];
        let (Some(from), Some(to)) = (
            inputs.shapes.first_move(track),
            inputs.shapes.last_move(track),
        ) else {
            continue;
        };
        if t <= from || t >= to {
            continue;
        }
        let (psi, dpsi, ddpsi) = inputs.shapes.motion(track, t);
        let c = model.joint_angle(k, 1.0);
        let phi = c * psi.clamp(0.0, 1.0);
        let turn = Turn::of(sk, phi, c * dpsi, c * ddpsi);
        let hk = hinge(model, k);
        let (m, d) = (&sj.mass_first, &sj.drag_first);
        if k < j {
            // the part after j rides on side B of k
            let r = turned(hj - hk, phi);
            let q = turn.point(r, true);
            need += carry(
                q,
                turn.omega_b,
                turn.alpha_b,
                (turned(m.b, phi), m.jb),
                (turned(d.b, phi), d.jb),
            );
        } else {
            // the part after j: Q (j to k, on side A of k, straight) and P (after k, on B)
            let (pm, pd) = (&sk.mass_first, &sk.drag_first);
            let dv = hk - hj;
            let q = turn.point(-dv, false);
            let minus = |f: &FirstMoments, g: &FirstMoments| {
                (
                    f.b - (g.b + dv * g.mb),
                    f.jb - (g.jb + 2.0 * dv.dot(g.b) + g.mb * dv.hypot2()),
                )
            };
            need += carry(q, turn.omega_a, turn.alpha_a, minus(m, pm), minus(d, pd));
            let (sp, sdp) = (turned(pm.b, phi), turned(pd.b, phi));
            let hq = (turn.v, turn.a);
            let force =
                turn.a * pm.mb + perp(sp) * turn.alpha_b - sp * (turn.omega_b * turn.omega_b);
            let drag = turn.v * pd.mb + perp(sdp) * turn.omega_b;
            need += carry(hq, turn.omega_b, turn.alpha_b, (sp, pm.jb), (sdp, pd.jb))
                + cross(dv, force + drag);
        }
    }
    -model.joint_sign(j) * need
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use crate::engine::local::run_local;
    use crate::engine::local::test_support::{inertial_model, words};
    use crate::model::{Dynamics, Model, ModelOptions};
    use crate::reference::{run_reference, ReferenceOptions};
    use crate::timeline::TileDesigns;
    use crate::{Chain, Design};

    fn model(word: &str, s: f64, swung: u8) -> Model {
        let mut m = inertial_model(word, s);
        m.swung_faces = swung > 0;
        m.swung_back = swung > 1;
        m
    }

    /// What a test reads of a run: `(joint, start, end)` of every fold, the outcome and
    /// the last event's time.
    type Run = (Vec<(usize, f64, f64)>, String, f64);

    fn read(
        folds: &[crate::timeline::FoldRecord],
        outcome: &crate::timeline::Outcome,
        events: &[crate::timeline::Event],
    ) -> Run {
        (
            folds.iter().map(|f| (f.joint, f.start, f.end)).collect(),
            format!("{outcome:?}"),
            events.last().map_or(0.0, |e| e.time),
        )
    }

    /// The engine on `word` (`swung`: 0 one joint at a time, 1 swung faces, 2 and the
    /// folds downstream).
    fn engine(word: &str, s: f64, swung: u8) -> Run {
        let run = run_local(&model(word, s, swung), 1e-8, 1, 100_000);
        read(&run.folds, &run.outcome, &run.events)
    }

    /// The coupled reference on `word`.
    fn coupled(word: &str, s: f64) -> Run {
        let ro = ReferenceOptions::default()
            .with_model(ModelOptions::default().with_dynamics(Dynamics::Inertial))
            .with_coupled(true);
        let designs = TileDesigns::global(Design::thesis().with_s(s));
        let run = run_reference(&Chain::parse(word).unwrap(), &designs, &ro).unwrap();
        read(&run.folds, &run.outcome, &run.events)
    }

    /// The outcome's kind, the folded joints and the last event's time.
    type Verdict = (String, Vec<usize>, f64);

    fn verdict(run: Run) -> Verdict {
        let mut folds: Vec<usize> = run.0.iter().map(|f| f.0).collect();
        folds.sort_unstable();
        let kind = run.1.split([' ', '{']).next().unwrap().to_string();
        (kind, folds, run.2)
    }

    #[test]
    #[ignore = "an experiment: every word of 1 to 6 letters, the engine with and without swung faces against the coupled reference"]
    fn swung_faces_on_every_short_word() {
        let letters: usize = std::env::var("SWUNG_LETTERS").map_or(6, |v| v.parse().unwrap());
        for s in [0.3, 0.05] {
            let all = words(letters);
            let mut counts = [[0usize; 3]; 3];
            let mut largest = [
                (0.0f64, String::new()),
                (0.0, String::new()),
                (0.0, String::new()),
            ];
            let mut examples = [Vec::new(), Vec::new(), Vec::new()];
            for w in &all {
                let c = verdict(coupled(w, s));
                for (i, swung) in [0u8, 1, 2].into_iter().enumerate() {
                    let e = verdict(engine(w, s, swung));
                    if (&e.0, &e.1) != (&c.0, &c.1) {
                        counts[i][0] += 1;
                        if examples[i].len() < 12 {
                            examples[i].push(format!("{w}: {e:?} vs {c:?}"));
                        }
                        continue;
                    }
                    let off = (e.2 / c.2 - 1.0).abs();
                    counts[i][1] += usize::from(off > 0.005);
                    counts[i][2] += usize::from(off > 0.01);
                    if off > largest[i].0 {
                        largest[i] = (off, w.clone());
                    }
                }
            }
            for i in 0..3 {
                println!(
                    "s = {s}, {} words, swung {}: verdicts differ {}, off > 0.5% {}, > 1% {}, largest {:.3}% ({})",
                    all.len(), i, counts[i][0], counts[i][1], counts[i][2], 100.0 * largest[i].0, largest[i].1
                );
                for e in &examples[i] {
                    println!("    {e}");
                }
            }
        }
    }

    /// Every fold's start and end within `tol` s of the coupled reference's, the same
    /// joints in the same order.
    fn close(word: &str, swung: u8, tol: f64) {
        let (e, eo, _) = engine(word, 0.3, swung);
        let (c, co, _) = coupled(word, 0.3);
        assert_eq!(e.len(), c.len(), "{word}: {e:?} {c:?}");
        for (a, b) in e.iter().zip(&c) {
            assert_eq!(a.0, b.0, "{word}: {e:?} {c:?}");
            assert!(
                (a.1 - b.1).abs() < tol && (a.2 - b.2).abs() < tol,
                "{word}: {e:?} {c:?}"
            );
        }
        assert_eq!(eo.split(' ').next(), co.split(' ').next(), "{word}");
    }

    #[test]
    fn a_face_swung_shut_opens_when_the_fold_before_it_ends() {
        // the next fold the same way: the free body holds its face shut until the first fold
        // ends; the one-joint engine started it when its pair's static torque turned, and
        // ended the chain 9-26% early (LL 0.3184 s, SLLS 0.5196 s, SLSLS 0.5751 s)
        for w in ["LL", "SLLS", "SLSLS"] {
            close(w, 1, 5e-5);
            close(w, 2, 5e-5);
        }
        // without the swing the engine is the one-joint model of before
        let (e, _, _) = engine("SLLS", 0.3, 0);
        assert!((e[1].1 - 0.22164).abs() < 1e-4, "{e:?}");
    }

    #[test]
    fn a_face_swung_open_starts_its_fold_with_the_swing() {
        // the next fold the other way: the swing pulls its face open 0.02 s after the first
        // fold starts (coupled reference 0.16009 s in SLRS, 0.15999 s in SLSRS), before its
        // magnets' pull would (the one-joint engine: 0.2373 s, 0.2596 s)
        for w in ["SLRS", "SLSRS"] {
            let (e, _, _) = engine(w, 0.3, 1);
            let (c, _, _) = coupled(w, 0.3);
            assert!((e[1].1 - c[1].1).abs() < 1e-4, "{w}: {e:?} {c:?}");
        }
        // with the later fold's reaction on the earlier one the first fold ends with the
        // free body's (SLRS: 0.33190 s; alone, as before, 0.41303 s)
        let (e, _, _) = engine("SLRS", 0.3, 2);
        let (c, _, _) = coupled("SLRS", 0.3);
        assert!((e[0].2 - c[0].2).abs() < 1e-3, "{e:?} {c:?}");
    }

    #[test]
    #[ignore = "an experiment: prints the engine with and without swung faces against the coupled reference"]
    fn swung_faces_against_the_coupled_reference() {
        for w in [
            "SL",
            "LL",
            "SLLS",
            "SLLLS",
            "SLSLS",
            "SLRS",
            "SLSRS",
            "S*2LS*2RS*2",
            "LRL",
            "S*4LLS*4RRS*4",
            "S*8LLS*8RRS*8",
        ] {
            println!("{w}");
            println!("  coupled  {:?}", coupled(w, 0.3));
            println!("  engine   {:?}", engine(w, 0.3, 0));
            println!("  swung    {:?}", engine(w, 0.3, 1));
            println!("  both     {:?}", engine(w, 0.3, 2));
        }
    }
}
